//! Generic SIMD math and the process-wide switch that the SIMD kernels obey: polynomial
//! sin/cos and atan2 within 2 ulp of glibc ([`math`]) and their 4-lane AVX2 + FMA form.
//! [`enabled`] is true when the CPU has AVX2 and FMA, unless `PLANARKIN_SIMD=0` or
//! [`set_enabled`]`(false)` asked for the scalar paths, which are bit-identical to the
//! NumPy reference. The kernels that use this live with their subject (the four-bar's in
//! `fourbar::simd`).

#[cfg(target_arch = "x86_64")]
pub(crate) mod avx2;
pub mod math;

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

/// Defines `fn $name(args) -> $ret` (`$ret` optional) running `$body::<true>(args)` compiled with AVX2 and
/// FMA where the CPU has them (checked at run time), else `$body::<false>(args)`: the one
/// trampoline of every SIMD kernel. `$body` must be `#[inline(always)]`, so that it is
/// compiled into the `#[target_feature(enable = "avx2,fma")]` function the macro writes
/// (`AVX` is true there, for the code written in intrinsics).
macro_rules! avx2_kernel {
    ($(#[$meta:meta])* $vis:vis fn $name:ident($($arg:ident: $ty:ty),* $(,)?) $(-> $ret:ty)? = $body:ident;) => {
        $(#[$meta])*
        $vis fn $name($($arg: $ty),*) $(-> $ret)? {
            #[cfg(target_arch = "x86_64")]
            #[target_feature(enable = "avx2,fma")]
            unsafe fn avx2($($arg: $ty),*) $(-> $ret)? {
                $body::<true>($($arg),*)
            }
            #[cfg(target_arch = "x86_64")]
            if $crate::simd::available() {
                // SAFETY: AVX2 and FMA checked at run time.
                return unsafe { avx2($($arg),*) };
            }
            $body::<false>($($arg),*)
        }
    };
}
pub(crate) use avx2_kernel;

avx2_kernel! {
    /// The polynomial (sin, cos) of every angle of `theta`, into `out`.
    fn table(theta: &[f64], out: &mut [(f64, f64)]) = table_body;
}

#[inline(always)]
fn table_body<const AVX: bool>(theta: &[f64], out: &mut [(f64, f64)]) {
    let out = &mut out[..theta.len()];
    for (o, &t) in out.iter_mut().zip(theta) {
        *o = math::sin_cos(t);
    }
}

/// (sin, cos) of one angle as [`sin_cos_block`] gives it in a block, bit for bit (the
/// scenes' continuation turns its input and its groups' rotations with this, the column
/// sweep with the block form, so both paths turn alike): the polynomial where the SIMD
/// kernels are on, libm otherwise or beyond the polynomial's range.
pub fn sin_cos(theta: f64) -> (f64, f64) {
    #[cfg(target_arch = "x86_64")]
    if enabled() && !(theta.is_nan() || theta.abs() > math::SIN_COS_MAX) {
        // SAFETY: the SIMD kernels are on only where the CPU has AVX2 and FMA.
        return unsafe { sin_cos_fma(theta) };
    }
    theta.sin_cos()
}

/// The polynomial sin/cos with its fused multiply-adds in hardware (not libm's `fma`).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn sin_cos_fma(theta: f64) -> (f64, f64) {
    math::sin_cos(theta)
}

/// (sin, cos) of a block of angles: polynomial, 4 at a time, where the SIMD kernels are on
/// (within 2 ulp of libm; libm beyond the polynomial's range), libm otherwise.
pub fn sin_cos_block(theta: &[f64], out: &mut [(f64, f64)]) {
    if enabled() {
        sin_cos_into(theta, out);
    } else {
        for (o, t) in out.iter_mut().zip(theta) {
            *o = t.sin_cos();
        }
    }
}

/// The direction of `d` = (x, y) in (-pi, pi] (`atan2(y + 0.0, x)`: a zero `y` of either
/// sign counts as +0, so a vector along -x reads +pi): the branch-free polynomial
/// ([`math::atan2`], within 2 ulp of libm) where `fast` (the SIMD kernels on, asked once by
/// the caller, whose code must be compiled with FMA); libm otherwise, the NumPy
/// reference's numbers.
#[inline(always)]
pub fn direction(d: [f64; 2], fast: bool) -> f64 {
    if fast {
        math::atan2(d[1] + 0.0, d[0])
    } else {
        (d[1] + 0.0).atan2(d[0])
    }
}

/// [`direction`] of every vector (`x[i]`, `y[i]`) (a NaN `x` gives NaN), 4 at a time with
/// the polynomial where the SIMD kernels are on; each value is the one the scalar call
/// gives, bit for bit.
pub fn directions_into(x: &[f64], y: &[f64], out: &mut [f64]) {
    // (where the kernels are on, the CPU has AVX2 and FMA: `directions` takes its AVX2 path)
    if enabled() {
        directions(x, y, out);
    } else {
        directions_body(x, y, out, false);
    }
}

avx2_kernel! {
    /// [`directions_body`] with the polynomial, compiled with AVX2 and FMA where the CPU
    /// has them.
    fn directions(x: &[f64], y: &[f64], out: &mut [f64]) = directions_fast;
}

#[inline(always)]
fn directions_fast<const AVX: bool>(x: &[f64], y: &[f64], out: &mut [f64]) {
    directions_body(x, y, out, true);
}

/// The loop of [`directions_into`], compiled into each caller (a kernel compiled with FMA
/// calls it with `fast`): coordinates in two arrays and a select, no branch, so it
/// vectorizes.
#[inline(always)]
pub(crate) fn directions_body(x: &[f64], y: &[f64], out: &mut [f64], fast: bool) {
    for ((o, &x), &y) in out.iter_mut().zip(x).zip(y) {
        let a = direction([x, y], fast);
        *o = if x.is_nan() { f64::NAN } else { a };
    }
}

/// (sin, cos) of every angle into a buffer the caller allocated (fallibly, for user
/// sizes), 4 at a time; arguments beyond the polynomial's range (|x| > 1e5, infinities,
/// NaN) go to libm.
pub fn sin_cos_into(theta: &[f64], out: &mut [(f64, f64)]) {
    table(theta, out);
    // beyond the polynomial's range, or NaN (which fails `<=`): one fold (it vectorizes)
    // finds whether any argument needs libm, and the loop that gives it runs only then
    let libm = |t: f64| !(t.abs() <= math::SIN_COS_MAX);
    if theta.iter().fold(false, |any, &t| any | libm(t)) {
        for (o, &t) in out.iter_mut().zip(theta).filter(|(_, &t)| libm(t)) {
            *o = t.sin_cos();
        }
    }
}
