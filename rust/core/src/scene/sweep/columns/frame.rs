//! The columns of one block of input values and the small helpers the block operations
//! share: disjoint column views, the first failure of a value, a solve's status.

use crate::scene::vec2::Xy;
use crate::Status;

/// Angles per block: the columns of a block stay in cache.
pub(super) const B: usize = 128;

pub(super) const OK: i8 = 0;

/// Columns of one block: point p's values for the block's angles are `[p * B .. p * B + m]`.
pub(super) struct Columns<'a> {
    pub(super) x: &'a mut [f64],
    pub(super) y: &'a mut [f64],
    pub(super) vx: &'a mut [f64],
    pub(super) vy: &'a mut [f64],
    /// Second derivatives by the input angle (empty unless accelerations are asked for).
    pub(super) ax: &'a mut [f64],
    pub(super) ay: &'a mut [f64],
    pub(super) st: &'a mut [i8],
}

impl<'a> Columns<'a> {
    /// The columns cut from one buffer `reals` (positions of `len` values each, then rates
    /// of `nv` each) and the statuses `st`.
    pub(super) fn carve(reals: &'a mut [f64], st: &'a mut [i8], len: usize, nv: usize) -> Self {
        let (x, rest) = reals.split_at_mut(len);
        let (y, rest) = rest.split_at_mut(len);
        let (vx, rest) = rest.split_at_mut(nv);
        let (vy, rest) = rest.split_at_mut(nv);
        let (ax, ay) = rest.split_at_mut(nv);
        Columns { x, y, vx, vy, ax, ay, st }
    }
}

/// One input value's known points, indexed by point, for the slider solves with rates
/// (only the operation's inputs are filled in).
pub(super) struct Scratch {
    pub(super) pos: Vec<Xy>,
    pub(super) vel: Vec<Xy>,
    pub(super) acc: Vec<Xy>,
}

/// Keeps each value's first failure: `st` where nothing failed before.
#[inline(always)]
pub(super) fn note(first_bad: &mut [i8], st: &[i8]) {
    for (f, &s) in first_bad.iter_mut().zip(st) {
        *f = if *f == OK { s } else { *f };
    }
}

impl Columns<'_> {
    /// Point p's position at the block's value j.
    #[inline(always)]
    pub(super) fn point(&self, p: usize, j: usize) -> Xy {
        [self.x[p * B + j], self.y[p * B + j]]
    }
}

/// Point a's column (read) and point b's (written) for the block's `m` values (a != b).
pub(super) fn two_columns<T>(v: &mut [T], a: usize, b: usize, m: usize) -> (&[T], &mut [T]) {
    let (x, _, q) = two_in_one_out(v, a, a, b, m);
    (x, q)
}

/// Columns `a` and `b` (read; they may be one) and column `q` (written; another) for the
/// block's `m` values.
pub(super) fn two_in_one_out<T>(v: &mut [T], a: usize, b: usize, q: usize, m: usize) -> (&[T], &[T], &mut [T]) {
    let (lo, hi) = v.split_at_mut(q * B);
    let (out, rest) = hi.split_at_mut(B);
    let (lo, rest) = (&*lo, &*rest);
    let col = |p: usize| if p < q { &lo[p * B..p * B + m] } else { &rest[(p - q - 1) * B..(p - q - 1) * B + m] };
    (col(a), col(b), &mut out[..m])
}

/// The first failure among an operation's inputs at the block's value `j`.
#[inline(always)]
pub(super) fn inputs_status(c: &Columns<'_>, ins: &[usize], j: usize) -> i8 {
    ins.iter().map(|&p| c.st[p * B + j]).find(|&s| s != OK).unwrap_or(OK)
}

/// The status of a solve with conditioning `det` at a finite or not position `x`.
#[inline(always)]
pub(super) fn solved_status(x: Xy, det: f64, singular: f64) -> i8 {
    if det.abs() >= singular && x[0].is_finite() && x[1].is_finite() {
        OK
    } else if det.is_nan() || !(x[0].is_finite() && x[1].is_finite()) {
        Status::NonFinite.code()
    } else {
        Status::Singular.code()
    }
}
