//! Explicit AVX2 + FMA forms of the hot part of the four-bar's Newton lane kernel: one
//! Newton evaluation of 4 linkages and one lock-step iteration (LLVM's SLP vectorizer
//! split the plain per-lane code into 2-wide halves). The formulas are those of the
//! scalar `Loop::eval`, `newton::solve` and `cramer`, in the same operation order (no
//! contraction into FMA outside the sin/cos reduction, as there).

use std::arch::x86_64::*;

use super::lane::{wrap, Block, Check, Eval, M};
use crate::simd::avx2::{abs, ld, neg, sin_cos4, splat, st, V};

/// [`super::lane::eval_lanes`] with AVX2 at one crank angle for every lane: the same
/// values, bit for bit.
#[inline]
#[target_feature(enable = "avx2,fma")]
pub(crate) fn eval4(r: &[V; 4], scale: &V, r3r4: &V, s2: f64, c2: f64, x: &[V; 2]) -> Eval {
    eval4_at(r, scale, r3r4, splat(s2), splat(c2), x)
}

/// [`super::lane::eval_lanes`] with AVX2, each lane at its own crank angle (s2, c2): the
/// same values, bit for bit.
#[inline]
#[target_feature(enable = "avx2,fma")]
pub(crate) fn eval4_at(r: &[V; 4], scale: &V, r3r4: &V, s2: __m256d, c2: __m256d, x: &[V; 2]) -> Eval {
    let (add, sub, mul, div) = (_mm256_add_pd, _mm256_sub_pd, _mm256_mul_pd, _mm256_div_pd);
    let (r1, r2, r3, r4) = (ld(&r[0]), ld(&r[1]), ld(&r[2]), ld(&r[3]));
    let (s3, c3) = sin_cos4(ld(&x[0]));
    let (s4, c4) = sin_cos4(ld(&x[1]));
    let f1 = sub(sub(add(mul(r2, c2), mul(r3, c3)), mul(r4, c4)), r1);
    let f2 = sub(add(mul(r2, s2), mul(r3, s3)), mul(r4, s4));
    let j00 = mul(neg(r3), s3);
    let j01 = mul(r4, s4);
    let j10 = mul(r3, c3);
    let j11 = mul(neg(r4), c4);
    // f64::max ignores NaN; a NaN residual is caught by the finiteness test anyway
    let residual = div(_mm256_max_pd(_mm256_max_pd(splat(0.0), abs(f1)), abs(f2)), ld(scale));
    let det = sub(mul(j00, j11), mul(j01, j10));
    let sin34 = div(neg(det), ld(r3r4));
    let (b0, b1) = (neg(f1), neg(f2));
    let dx0 = div(sub(mul(b0, j11), mul(b1, j01)), det);
    let dx1 = div(sub(mul(j00, b1), mul(j10, b0)), det);
    let step = _mm256_max_pd(abs(dx0), abs(dx1));
    Eval {
        f1: st(f1),
        f2: st(f2),
        j: [st(j00), st(j01), st(j10), st(j11)],
        residual: st(residual),
        det: st(det),
        sin34: st(sin34),
        dx: [st(dx0), st(dx1)],
        step: st(step),
    }
}

/// (sin x3, cos x3, sin x4, cos x4) in one 4-lane call (lanes x3, x4, x3, x4).
#[inline]
#[target_feature(enable = "avx2,fma")]
pub(crate) fn sin_cos2(x3: f64, x4: f64) -> [f64; 4] {
    let (s, c) = sin_cos4(_mm256_set_pd(x4, x3, x4, x3));
    let (s, c) = (st(s), st(c));
    [s[0], c[0], s[1], c[1]]
}

/// The lock-step state of [`super::batch`]'s group kernel, advanced one Newton
/// evaluation by [`iterate4`].
pub(crate) struct Lanes<'a> {
    pub x: &'a mut [V; 2],
    pub nit: &'a mut [u32; 4],
    pub last_small: &'a mut V,
    pub active: &'a mut [bool; 4],
    pub done: &'a mut [bool; 4],
    pub fail: &'a mut [bool; 4],
    pub xf: &'a mut [V; 2],
    pub resid: &'a mut V,
    pub jac: &'a mut [V; 4],
}

