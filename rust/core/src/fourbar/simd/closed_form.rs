//! The four-bar closed form over many crank angles, branch-free so that its loops run 4
//! (AVX2) angles at a time: one sqrt for |A O4|, one for the triangle's height, two
//! polynomial atan2 (in a loop of their own, a block of angles at a time). The same
//! formulas and operation order as `FourBar::geometry` and `Triangle::angles`, so only the
//! atan2 differs from the scalar path (by <= 2 ulp).

use crate::error::Error;
use crate::fourbar::model::{FourBar, Mode, Point, FLAT_ULPS};
use crate::fourbar::options::{MotionOut, SweepOptions, SweepOut};
use crate::fourbar::point::fill_motion;
use crate::interrupt::Poll;
use crate::simd::{avx2_kernel, directions_body};
use crate::Status;

const CONVERGED: i8 = Status::Converged as i8;
const NON_FINITE: i8 = Status::NonFinite as i8;
const SINGULAR: i8 = Status::Singular as i8;
const NOT_ASSEMBLABLE: i8 = Status::NotAssemblable as i8;

/// What a closed-form row computes; `nan_singular` gives NaN angles at singular points
/// (the sweep's convention) rather than the closed form's angles (the arrays' one).
#[derive(Clone, Copy)]
pub(crate) struct RowSpec {
    pub mode: Mode,
    pub singular: f64,
    pub nan_singular: bool,
}

#[inline(always)]
fn row_body<const STATUS: bool, const WELL: bool>(
    fb: &FourBar,
    theta2: &[f64],
    trig: &[(f64, f64)],
    spec: RowSpec,
    theta3: &mut [f64],
    theta4: &mut [f64],
    status: &mut [i8],
) {
    let n = theta2.len();
    let (trig, theta3, theta4) = (&trig[..n], &mut theta3[..n], &mut theta4[..n]);
    let status = if STATUS { &mut status[..n] } else { status };
    let [r1, r2, r3, r4] = fb.unit_lengths();
    let cond_scale = r3.min(r4) / fb.longest();
    let (k, r3r4, sign) = ((r3 - r4) * (r3 + r4), r3 * r4, spec.mode.sign());
    let indeterminate = if r3 == r4 { SINGULAR } else { NOT_ASSEMBLABLE };
    let slack = FLAT_ULPS * f64::EPSILON * fb.longest();
    // in blocks, each in three loops: |A O4|, then the rest of the geometry, then the two
    // atan2s (short loops keep few values live, so more of their iterations are in flight:
    // the square roots' and divisions' latencies overlap)
    // the two atan2s' arguments, theta3's then theta4's
    let (mut xs, mut ys) = ([0.0; 2 * BLOCK], [0.0; 2 * BLOCK]);
    let mut ds = [0.0; BLOCK];
    let crank = |(s2, c2): (f64, f64)| {
        let (ux, uy) = (r1 - r2 * c2, -(r2 * s2));
        (ux, uy, ux * ux + uy * uy)
    };
    for start in (0..n).step_by(BLOCK) {
        let m = BLOCK.min(n - start);
        for (d, &t) in ds[..m].iter_mut().zip(&trig[start..start + m]) {
            *d = crank(t).2.sqrt();
        }
        for j in 0..m {
            let i = start + j;
            let (ux, uy, d2) = crank(trig[i]);
            let d = ds[j];
            // as the scalar geometry: within FLAT_ULPS ulp of closing, a triangle is flat
            let flat = |q: f64| if (q < 0.0) & (q >= -slack) { 0.0 } else { q };
            let q1 = flat(d + r3 - r4);
            let q2 = flat(d - r3 + r4);
            let q3 = flat(r3 + r4 - d);
            let tri = (q1 >= 0.0) & (q2 >= 0.0) & (q3 >= 0.0) & (d != 0.0);
            let two_dh = ((r3 + r4 + d) * q1 * q2 * q3).sqrt();
            let h = sign * two_dh;
            let (ca, cb) = (k + d2, k - d2);
            // the conditioning, where a status or the kept angles need it
            let well = !WELL || (h / (2.0 * r3r4)).abs() * cond_scale >= spec.singular;
            let finite = theta2[i].is_finite();
            let keep = finite & tri & (well | !spec.nan_singular);
            // a NaN abscissa marks an angle that is not kept
            (xs[j], ys[j]) = (if keep { ux * ca - uy * h } else { f64::NAN }, uy * ca + ux * h);
            (xs[BLOCK + j], ys[BLOCK + j]) = (if keep { ux * cb - uy * h } else { f64::NAN }, uy * cb + ux * h);
            if STATUS {
                status[i] = if !finite {
                    NON_FINITE
                } else if tri {
                    if well {
                        CONVERGED
                    } else {
                        SINGULAR
                    }
                } else if d == 0.0 {
                    indeterminate
                } else {
                    NOT_ASSEMBLABLE
                };
            }
        }
        directions_body(&xs[..m], &ys[..m], &mut theta3[start..start + m], true);
        directions_body(&xs[BLOCK..BLOCK + m], &ys[BLOCK..BLOCK + m], &mut theta4[start..start + m], true);
    }
}

