//! The ways from the drawn pose to each input value of a sweep, which make a value's pose
//! independent of the rest of the array (DESIGN, "Scenes"): the direct way (the input moved
//! from its drawn value straight to t, up or down), and for an angle the other way round
//! (to the same angle the opposite way, less than a turn). The values are visited in order
//! of their distance from the drawn value along each way, so one continuation per way and
//! direction serves them all, whatever the order of the array.

use std::f64::consts::TAU;

/// One continuation from the drawn value: the indices it visits with the input value it
/// solves each at, in the order it reaches them.
pub(super) type Run = Vec<(usize, f64)>;

/// The direct ways of the finite values of `theta` from `theta0`: the values above it in
/// increasing order, those below in decreasing order.
pub(super) fn direct(theta: &[f64], theta0: f64) -> [Run; 2] {
    let mut up: Run = Vec::new();
    let mut down: Run = Vec::new();
    for (k, &t) in theta.iter().enumerate() {
        if !t.is_finite() {
            continue;
        }
        if t >= theta0 {
            up.push((k, t));
        } else {
            down.push((k, t));
        }
    }
    // a stable sort keeps repeated values in array order (their answers are equal anyway)
    up.sort_by(|a, b| a.1.total_cmp(&b.1));
    down.sort_by(|a, b| b.1.total_cmp(&a.1));
    [up, down]
}

/// The other way round to the angles `theta[k]` for the indices `ks`: the same angle less
/// than a turn the opposite way from `theta0` (no way at all for a whole number of turns:
/// the drawn angle), as runs up and down (see [`direct`]).
pub(super) fn other(theta: &[f64], theta0: f64, ks: impl Iterator<Item = usize>) -> [Run; 2] {
    let mut up: Run = Vec::new();
    let mut down: Run = Vec::new();
    for k in ks {
        let d = theta[k] - theta0;
        if d >= 0.0 {
            // reached going down by less than a turn (a whole number of turns up is the
            // drawn angle itself: no way at all)
            let back = d.rem_euclid(TAU);
            down.push((k, if back > 0.0 { theta0 + back - TAU } else { theta0 }));
        } else {
            let ahead = (-d).rem_euclid(TAU);
            up.push((k, if ahead > 0.0 { theta0 + TAU - ahead } else { theta0 }));
        }
    }
    up.sort_by(|a, b| a.1.total_cmp(&b.1));
    down.sort_by(|a, b| b.1.total_cmp(&a.1));
    [up, down]
}

/// True when the continuation along every direct way moves in steps of at most `max_step`
/// (from the drawn value, through the values in the order [`direct`] visits them), or, for
/// an angle, when the values cover the whole turn that way (taken modulo a turn, the gaps
/// between neighbours at most `max_step`): then a column sweep whose every step is far from
/// a dead point is the motion reached either way, and the values' order does not matter.
/// No sort: vectorized passes over the usual arrays ([`covered_in_order`]), buckets for
/// shuffled ones, and one general walk ([`steps_within`]) for the rest (values on both
/// sides of the drawn one, NaN): a sweep from any start, or shuffled, costs about what one
/// from the drawn value does.
pub(super) fn covered(theta: &[f64], theta0: f64, max_step: f64, linear: bool) -> bool {
    if let Some(answer) = covered_in_order(theta, theta0, max_step, linear) {
        return answer;
    }
    let finite = || theta.iter().copied().filter(|t| t.is_finite());
    // both direct ways walked in one pass; where their offsets come in increasing order
    // (a sweep from the drawn value, either way) that pass answers
    let (mut up, mut down) = (Walk::new(max_step, None), Walk::new(max_step, None));
    for t in finite() {
        if t >= theta0 {
            up.visit(t - theta0);
        } else {
            down.visit(theta0 - t);
        }
    }
    let direct = up.covers(|| finite().filter(|&t| t >= theta0).map(|t| t - theta0))
        && down.covers(|| finite().filter(|&t| t < theta0).map(|t| theta0 - t));
    // (the turn's ends: a value a whole number of turns away is the drawn one, at 0)
    direct || (!linear && steps_within(|| finite().map(|t| turned(t - theta0)), max_step, Some(TAU)))
}