/// Fixed parameters of a group: lengths, scales and the stopping criteria.
pub(crate) struct Params<'a> {
    pub r: &'a [V; 4],
    pub scale: &'a V,
    pub r3r4: &'a V,
    pub cond_scale: &'a V,
    pub sign: f64,
    pub tol: f64,
    pub singular: f64,
    pub max_iter: u32,
}

#[inline]
#[target_feature(enable = "avx2,fma")]
fn mask_of(b: &[bool; 4]) -> __m256d {
    let m = |v: bool| if v { -1i64 } else { 0 };
    _mm256_castsi256_pd(_mm256_set_epi64x(m(b[3]), m(b[2]), m(b[1]), m(b[0])))
}

#[inline]
#[target_feature(enable = "avx2,fma")]
fn bools(m: __m256d) -> [bool; 4] {
    let b = _mm256_movemask_pd(m);
    [b & 1 != 0, b & 2 != 0, b & 4 != 0, b & 8 != 0]
}

/// Lanes whose residuals are finite and whose angles lie where the polynomial sin/cos
/// holds (|x| <= `SIN_COS_MAX`); NaN fails both tests.
#[inline]
#[target_feature(enable = "avx2,fma")]
fn finite4(f1: __m256d, f2: __m256d, x0: __m256d, x1: __m256d) -> __m256d {
    let (inf, max) = (splat(f64::INFINITY), splat(crate::simd::math::SIN_COS_MAX));
    let residuals = _mm256_and_pd(_mm256_cmp_pd::<_CMP_LT_OQ>(abs(f1), inf), _mm256_cmp_pd::<_CMP_LT_OQ>(abs(f2), inf));
    let angles = _mm256_and_pd(_mm256_cmp_pd::<_CMP_LE_OQ>(abs(x0), max), _mm256_cmp_pd::<_CMP_LE_OQ>(abs(x1), max));
    _mm256_and_pd(residuals, angles)
}

/// One lock-step Newton evaluation with the masks of the portable loop in
/// `batch::group_body` (the same decisions, lane for lane), all in AVX2 registers.
#[inline]
#[target_feature(enable = "avx2,fma")]
pub(crate) fn iterate4(p: &Params<'_>, s2: f64, c2: f64, l: Lanes<'_>) {
    let e = eval4(p.r, p.scale, p.r3r4, s2, c2, l.x);
    let (and, or, andn) = (_mm256_and_pd, _mm256_or_pd, _mm256_andnot_pd);
    let cmp_lt = |a, b| _mm256_cmp_pd::<_CMP_LT_OQ>(a, b);
    let (f1, f2, x0, x1) = (ld(&e.f1), ld(&e.f2), ld(&l.x[0]), ld(&l.x[1]));
    let (dx0, dx1, step, sin34) = (ld(&e.dx[0]), ld(&e.dx[1]), ld(&e.step), ld(&e.sin34));
    let finite = finite4(f1, f2, x0, x1);
    let sing = or(
        cmp_lt(_mm256_mul_pd(abs(sin34), ld(p.cond_scale)), splat(p.singular)),
        _mm256_cmp_pd::<_CMP_EQ_OQ>(ld(&e.det), splat(0.0)),
    );
    let small = cmp_lt(ld(&e.residual), splat(p.tol));
    let conv = and(small, cmp_lt(step, splat(p.tol)));
    let ploss = andn(conv, and(small, _mm256_cmp_pd::<_CMP_GT_OQ>(step, _mm256_mul_pd(splat(0.5), ld(l.last_small)))));
    let nit = _mm256_set_pd(l.nit[3] as f64, l.nit[2] as f64, l.nit[1] as f64, l.nit[0] as f64);
    let out_of_steps = andn(or(conv, ploss), _mm256_cmp_pd::<_CMP_GE_OQ>(nit, splat(p.max_iter as f64)));
    let branch_jump = and(conv, cmp_lt(_mm256_mul_pd(sin34, splat(p.sign)), splat(0.0)));
    let bad = or(
        or(andn(finite, _mm256_castsi256_pd(_mm256_set1_epi64x(-1))), sing),
        or(or(ploss, out_of_steps), branch_jump),
    );
    let active = mask_of(l.active);
    let finished = andn(bad, and(active, conv));
    let go_on = andn(bad, andn(conv, active));
    let failed = and(active, bad);
    let blend = |old: __m256d, new: __m256d, m| _mm256_blendv_pd(old, new, m);
    let (x0n, x1n) = (_mm256_add_pd(x0, dx0), _mm256_add_pd(x1, dx1));
    *l.xf = [st(blend(ld(&l.xf[0]), x0n, finished)), st(blend(ld(&l.xf[1]), x1n, finished))];
    *l.resid = st(blend(ld(l.resid), ld(&e.residual), finished));
    for k in 0..4 {
        l.jac[k] = st(blend(ld(&l.jac[k]), ld(&e.j[k]), finished));
    }
    *l.last_small = st(blend(ld(l.last_small), step, and(go_on, small)));
    *l.x = [st(blend(x0, x0n, go_on)), st(blend(x1, x1n, go_on))];
    let go = bools(go_on);
    for (n, g) in l.nit.iter_mut().zip(go) {
        *n += g as u32;
    }
    let (fin, fl) = (bools(finished), bools(failed));
    for k in 0..4 {
        l.done[k] |= fin[k];
        l.fail[k] |= fl[k];
    }
    *l.active = go;
}

