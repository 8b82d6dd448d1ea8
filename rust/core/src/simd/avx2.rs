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