/// [`covered`]'s answer where every value is finite and on one side of the drawn value (and,
/// for the turn, within two turns of it), in branch-free passes that vectorize where the
/// values are in increasing or decreasing order, or in two increasing runs modulo the turn
/// (a full turn from any start), and the buckets otherwise (shuffled); None: the general
/// walk answers.
fn covered_in_order(theta: &[f64], theta0: f64, max_step: f64, linear: bool) -> Option<bool> {
    covered_in_order_kernel(theta, theta0, max_step, linear)
}

crate::simd::avx2_kernel! {
    /// [`covered_in_order_body`], 4 lanes wide where the CPU has AVX2 (comparisons, sums
    /// and masks only: the same answer on every path).
    fn covered_in_order_kernel(theta: &[f64], theta0: f64, max_step: f64, linear: bool) -> Option<bool> = covered_in_order_body;
}

#[inline(always)]
fn covered_in_order_body<const AVX: bool>(theta: &[f64], theta0: f64, max_step: f64, linear: bool) -> Option<bool> {
    // (loops that count, two counts at most: they vectorize, where min and max do not)
    let (mut below, mut nonfinite) = (0usize, 0usize);
    for &t in theta {
        below += (t < theta0) as usize;
        nonfinite += !t.is_finite() as usize;
    }
    let n = theta.len();
    if nonfinite > 0 || n == 0 {
        return None;
    }
    let (above, below) = (below == 0, below == n);
    if !(above || below) {
        return None;
    }
    if linear {
        return Some(direct_way(theta, theta0, above, max_step));
    }
    // covered either way: with neither end at the drawn value (a full turn from elsewhere)
    // the turn is asked first, else the direct way (the order changes no answer)
    let offset = |t: f64| if above { t - theta0 } else { theta0 - t };
    if offset(theta[0]) > max_step && offset(theta[n - 1]) > max_step {
        match turn_way(theta, theta0, max_step) {
            Some(true) => Some(true),
            turned => {
                if direct_way(theta, theta0, above, max_step) {
                    Some(true)
                } else {
                    turned
                }
            }
        }
    } else if direct_way(theta, theta0, above, max_step) {
        Some(true)
    } else {
        turn_way(theta, theta0, max_step)
    }
}

// (functions, not closures, so that they are compiled into the kernel, with its features)

/// The direct way over finite values all above (or all below) `theta0`.
#[inline(always)]
fn direct_way(theta: &[f64], theta0: f64, above: bool, max_step: f64) -> bool {
    // (each way its own closure: a select between them would keep the loops scalar)
    if above {
        Walk::check(theta, |t| t - theta0, max_step, None)
    } else {
        Walk::check(theta, |t| theta0 - t, max_step, None)
    }
}

/// The way modulo the turn over finite values, where all lie within two turns of `theta0`
/// (None: some do not).
#[inline(always)]
fn turn_way(theta: &[f64], theta0: f64, max_step: f64) -> Option<bool> {
    let mut far = 0usize;
    for &t in theta {
        let x = t - theta0;
        far += !(x > -TAU && x < 2.0 * TAU) as usize;
    }
    if far > 0 {
        return None;
    }
    Some(Walk::check(theta, |t| turned_near(t - theta0), max_step, Some(TAU)))
}

/// One pass over nonnegative offsets from 0: whether they came in increasing order, or in
/// two increasing runs (a full turn asked for from some other angle, taken modulo the
/// turn, rises to the turn's end and again from 0), the steps within each run at most
/// `max_step`, and their count and range.
struct Walk {
    max_step: f64,
    end: Option<f64>,
    at: f64,
    /// The first offset, and the last before the one descent and the first after it.
    first: f64,
    top: f64,
    bottom: f64,
    descents: usize,
    ok: bool,
    n: usize,
    lo: f64,
    hi: f64,
}

impl Walk {
    fn new(max_step: f64, end: Option<f64>) -> Self {
        let (lo, hi) = (end.unwrap_or(f64::INFINITY), end.unwrap_or(0.0));
        let (first, top, bottom) = (0.0, 0.0, 0.0);
        Walk { max_step, end, at: 0.0, first, top, bottom, descents: 0, ok: true, n: 0, lo, hi }
    }

    #[inline]
    fn visit(&mut self, x: f64) {
        // (selects, not branches: the loop stays tight)
        let down = x < self.at;
        let start = self.n == 0;
        self.descents += (down && !start) as usize;
        self.top = if down { self.at } else { self.top };
        self.bottom = if down { x } else { self.bottom };
        self.first = if start { x } else { self.first };
        self.ok &= down | start | (x - self.at <= self.max_step);
        self.at = x;
        self.n += 1;
        // (finite offsets: plain comparisons)
        if x < self.lo {
            self.lo = x;
        }
        if x > self.hi {
            self.hi = x;
        }
    }

