//! The 4-lane AVX2 + FMA form of the polynomial sin/cos ([`super::math::sin_cos`], lane for
//! lane, bit for bit) and the register helpers the subjects' AVX2 kernels share.

use std::arch::x86_64::*;

use super::math::{
    C1, C2, C3, C4, C5, C6, PIO2_1, PIO2_2, PIO2_3, PIO2_3T, ROUND, S1, S2, S3, S4, S5, S6, TWO_OVER_PI,
};

/// Four f64 lanes in memory.
pub(crate) type V = [f64; 4];

#[inline]
#[target_feature(enable = "avx2,fma")]
pub(crate) fn splat(x: f64) -> __m256d {
    _mm256_set1_pd(x)
}

#[inline]
#[target_feature(enable = "avx2,fma")]
pub(crate) fn abs(x: __m256d) -> __m256d {
    _mm256_andnot_pd(splat(-0.0), x)
}

#[inline]
#[target_feature(enable = "avx2,fma")]
pub(crate) fn neg(x: __m256d) -> __m256d {
    _mm256_xor_pd(x, splat(-0.0))
}

#[inline]
#[target_feature(enable = "avx2,fma")]
pub(crate) fn ld(v: &V) -> __m256d {
    // SAFETY: V is 4 f64; unaligned load.
    unsafe { _mm256_loadu_pd(v.as_ptr()) }
}

#[inline]
#[target_feature(enable = "avx2,fma")]
pub(crate) fn st(v: __m256d) -> V {
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
