//! Grashof condition and Barker's classification (Norton, Design of Machinery, Table 2-4).
//! S + L versus P + Q is decided exactly on the float inputs: both sums are formed with
//! an error-free two-sum, so no tolerance is involved and 0.1 + 0.4 = 0.2 + 0.3 holds
//! only if it holds for the exact binary values.

/// Grashof condition.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum GrashofClass {
    /// S + L < P + Q: at least one link turns fully relative to the others.
    Grashof,
    /// S + L = P + Q: the linkage can reach a change point where the modes meet.
    ChangePoint,
    /// S + L > P + Q: no link turns fully (triple rocker).
    NonGrashof,
}

impl GrashofClass {
    /// The condition's name as every binding spells it (Python's `Grashof.condition`, the
    /// page's JSON): `"grashof"`, `"change-point"` or `"non-grashof"`.
    pub fn name(self) -> &'static str {
        match self {
            GrashofClass::Grashof => "grashof",
            GrashofClass::ChangePoint => "change-point",
            GrashofClass::NonGrashof => "non-grashof",
        }
    }
}

/// Barker's fourteen classes. Links: 1 ground, 2 input (crank), 3 coupler, 4 output.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Barker {
    /// Grashof, shortest = input: crank-rocker.
    Gcrr,
    /// Grashof, shortest = coupler: double-rocker.
    Grcr,
    /// Grashof, shortest = ground: double-crank.
    Gccc,
    /// Grashof, shortest = output: rocker-crank.
    Grrc,
    /// Non-Grashof, longest = ground.
    Rrr1,
    /// Non-Grashof, longest = input.
    Rrr2,
    /// Non-Grashof, longest = coupler.
    Rrr3,
    /// Non-Grashof, longest = output.
    Rrr4,
    /// Change point, shortest = ground.
    Sccc,
    /// Change point, shortest = input.
    Scrr,
    /// Change point, shortest = coupler.
    Srcr,
    /// Change point, shortest = output.
    Srrc,
    /// Change point with two equal pairs (parallelogram or kite).
    S2x,
    /// Change point with all four links equal.
    S3x,
}

impl Barker {
    /// Norton's code, e.g. "GCRR".
    pub fn code(self) -> &'static str {
        use Barker::*;
        match self {
            Gcrr => "GCRR",
            Grcr => "GRCR",
            Gccc => "GCCC",
            Grrc => "GRRC",
            Rrr1 => "RRR1",
            Rrr2 => "RRR2",
            Rrr3 => "RRR3",
            Rrr4 => "RRR4",
            Sccc => "SCCC",
            Scrr => "SCRR",
            Srcr => "SRCR",
            Srrc => "SRRC",
            S2x => "S2X",
            S3x => "S3X",
        }
    }

    /// The basic type: crank-rocker, double-crank, rocker-crank, double-rocker,
    /// change-point or triple-rocker.
    pub fn kind(self) -> &'static str {
        use Barker::*;
        match self {
            Gcrr => "crank-rocker",
            Gccc => "double-crank",
            Grrc => "rocker-crank",
            Grcr => "double-rocker",
            Rrr1 | Rrr2 | Rrr3 | Rrr4 => "triple-rocker",
            Sccc | Scrr | Srcr | Srrc | S2x | S3x => "change-point",
        }
    }

    /// Words for the class, as in Norton's table.
    pub fn description(self) -> &'static str {
        use Barker::*;
        match self {
            Gcrr => "Grashof crank-rocker-rocker (shortest link is the input)",
            Grcr => "Grashof rocker-crank-rocker (shortest link is the coupler)",
            Gccc => "Grashof crank-crank-crank (shortest link is the ground)",
            Grrc => "Grashof rocker-rocker-crank (shortest link is the output)",
            Rrr1 => "non-Grashof triple rocker, class 1 (longest link is the ground)",
            Rrr2 => "non-Grashof triple rocker, class 2 (longest link is the input)",
            Rrr3 => "non-Grashof triple rocker, class 3 (longest link is the coupler)",
            Rrr4 => "non-Grashof triple rocker, class 4 (longest link is the output)",
            Sccc => "change-point crank-crank-crank (shortest link is the ground)",
            Scrr => "change-point crank-rocker-rocker (shortest link is the input)",
            Srcr => "change-point rocker-crank-rocker (shortest link is the coupler)",
            Srrc => "change-point rocker-rocker-crank (shortest link is the output)",
            S2x => "change point with two equal pairs (parallelogram or kite)",
            S3x => "change point with all four links equal",
        }
    }
}

/// The classification of one linkage.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grashof {
    /// Grashof condition.
    pub class: GrashofClass,
    /// Barker class.
    pub barker: Barker,
    /// Shortest length.
    pub s: f64,
    /// Longest length.
    pub l: f64,
    /// The smaller of the two others.
    pub p: f64,
    /// The larger of the two others.
    pub q: f64,
}