    /// Whether the offsets `f(t)` of every value of `theta` step by at most a step in
    /// increasing order: [`Walk::in_order`], or the buckets where it cannot tell.
    #[inline(always)]
    fn check(theta: &[f64], f: impl Fn(f64) -> f64 + Copy, max_step: f64, end: Option<f64>) -> bool {
        match Walk::in_order(theta, f, max_step, end) {
            Ok(answer) => answer,
            Err((lo, hi)) => buckets(|| theta.iter().map(|&t| f(t)), theta.len(), (lo, hi), max_step, end),
        }
    }

    /// [`Walk::answer`] for the offsets `f(t)` of every value of `theta` (at least one),
    /// visited in the array's order or, where they decrease throughout, the reverse order,
    /// from pairs of neighbours in one pass with no branch (it vectorizes); where it has
    /// none, their range (with `end`), for the buckets.
    #[inline(always)]
    fn in_order(theta: &[f64], f: impl Fn(f64) -> f64, max_step: f64, end: Option<f64>) -> Result<bool, (f64, f64)> {
        let (n, step) = (theta.len(), max_step);
        let pairs = || theta.iter().zip(&theta[1..]).map(|(&a, &b)| (f(a), f(b)));
        let (first, last) = (f(theta[0]), f(theta[n - 1]));
        // (counts, not flags, and the descent's pair by the bits of its values, or-ed: the
        // loop vectorizes; with one descent they are its values)
        let (mut descents, mut ascents, mut long) = (0usize, 0usize, 0usize);
        let (mut top, mut bottom) = (0u64, 0u64);
        for (a, b) in pairs() {
            let (down, up) = (b < a, b > a);
            descents += down as usize;
            ascents += up as usize;
            long += (!down & (b - a > step)) as usize;
            let mask = 0u64.wrapping_sub(down as u64);
            top |= a.to_bits() & mask;
            bottom |= b.to_bits() & mask;
        }
        let mut w = Walk::new(max_step, end);
        w.n = n;
        if descents <= 1 {
            (w.first, w.at, w.ok, w.descents) = (first, last, long == 0, descents);
            (w.top, w.bottom) = (f64::from_bits(top), f64::from_bits(bottom));
        } else if ascents == 0 {
            // decreasing throughout: the steps the other way
            let long = pairs().map(|(a, b)| (a - b > step) as usize).sum::<usize>();
            (w.first, w.at, w.ok) = (last, first, long == 0);
        } else {
            w.descents = descents;
        }
        if let Some(answer) = w.answer() {
            return Ok(answer);
        }
        // the range, for the buckets: by the bits, which order nonnegative offsets as their
        // values (a loop that vectorizes)
        let (mut lo, mut hi) = (i64::MAX, 0i64);
        for &t in theta {
            let x = f(t).to_bits() as i64;
            lo = lo.min(x);
            hi = hi.max(x);
        }
        let (lo, hi) = (f64::from_bits(lo as u64), f64::from_bits(hi as u64));
        Err(end.map_or((lo, hi), |e| (lo.min(e), hi.max(e))))
    }

    /// The answer where the offsets came in increasing order, or in two increasing runs
    /// that each step by at most a step (None: otherwise). Two such runs cover from the
    /// lower of their firsts to the higher of their lasts in such steps where they overlap
    /// or lie at most a step apart (a value between two of one run's neighbours only
    /// shortens their gap); then the steps from 0 and on to `end` remain. (A run with a
    /// longer step may still be covered by the other's values: that needs the buckets.)
    fn answer(&self) -> Option<bool> {
        let step = self.max_step;
        let from_zero = |x: f64| self.n == 0 || x <= step;
        let to_end = |last: f64| self.end.is_none_or(|e| e - last <= step);
        match self.descents {
            0 => Some(self.ok && from_zero(self.first) && to_end(self.at)),
            // runs [first, top] and [bottom, at], top > bottom
            1 if self.ok => Some(
                from_zero(self.first.min(self.bottom)) && self.first - self.at <= step && to_end(self.top.max(self.at)),
            ),
            _ => None,
        }
    }
}