/// Angles a block of [`row_body`] takes at once.
const BLOCK: usize = 128;

avx2_kernel! {
    /// The closed form of one linkage at every crank angle (with its precomputed (sin,
    /// cos)), with the statuses of the scalar path: NonFinite, NotAssemblable, Singular
    /// (below `singular`, or indeterminate), Converged. The status is written only when
    /// given.
    pub(crate) fn closed_form_row(
        fb: &FourBar,
        theta2: &[f64],
        trig: &[(f64, f64)],
        spec: RowSpec,
        theta3: &mut [f64],
        theta4: &mut [f64],
        status: Option<&mut [i8]>,
    ) = rows;
}

/// [`row_body`] for what `out` asks: the conditioning is computed only where a status or
/// the kept angles need it. The loops are the same with AVX2 (`_AVX`): the trampoline's
/// features vectorize them.
#[inline(always)]
fn rows<const _AVX: bool>(
    fb: &FourBar,
    theta2: &[f64],
    trig: &[(f64, f64)],
    spec: RowSpec,
    theta3: &mut [f64],
    theta4: &mut [f64],
    status: Option<&mut [i8]>,
) {
    match (status, spec.nan_singular) {
        (Some(s), _) => row_body::<true, true>(fb, theta2, trig, spec, theta3, theta4, s),
        (None, true) => row_body::<false, true>(fb, theta2, trig, spec, theta3, theta4, &mut []),
        (None, false) => row_body::<false, false>(fb, theta2, trig, spec, theta3, theta4, &mut []),
    }
}

/// The closed-form sweep (`Method::ClosedForm`) of one linkage: NaN angles unless
/// Converged, `nit` 0, residual NaN, then velocities and accelerations when asked for.
pub(crate) fn sweep(
    fb: &FourBar,
    theta2: &[f64],
    trig: &[(f64, f64)],
    opts: &SweepOptions,
    out: SweepOut<'_>,
    mut motion: Option<MotionOut<'_>>,
    poll: &Poll<'_>,
) -> Result<(), Error> {
    poll.tick_n(theta2.len())?; // the whole row at once: closed-form points cost nanoseconds
    let spec = RowSpec { mode: opts.mode, singular: opts.newton.singular, nan_singular: true };
    closed_form_row(fb, theta2, trig, spec, out.theta3, out.theta4, Some(&mut *out.status));
    out.nit.fill(0);
    out.residual.fill(f64::NAN);
    if let Some(m) = motion.as_mut() {
        for (i, &t2) in theta2.iter().enumerate() {
            // fill_motion reads the angles and the flag only
            let ok = out.status[i] == CONVERGED;
            let status = if ok { Status::Converged } else { Status::Singular };
            let p = Point { theta3: out.theta3[i], theta4: out.theta4[i], status, nit: 0, residual: f64::NAN };
            fill_motion(fb, t2, &p, ok, i, m, opts.newton.singular);
        }
    }
    Ok(())
}