/// `across::accept` in AVX2 registers: the same evaluation ([`eval4_at`]), the same
/// criteria and the same wrap, lane for lane.
#[inline]
#[target_feature(enable = "avx2,fma")]
pub(crate) fn accept4(c: &Check, cand: M, b: Block<'_>) -> M {
    let (and, cmp_lt) = (_mm256_and_pd, |a, b| _mm256_cmp_pd::<_CMP_LT_OQ>(a, b));
    let x: [V; 2] = [lane4(b.theta3), lane4(b.theta4)];
    let (x0, x1) = (ld(&x[0]), ld(&x[1]));
    let t = b.trig;
    let s2 = _mm256_set_pd(t[3].0, t[2].0, t[1].0, t[0].0);
    let c2 = _mm256_set_pd(t[3].1, t[2].1, t[1].1, t[0].1);
    let e = eval4_at(&c.r, &c.scale, &c.r3r4, s2, c2, &x);
    let (sin34, step) = (ld(&e.sin34), ld(&e.step));
    let finite = finite4(ld(&e.f1), ld(&e.f2), x0, x1);
    let well = and(
        // `!=` is true of NaN (unordered), as the lane loop's `det != 0.0` is
        _mm256_cmp_pd::<_CMP_NEQ_UQ>(ld(&e.det), splat(0.0)),
        _mm256_cmp_pd::<_CMP_GE_OQ>(_mm256_mul_pd(abs(sin34), splat(c.cond_scale)), splat(c.singular)),
    );
    let small = and(cmp_lt(ld(&e.residual), splat(c.tol)), cmp_lt(step, splat(c.tol)));
    let mode = _mm256_cmp_pd::<_CMP_GT_OQ>(_mm256_mul_pd(sin34, splat(c.sign)), splat(0.0));
    let bits = _mm256_movemask_pd(and(and(finite, well), and(small, mode)));
    let ok: M = [0, 1, 2, 3].map(|l| cand[l] & (bits >> l & 1 != 0));
    if ok.iter().any(|&o| o) {
        let t3 = wrap(st(_mm256_add_pd(x0, ld(&e.dx[0]))));
        let t4 = wrap(st(_mm256_add_pd(x1, ld(&e.dx[1]))));
        for l in (0..4).filter(|&l| ok[l]) {
            b.theta3[l] = t3[l];
            b.theta4[l] = t4[l];
            b.residual[l] = e.residual[l];
        }
    }
    ok
}

/// The first 4 values of a block's slice.
#[inline(always)]
fn lane4(v: &[f64]) -> V {
    [v[0], v[1], v[2], v[3]]
}