/// `x.rem_euclid(TAU)`, with no fmod for an offset within a turn down or two turns up
/// ([`turned_near`]).
#[inline]
fn turned(x: f64) -> f64 {
    if x > -TAU && x < 2.0 * TAU {
        turned_near(x)
    } else {
        x.rem_euclid(TAU)
    }
}

/// `x.rem_euclid(TAU)` for `-TAU < x < 2 TAU`: within the turn `x`; in the second turn
/// `x - TAU`, exact (Sterbenz: `TAU <= x <= 2 TAU`) as fmod's answer is; below 0,
/// `x + TAU`, the sum `rem_euclid` rounds (`x % TAU` is `x` there). Written as
/// `(x - a) + b` with `a` and `b` each `TAU` or 0 by a mask (adding or taking 0 changes
/// nothing), so a loop of it vectorizes.
#[inline(always)]
fn turned_near(x: f64) -> f64 {
    let turn = |on: bool| f64::from_bits(TAU.to_bits() & 0u64.wrapping_sub(on as u64));
    (x - turn(x >= TAU)) + turn(x < 0.0)
}

/// Whether the nonnegative offsets `xs()` (in any order), visited in increasing order from
/// 0 and then on to `end` (if given), step by at most `max_step` ([`Walk::covers`]).
fn steps_within<I: Iterator<Item = f64>>(xs: impl Fn() -> I, max_step: f64, end: Option<f64>) -> bool {
    let mut walk = Walk::new(max_step, end);
    for x in xs() {
        walk.visit(x);
    }
    walk.covers(xs)
}

impl Walk {
    /// Whether the offsets this walk visited, `xs()` again, step by at most a step in
    /// increasing order: the walk's answer where they came in order (or in two runs);
    /// otherwise the buckets'.
    fn covers<I: Iterator<Item = f64>>(&self, xs: impl Fn() -> I) -> bool {
        self.answer().unwrap_or_else(|| buckets(xs, self.n, (self.lo, self.hi), self.max_step, self.end))
    }
}