/// a + b as (sum, error) with sum + error == a + b exactly (Knuth's two-sum).
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// Whether a + b == c + d exactly on the binary values (no rounding, no tolerance).
pub(crate) fn sums_equal(a: f64, b: f64, c: f64, d: f64) -> bool {
    let (x, ex) = two_sum(a, b);
    let (y, ey) = two_sum(c, d);
    x == y && ex == ey
}

/// Classifies lengths [r1 ground, r2 input, r3 coupler, r4 output] (validated, > 0).
pub fn classify(r: [f64; 4]) -> Grashof {
    let mut sorted = r;
    sorted.sort_by(f64::total_cmp);
    let [s, p, q, l] = sorted;
    let (a, ea) = two_sum(s, l);
    let (b, eb) = two_sum(p, q);
    // Rounding is monotone, so unequal rounded sums order the exact sums; equal rounded
    // sums leave the exact difference in the error terms.
    let ord = a.partial_cmp(&b).unwrap().then(ea.partial_cmp(&eb).unwrap());
    let shortest = (0..4).min_by(|&i, &j| r[i].total_cmp(&r[j])).unwrap();
    let longest = (0..4).max_by(|&i, &j| r[i].total_cmp(&r[j]).then(j.cmp(&i))).unwrap();
    use std::cmp::Ordering::*;
    let (class, barker) = match ord {
        Less => (GrashofClass::Grashof, [Barker::Gccc, Barker::Gcrr, Barker::Grcr, Barker::Grrc][shortest]),
        Greater => (GrashofClass::NonGrashof, [Barker::Rrr1, Barker::Rrr2, Barker::Rrr3, Barker::Rrr4][longest]),
        Equal => {
            let barker = if s == l {
                Barker::S3x
            } else if s == p {
                Barker::S2x // s = p forces q = l: two equal pairs
            } else {
                [Barker::Sccc, Barker::Scrr, Barker::Srcr, Barker::Srrc][shortest]
            };
            (GrashofClass::ChangePoint, barker)
        }
    };
    Grashof { class, barker, s, l, p, q }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed_is_a_crank_rocker() {
        let g = classify([6.0, 2.0, 5.0, 5.0]);
        assert_eq!((g.class, g.barker, g.barker.kind()), (GrashofClass::Grashof, Barker::Gcrr, "crank-rocker"));
        assert_eq!([g.s, g.l, g.p, g.q], [2.0, 6.0, 5.0, 5.0]);
    }

    #[test]
    fn each_shortest_and_longest_link_gives_its_class() {
        // Grashof: a = 2 shortest, 7 longest, 5 and 6 the others (2 + 7 < 11)
        for (i, want) in [Barker::Gccc, Barker::Gcrr, Barker::Grcr, Barker::Grrc].into_iter().enumerate() {
            let mut r = [5.0, 6.0, 7.0, 5.5];
            r[i] = 2.0;
            r[(i + 1) % 4] = 7.0;
            r[(i + 2) % 4] = 5.0;
            r[(i + 3) % 4] = 6.0;
            assert_eq!(classify(r).barker, want, "{r:?}");
        }
        // non-Grashof: 9 longest with 2, 3, 4 (2 + 9 > 7)
        for (i, want) in [Barker::Rrr1, Barker::Rrr2, Barker::Rrr3, Barker::Rrr4].into_iter().enumerate() {
            let mut r = [2.0, 3.0, 4.0, 4.0];
            r[i] = 9.0;
            assert_eq!(classify(r).barker, want);
        }
        // change point: 2 + 6 = 3 + 5
        for (i, want) in [Barker::Sccc, Barker::Scrr, Barker::Srcr, Barker::Srrc].into_iter().enumerate() {
            let mut r = [6.0, 5.0, 3.0, 3.0];
            r[i] = 2.0;
            r[(i + 1) % 4] = 6.0;
            r[(i + 2) % 4] = 3.0;
            r[(i + 3) % 4] = 5.0;
            assert_eq!(classify(r).barker, want, "{r:?}");
        }
        assert_eq!(classify([6.0, 2.0, 6.0, 2.0]).barker, Barker::S2x);
        assert_eq!(classify([2.0, 2.0, 6.0, 6.0]).barker, Barker::S2x);
        assert_eq!(classify([3.0, 3.0, 3.0, 3.0]).barker, Barker::S3x);
    }

    #[test]
    fn equality_is_exact_on_the_binary_values() {
        // 0.1 + 0.4 and 0.2 + 0.3 both round to 0.5, but the exact binary sums differ
        // (0.1 + 0.4 is below 0.5 by 2^-56 - ..., 0.2 + 0.3 above): no tolerance hides it.
        let g = classify([0.1, 0.4, 0.3, 0.2]);
        assert_ne!(g.class, GrashofClass::ChangePoint);
        // sums that are exactly equal in binary are a change point
        assert_eq!(classify([0.5, 0.25, 0.375, 0.375]).class, GrashofClass::ChangePoint);
    }
}
