//! The four-bar's SIMD kernels (AVX2 + FMA, chosen at run time by [`crate::simd::enabled`]):
//! the closed form over crank angles ([`closed_form`]), the closed-form predictor's sweep
//! with its Newton check across angles ([`across`]), the Newton continuation of one
//! linkage with 4-lane sin/cos ([`row`]), and the Newton batch, 4 linkages in lock-step
//! ([`batch`]). Statuses are the scalar path's (any lane that leaves the common path is
//! solved by the scalar code); angles agree with it to a few ulp (the tests bound them at
//! 1e-12 rad). `lane` holds the lane types and portable per-lane operations, `avx2` their
//! explicit AVX2 forms.

pub(super) mod across;
#[cfg(target_arch = "x86_64")]
mod avx2;
pub(super) mod batch;
pub(super) mod closed_form;
mod lane;
pub(super) mod row;

pub(super) use lane::W;