/// Whether the `n` nonnegative offsets `xs()` (in any order; their range `lo..=hi`, with
/// `end` where given), visited in increasing order from 0 and on to `end`, step by at most
/// `max_step`: exact and in linear time, the offsets in buckets half a step wide, where
/// neighbours in one bucket are closer than a step, so only the gaps between the last of a
/// bucket and the first of the next one that holds any need checking. More than a step
/// per offset is never covered.
#[inline(always)]
fn buckets<I: Iterator<Item = f64>>(
    xs: impl Fn() -> I,
    n: usize,
    (lo, hi): (f64, f64),
    max_step: f64,
    end: Option<f64>,
) -> bool {
    // (the first step, and enough offsets to span the rest)
    if !(lo <= max_step && hi <= (n + 1) as f64 * max_step) {
        return false;
    }
    // (by a product: a bucket's width is within rounding of half a step, well below one)
    let per = 2.0 / max_step;
    let count = (hi * per) as usize + 1;
    // (each bucket's least and greatest offset in two arrays, written whole: no masked
    // store, whose value a following load of the same bucket cannot be forwarded)
    let (mut least, mut most) = (vec![f64::INFINITY; count], vec![f64::NEG_INFINITY; count]);
    for x in xs() {
        let b = ((x * per) as usize).min(count - 1);
        let (lo, hi) = (least[b], most[b]);
        least[b] = if x < lo { x } else { lo };
        most[b] = if x > hi { x } else { hi };
    }
    let mut at = 0.0;
    for (&lo, &top) in least.iter().zip(&most).filter(|(lo, top)| lo <= top) {
        if lo - at > max_step {
            return false;
        }
        at = top;
    }
    end.is_none_or(|e| e - at <= max_step)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn direct_ways_sort_each_side_away_from_the_drawn_value() {
        let theta = [0.3, -0.1, 0.1, f64::NAN, -0.4, 0.2];
        let [up, down] = direct(&theta, 0.0);
        assert_eq!(up, vec![(2, 0.1), (5, 0.2), (0, 0.3)]);
        assert_eq!(down, vec![(1, -0.1), (4, -0.4)]);
    }

    #[test]
    fn the_other_way_reaches_the_same_angle_the_opposite_way() {
        let theta = [0.0 + 3.0, -1.0, 7.0];
        let [up, down] = other(&theta, 0.0, 0..3);
        assert_eq!(up.len(), 1);
        assert_eq!(up[0].0, 1);
        assert!((up[0].1 - (TAU - 1.0)).abs() < 1e-15);
        // 3 rad up is 2pi - 3 down; 7 rad up (a turn and a bit) is 2pi - (7 - 2pi) down
        assert_eq!(down.iter().map(|r| r.0).collect::<Vec<_>>(), vec![0, 2]);
        assert!((down[0].1 - (3.0 - TAU)).abs() < 1e-15);
        assert!((down[1].1 - ((7.0 - TAU) - TAU)).abs() < 1e-15);
    }

    #[test]
    fn turned_is_rem_euclid_bit_for_bit() {
        let mut x = -3.0 * TAU;
        while x < 4.0 * TAU {
            assert_eq!(turned(x).to_bits(), x.rem_euclid(TAU).to_bits(), "{x}");
            x += 0.0137;
        }
        for x in [TAU, 2.0 * TAU, f64::from_bits(TAU.to_bits() - 1), f64::from_bits((2.0 * TAU).to_bits() - 1)] {
            assert_eq!(turned(x).to_bits(), x.rem_euclid(TAU).to_bits(), "{x}");
        }
    }

    #[test]
    fn a_shifted_full_turn_is_covered_modulo_the_turn() {
        let n = 361;
        let step = TAU / (n - 1) as f64;
        let shifted: Vec<f64> = (0..n).map(|k| 0.5 + k as f64 * step).collect();
        assert!(!covered(&shifted, 0.0, 1.5 * step, true));
        assert!(covered(&shifted, 0.0, 1.5 * step, false));
        let half: Vec<f64> = (0..n / 2).map(|k| 0.5 + k as f64 * step).collect();
        assert!(!covered(&half, 0.0, 1.5 * step, false));
    }

    /// The one pass answers as sorting and walking the gaps does, on shuffled, rotated and
    /// reversed values with gaps on either side of the step, repeats, values a turn or more
    /// away, and NaN.
    #[test]
    fn coverage_in_one_pass_agrees_with_sorting() {
        let sorted_check = |theta: &[f64], theta0: f64, max_step: f64, linear: bool| {
            let walk = |mut xs: Vec<f64>, end: Option<f64>| {
                xs.sort_by(f64::total_cmp);
                let mut at = 0.0;
                xs.iter().chain(end.as_ref()).all(|&x| {
                    let ok = x - at <= max_step;
                    at = x;
                    ok
                })
            };
            let fin: Vec<f64> = theta.iter().copied().filter(|t| t.is_finite()).collect();
            let up = fin.iter().filter(|&&t| t >= theta0).map(|t| t - theta0).collect();
            let down = fin.iter().filter(|&&t| t < theta0).map(|t| theta0 - t).collect();
            (walk(up, None) && walk(down, None))
                || (!linear && walk(fin.iter().map(|t| (t - theta0).rem_euclid(TAU)).collect(), Some(TAU)))
        };
        let mut state = 0x2545f4914f6cdd1d_u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut agreed = [0usize; 2];
        for case in 0..4000 {
            let n = 2 + (next() * 60.0) as usize;
            let max_step = TAU / (n - 1) as f64 * (0.9 + 0.6 * next());
            let theta0 = next() * 4.0 - 2.0;
            let start = theta0 + (next() - 0.5) * 20.0;
            let mut theta: Vec<f64> =
                (0..n).map(|k| start + k as f64 * TAU / (n - 1) as f64 * (0.9 + 0.2 * next())).collect();
            if case % 7 == 0 {
                theta[n / 2] = f64::NAN;
            }
            if case % 5 == 0 {
                theta.push(theta[0] + 3.0 * TAU);
            }
            match case % 4 {
                // in order, from some other value: a rotated run modulo the turn
                1 => {
                    let by = (next() * theta.len() as f64) as usize;
                    theta.sort_by(f64::total_cmp);
                    theta.rotate_left(by);
                }
                // reversed
                2 => theta.sort_by(|a, b| b.total_cmp(a)),
                _ => {
                    for k in (1..theta.len()).rev() {
                        theta.swap(k, (next() * (k + 1) as f64) as usize);
                    }
                }
            }
            let linear = case % 3 == 0;
            let want = sorted_check(&theta, theta0, max_step, linear);
            assert_eq!(covered(&theta, theta0, max_step, linear), want, "case {case}");
            agreed[want as usize] += 1;
        }
        // both answers were exercised
        assert!(agreed[0] > 100 && agreed[1] > 100, "{agreed:?}");
    }
}
