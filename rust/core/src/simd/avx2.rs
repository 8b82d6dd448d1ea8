//! Explicit AVX2 + FMA forms of the hot part of the Newton lane kernel: sin/cos of 4
//! angles and one Newton evaluation of 4 linkages (LLVM's SLP vectorizer split the plain
//! per-lane code into 2-wide halves). The formulas are those of [`super::math::sin_cos`]
//! and of the scalar `Loop::eval`, `newton::solve` and `cramer`, in the same operation
//! order (no contraction into FMA outside the sin/cos reduction, as there).

use std::arch::x86_64::*;

use super::math::{
    C1, C2, C3, C4, C5, C6, PIO2_1, PIO2_2, PIO2_3, PIO2_3T, ROUND, S1, S2, S3, S4, S5, S6, TWO_OVER_PI,
};
use super::newton::Eval;

type V = [f64; 4];

#[inline]
#[target_feature(enable = "avx2,fma")]
fn splat(x: f64) -> __m256d {
    _mm256_set1_pd(x)
}

#[inline]
#[target_feature(enable = "avx2,fma")]
fn abs(x: __m256d) -> __m256d {
    _mm256_andnot_pd(splat(-0.0), x)
}

#[inline]
#[target_feature(enable = "avx2,fma")]
fn neg(x: __m256d) -> __m256d {
    _mm256_xor_pd(x, splat(-0.0))
}

#[inline]
#[target_feature(enable = "avx2,fma")]
fn ld(v: &V) -> __m256d {
    // SAFETY: V is 4 f64; unaligned load.
    unsafe { _mm256_loadu_pd(v.as_ptr()) }
}

#[inline]
#[target_feature(enable = "avx2,fma")]
fn st(v: __m256d) -> V {
    let mut o = [0.0; 4];
    // SAFETY: o is 4 f64; unaligned store.
    unsafe { _mm256_storeu_pd(o.as_mut_ptr(), v) };
    o
}

/// (sin x, cos x) of 4 angles: [`super::math::sin_cos`] lane for lane, bit for bit.
#[inline]
#[target_feature(enable = "avx2,fma")]
pub(crate) fn sin_cos4(x: __m256d) -> (__m256d, __m256d) {
    let [s1, s2, s3, s4, s5, s6, c1, c2, c3, c4, c5, c6] = [S1, S2, S3, S4, S5, S6, C1, C2, C3, C4, C5, C6];
    let k = _mm256_add_pd(_mm256_mul_pd(x, splat(TWO_OVER_PI)), splat(ROUND));
    let q = _mm256_sub_pd(k, splat(ROUND));
    let nq = _mm256_sub_pd(splat(0.0), q);
    let r = _mm256_fmadd_pd(nq, splat(PIO2_1), x);
    let r = _mm256_fmadd_pd(nq, splat(PIO2_2), r);
    let r = _mm256_fmadd_pd(nq, splat(PIO2_3), r);
    let r = _mm256_fmadd_pd(nq, splat(PIO2_3T), r);
    let (add, mul) = (_mm256_add_pd, _mm256_mul_pd);
    let z = mul(r, r);
    let ps = add(splat(s2), mul(z, add(splat(s3), mul(z, add(splat(s4), mul(z, add(splat(s5), mul(z, splat(s6)))))))));
    let s = add(r, mul(mul(r, z), add(splat(s1), mul(z, ps))));
    let hz = mul(splat(0.5), z);
    let w = _mm256_sub_pd(splat(1.0), hz);
    let inner = add(splat(c5), mul(z, splat(c6)));
    let inner = add(splat(c2), mul(z, add(splat(c3), mul(z, add(splat(c4), mul(z, inner))))));
    let pc = mul(z, add(splat(c1), mul(z, inner)));
    let c = add(w, add(_mm256_sub_pd(_mm256_sub_pd(splat(1.0), w), hz), mul(z, pc)));
    let qi = _mm256_castpd_si256(k);
    let odd =
        _mm256_castsi256_pd(_mm256_cmpeq_epi64(_mm256_and_si256(qi, _mm256_set1_epi64x(1)), _mm256_set1_epi64x(1)));
    let sin = _mm256_blendv_pd(s, c, odd);
    let cos = _mm256_blendv_pd(c, s, odd);
    let sin_sign = _mm256_slli_epi64(_mm256_and_si256(qi, _mm256_set1_epi64x(2)), 62);
    let cos_sign =
        _mm256_slli_epi64(_mm256_and_si256(_mm256_add_epi64(qi, _mm256_set1_epi64x(1)), _mm256_set1_epi64x(2)), 62);
    (_mm256_xor_pd(sin, _mm256_castsi256_pd(sin_sign)), _mm256_xor_pd(cos, _mm256_castsi256_pd(cos_sign)))
}

/// [`super::newton::eval_lanes`] with AVX2: the same values, bit for bit.
#[inline]
#[target_feature(enable = "avx2,fma")]
pub(crate) fn eval4(r: &[V; 4], scale: &V, r3r4: &V, s2: f64, c2: f64, x: &[V; 2]) -> Eval {
    let (add, sub, mul, div) = (_mm256_add_pd, _mm256_sub_pd, _mm256_mul_pd, _mm256_div_pd);
    let (r1, r2, r3, r4) = (ld(&r[0]), ld(&r[1]), ld(&r[2]), ld(&r[3]));
    let (s3, c3) = sin_cos4(ld(&x[0]));
    let (s4, c4) = sin_cos4(ld(&x[1]));
    let (s2, c2) = (splat(s2), splat(c2));
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

/// The lock-step state of [`super::newton`]'s group kernel, advanced one Newton
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

/// One lock-step Newton evaluation with the masks of the portable loop in
/// `newton::group_body` (the same decisions, lane for lane), all in AVX2 registers.
#[inline]
#[target_feature(enable = "avx2,fma")]
pub(crate) fn iterate4(p: &Params<'_>, s2: f64, c2: f64, l: Lanes<'_>) {
    let e = eval4(p.r, p.scale, p.r3r4, s2, c2, l.x);
    let (and, or, andn) = (_mm256_and_pd, _mm256_or_pd, _mm256_andnot_pd);
    let cmp_lt = |a, b| _mm256_cmp_pd::<_CMP_LT_OQ>(a, b);
    let (f1, f2, x0, x1) = (ld(&e.f1), ld(&e.f2), ld(&l.x[0]), ld(&l.x[1]));
    let (dx0, dx1, step, sin34) = (ld(&e.dx[0]), ld(&e.dx[1]), ld(&e.step), ld(&e.sin34));
    let inf = splat(f64::INFINITY);
    let max = splat(super::math::SIN_COS_MAX);
    let finite = and(
        and(cmp_lt(abs(f1), inf), cmp_lt(abs(f2), inf)),
        and(_mm256_cmp_pd::<_CMP_LE_OQ>(abs(x0), max), _mm256_cmp_pd::<_CMP_LE_OQ>(abs(x1), max)),
    );
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
