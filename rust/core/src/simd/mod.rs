//! SIMD kernels for the four-bar: the closed form over crank angles and the Newton batch
//! sweep over linkages, 4 lanes (AVX2 + FMA) at a time with polynomial sin/cos and atan2
//! ([`math`], within 2 ulp of glibc). Chosen at run time: [`enabled`] is true when the CPU
//! has AVX2 and FMA, unless `PLANARKIN_SIMD=0` or [`set_enabled`]`(false)` asked for the
//! scalar path, which is bit-identical to the NumPy reference. Statuses are the scalar
//! path's (any lane that leaves the common path is solved by the scalar code); angles
//! agree with it to a few ulp (the tests bound them at 1e-12 rad).

#[cfg(target_arch = "x86_64")]
mod avx2;
pub mod closed_form;
pub mod math;
pub mod newton;
pub(crate) mod sweep;

use std::sync::atomic::{AtomicU8, Ordering};

/// 0: not decided yet, 1: off, 2: on.
static STATE: AtomicU8 = AtomicU8::new(0);

/// True when the CPU has the features the SIMD kernels are compiled for (AVX2 and FMA).
pub fn available() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// Whether the SIMD kernels are used: the CPU has them and they were not switched off (by
/// `PLANARKIN_SIMD=0` in the environment, read once, or by [`set_enabled`]).
pub fn enabled() -> bool {
    match STATE.load(Ordering::Relaxed) {
        1 => false,
        2 => true,
        _ => {
            let off = std::env::var("PLANARKIN_SIMD").is_ok_and(|v| matches!(v.trim(), "0" | "false" | "off" | "no"));
            set_enabled(!off);
            enabled()
        }
    }
}

/// Switches the SIMD kernels on (where the CPU has them) or off (the bit-exact scalar
/// path) for the whole process; returns the previous setting.
pub fn set_enabled(on: bool) -> bool {
    let was = STATE.swap(if on && available() { 2 } else { 1 }, Ordering::Relaxed);
    was == 2
}

#[inline(always)]
fn table_body(theta2: &[f64], out: &mut [(f64, f64)]) {
    let out = &mut out[..theta2.len()];
    for (o, &t) in out.iter_mut().zip(theta2) {
        *o = math::sin_cos(t);
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn table_avx2(theta2: &[f64], out: &mut [(f64, f64)]) {
    table_body(theta2, out)
}

/// (sin, cos) of every crank angle, 4 at a time; arguments beyond the polynomial's range
/// (|x| > 1e5, infinities) go to libm.
pub fn sin_cos_table(theta2: &[f64]) -> Vec<(f64, f64)> {
    let mut out = vec![(0.0, 0.0); theta2.len()];
    sin_cos_into(theta2, &mut out);
    out
}

/// [`sin_cos_table`] into a buffer the caller allocated (fallibly, for user sizes).
pub fn sin_cos_into(theta2: &[f64], out: &mut [(f64, f64)]) {
    #[cfg(target_arch = "x86_64")]
    if available() {
        // SAFETY: AVX2 and FMA checked at run time.
        unsafe { table_avx2(theta2, out) };
    } else {
        table_body(theta2, out);
    }
    #[cfg(not(target_arch = "x86_64"))]
    table_body(theta2, out);
    for (o, &t) in out.iter_mut().zip(theta2) {
        if t.is_nan() || t.abs() > math::SIN_COS_MAX {
            *o = t.sin_cos();
        }
    }
}
