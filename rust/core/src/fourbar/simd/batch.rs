//! The Newton continuation sweep of a batch, 4 linkages in lock-step (one per lane) at each
//! crank angle: the prediction, the Newton steps with polynomial sin/cos, the convergence
//! test and the predictor's rates, all lane-wise. A lane that leaves the common path (no
//! previous point, a toggle, a failed or slow solve, the other mode, a dead crank pin
//! position) is solved by the scalar `sweep_point` from the same start, so every status
//! is the scalar path's; angles differ from it only by the rounding of the polynomials.

use nalgebra::Vector2;

use super::lane::{eval_lanes, lanes, rates, wrap, Eval, M, V, W};
use crate::error::Error;
use crate::fourbar::model::{FourBar, Point, FLAT_ULPS};
use crate::fourbar::options::{Predictor, SweepOptions};
use crate::fourbar::point::{predictor_rates, sweep_point};
use crate::interrupt::Poll;
use crate::simd::avx2_kernel;
use crate::simd::math::SIN_COS_MAX;
use crate::{wrap_angle, Status};

/// Newton steps tried in lock-step before a lane goes to the scalar path (one or two are
/// the rule on a sweep with a predictor).
const LOCKSTEP_STEPS: u32 = 8;

avx2_kernel! {
    /// One group of [`W`] linkages solved in lock-step into its (W, N) outputs (for
    /// `crate::fourbar::sweep_batch`, which has checked the output lengths and that there
    /// is at least one angle).
    pub(crate) fn group(
        fbs: &[FourBar],
        theta2: &[f64],
        trig: &[(f64, f64)],
        opts: &SweepOptions,
        t3: &mut [f64],
        t4: &mut [f64],
        st: &mut [i8],
        nit: &mut [u32],
        res: &mut [f64],
        poll: &Poll<'_>,
    ) -> Result<(), Error> = group_body;
}

/// The last converged point of every lane, with the predictor's rates.
struct Prev {
    ok: M,
    x: [V; 2],
    v: [V; 2],
    a: [V; 2],
}

#[inline(always)]
fn group_body<const AVX: bool>(
    fbs: &[FourBar],
    theta2: &[f64],
    trig: &[(f64, f64)],
    opts: &SweepOptions,
    t3: &mut [f64],
    t4: &mut [f64],
    st: &mut [i8],
    nit_out: &mut [u32],
    res_out: &mut [f64],
    poll: &Poll<'_>,
) -> Result<(), Error> {
    let n = theta2.len();
    let r: [V; 4] = [0, 1, 2, 3].map(|k| lanes!(|l| fbs[l].unit_lengths()[k]));
    let [r1, r2, r3, r4] = r;
    let scale: V = lanes!(|l| fbs[l].longest());
    let cond_scale: V = lanes!(|l| r3[l].min(r4[l]) / scale[l]);
    let r3r4: V = lanes!(|l| r3[l] * r4[l]);
    let sign = opts.mode.sign();
    let (tol, singular, max_iter) = (opts.newton.tol, opts.newton.singular, opts.newton.max_iter);
    let cap = max_iter.min(LOCKSTEP_STEPS);
    let zero: V = [0.0; W];
    let mut prev = Prev { ok: [false; W], x: [zero; 2], v: [zero; 2], a: [zero; 2] };

    let mut write = |l: usize, i: usize, p: &Point| {
        let k = l * n + i;
        t3[k] = p.theta3;
        t4[k] = p.theta4;
        st[k] = p.status.code();
        nit_out[k] = p.nit;
        res_out[k] = p.residual;
    };

    for i in 0..n {
        poll.tick()?;
        let t2 = theta2[i];
        if !t2.is_finite() {
            for l in 0..W {
                write(l, i, &Point::failed(Status::NonFinite, 0, f64::NAN));
            }
            prev.ok = [false; W];
            continue;
        }
        let (s2, c2) = trig[i];
        // the previous converged point is always the previous angle's
        let h = if i > 0 { wrap_angle(t2 - theta2[i - 1]) } else { 0.0 };
        let start: [V; 2] = match opts.predictor {
            Predictor::ClosedForm => unreachable!("the closed-form predictor sweeps on the scalar path"),
            Predictor::Previous => prev.x,
            Predictor::Tangent => {
                [lanes!(|l| prev.x[0][l] + prev.v[0][l] * h), lanes!(|l| prev.x[1][l] + prev.v[1][l] * h)]
            }
            Predictor::Quadratic => {
                let hh = 0.5 * h * h;
                [
                    lanes!(|l| prev.x[0][l] + prev.v[0][l] * h + prev.a[0][l] * hh),
                    lanes!(|l| prev.x[1][l] + prev.v[1][l] * h + prev.a[1][l] * hh),
                ]
            }
        };
        // geometry: where the loop cannot close (decided before any iteration), and where
        // A sits on O4 (left to the scalar path)
        let mut not_asm: M = [false; W];
        let mut odd: M = [false; W];
        for l in 0..W {
            let ux = r1[l] - r2[l] * c2;
            let uy = -(r2[l] * s2);
            let d = (ux * ux + uy * uy).sqrt();
            let q1 = d + r3[l] - r4[l];
            let q2 = d - r3[l] + r4[l];
            let q3 = r3[l] + r4[l] - d;
            // within FLAT_ULPS ulp of closing, a triangle is flat: the scalar path decides
            let slack = FLAT_ULPS * f64::EPSILON * fbs[l].longest();
            let flat = |q: f64| (q < 0.0) & (q >= -slack);
            odd[l] = d == 0.0 || flat(q1) || flat(q2) || flat(q3);
            not_asm[l] = !odd[l] & !((q1 >= 0.0) & (q2 >= 0.0) & (q3 >= 0.0));
        }
        let mut active: M = lanes!(|l| prev.ok[l] & !not_asm[l] & !odd[l]);
        let mut fail: M = lanes!(|l| !prev.ok[l] | odd[l]);
        let mut x = start;
        let mut nit = [0u32; W];
        let mut last_small: V = [f64::INFINITY; W];
        let mut done: M = [false; W];
        let mut xf: [V; 2] = [zero; 2];
        let mut resid: V = zero;
        let mut jac: [V; 4] = [zero; 4];
        let mut iter = 0;
        while active.iter().any(|&a| a) {
            // AVX is never true off x86_64 (the AVX2 trampoline exists only there)
            if AVX {
                #[cfg(target_arch = "x86_64")]
                {
                    let params = super::avx2::Params {
                        r: &r,
                        scale: &scale,
                        r3r4: &r3r4,
                        cond_scale: &cond_scale,
                        sign,
                        tol,
                        singular,
                        max_iter,
                    };
                    let lanes = super::avx2::Lanes {
                        x: &mut x,
                        nit: &mut nit,
                        last_small: &mut last_small,
                        active: &mut active,
                        done: &mut done,
                        fail: &mut fail,
                        xf: &mut xf,
                        resid: &mut resid,
                        jac: &mut jac,
                    };
                    // SAFETY: AVX is true only in the AVX2 trampoline, called after the run-time check.
                    unsafe { super::avx2::iterate4(&params, s2, c2, lanes) };
                    x = [wrap(x[0]), wrap(x[1])];
                }
            } else {
                let e = eval_lanes(&r, &scale, &r3r4, &[s2; W], &[c2; W], &x);
                let Eval { f1, f2, j: [j00, j01, j10, j11], residual, det, sin34, dx: [dx0, dx1], step } = e;
                let small: M = lanes!(|l| residual[l] < tol);
                let conv: M = lanes!(|l| small[l] & (step[l] < tol));
                let bad: M = lanes!(|l| {
                    let finite = f1[l].is_finite()
                        & f2[l].is_finite()
                        & (x[0][l].abs() <= SIN_COS_MAX)
                        & (x[1][l].abs() <= SIN_COS_MAX);
                    let ploss = small[l] & !conv[l] & (step[l] > 0.5 * last_small[l]);
                    let out_of_steps = !conv[l] & !ploss & (nit[l] >= max_iter);
                    let branch_jump = conv[l] & (sin34[l] * sign < 0.0);
                    !finite
                        | (sin34[l].abs() * cond_scale[l] < singular)
                        | (det[l] == 0.0)
                        | ploss
                        | out_of_steps
                        | branch_jump
                });
                let finished: M = lanes!(|l| active[l] & !bad[l] & conv[l]);
                let go_on: M = lanes!(|l| active[l] & !bad[l] & !conv[l]);
                fail = lanes!(|l| fail[l] | (active[l] & bad[l]));
                done = lanes!(|l| done[l] | finished[l]);
                xf = [
                    lanes!(|l| if finished[l] { x[0][l] + dx0[l] } else { xf[0][l] }),
                    lanes!(|l| if finished[l] { x[1][l] + dx1[l] } else { xf[1][l] }),
                ];
                resid = lanes!(|l| if finished[l] { residual[l] } else { resid[l] });
                jac = [
                    lanes!(|l| if finished[l] { j00[l] } else { jac[0][l] }),
                    lanes!(|l| if finished[l] { j01[l] } else { jac[1][l] }),
                    lanes!(|l| if finished[l] { j10[l] } else { jac[2][l] }),
                    lanes!(|l| if finished[l] { j11[l] } else { jac[3][l] }),
                ];
                last_small = lanes!(|l| if go_on[l] & small[l] { step[l] } else { last_small[l] });
                x = [
                    wrap(lanes!(|l| if go_on[l] { x[0][l] + dx0[l] } else { x[0][l] })),
                    wrap(lanes!(|l| if go_on[l] { x[1][l] + dx1[l] } else { x[1][l] })),
                ];
                nit = lanes!(|l| nit[l] + go_on[l] as u32);
                active = go_on;
            }
            iter += 1;
            if iter > cap {
                fail = lanes!(|l| fail[l] | active[l]);
                break;
            }
        }
        let xf = [wrap(xf[0]), wrap(xf[1])];
        let (v, a) = rates(&r2, s2, c2, &jac, opts.predictor);
        for l in 0..W {
            if done[l] {
                let p = Point {
                    theta3: xf[0][l],
                    theta4: xf[1][l],
                    status: Status::Converged,
                    nit: nit[l],
                    residual: resid[l],
                };
                write(l, i, &p);
                prev.x[0][l] = xf[0][l];
                prev.x[1][l] = xf[1][l];
                prev.v[0][l] = v[0][l];
                prev.v[1][l] = v[1][l];
                prev.a[0][l] = a[0][l];
                prev.a[1][l] = a[1][l];
                prev.ok[l] = true;
            } else if not_asm[l] && prev.ok[l] {
                write(l, i, &Point::failed(Status::NotAssemblable, 0, f64::NAN));
                prev.ok[l] = false;
            } else if fail[l] {
                let fb = &fbs[l];
                let sys = fb.at_sin_cos(s2, c2);
                let x0 = if prev.ok[l] { Some(Vector2::new(start[0][l], start[1][l])) } else { None };
                let (p, j) = sweep_point(fb, &sys, x0, opts, poll)?;
                write(l, i, &p);
                if p.status == Status::Converged {
                    let (v, a) = predictor_rates(fb, (s2, c2), &j, opts.predictor);
                    prev.x[0][l] = p.theta3;
                    prev.x[1][l] = p.theta4;
                    prev.v[0][l] = v[0];
                    prev.v[1][l] = v[1];
                    prev.a[0][l] = a[0];
                    prev.a[1][l] = a[1];
                    prev.ok[l] = true;
                } else {
                    prev.ok[l] = false;
                }
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fourbar::options::{BatchOut, SweepOut};
    use crate::fourbar::{default_angles, validate_links, Method, Mode};
    use crate::solve::newton::NewtonOptions;

    /// The scalar Newton sweep of each row with libm's crank trigonometry (bit-identical to
    /// the NumPy reference), whatever the process-wide switch says.
    fn scalar(links: &[FourBar], t2: &[f64], opts: &SweepOptions) -> (Vec<f64>, Vec<f64>, Vec<i8>, Vec<u32>) {
        let trig: Vec<(f64, f64)> = t2.iter().map(|t| t.sin_cos()).collect();
        let n = t2.len();
        let mn = links.len() * n;
        let (mut a, mut b, mut s, mut k, mut r) =
            (vec![0.0; mn], vec![0.0; mn], vec![0i8; mn], vec![0u32; mn], vec![0.0; mn]);
        for (m, fb) in links.iter().enumerate() {
            let rg = m * n..(m + 1) * n;
            let row = SweepOut {
                theta3: &mut a[rg.clone()],
                theta4: &mut b[rg.clone()],
                status: &mut s[rg.clone()],
                nit: &mut k[rg.clone()],
                residual: &mut r[rg],
            };
            crate::fourbar::scalar::newton_sweep(fb, t2, &trig, None, opts, row, None, &Poll::new(&crate::Never))
                .unwrap();
        }
        (a, b, s, k)
    }

    fn lanes(links: &[FourBar], t2: &[f64], opts: &SweepOptions) -> (Vec<f64>, Vec<f64>, Vec<i8>, Vec<u32>) {
        let mn = links.len() * t2.len();
        let (mut a, mut b, mut s, mut k, mut r) =
            (vec![0.0; mn], vec![0.0; mn], vec![0i8; mn], vec![0u32; mn], vec![0.0; mn]);
        let out = BatchOut { theta3: &mut a, theta4: &mut b, status: &mut s, nit: &mut k, residual: &mut r };
        crate::fourbar::batch::sweep_groups(links, t2, opts, out, Some(1), &crate::Never, true).unwrap();
        (a, b, s, k)
    }

    /// Crank-rockers, double cranks, triple rockers (spans that cannot assemble), the
    /// parallelogram (change points), toggles on the sweep's grid, and xorshift-random ones.
    fn linkages() -> Vec<FourBar> {
        let mut raw = vec![
            6.0, 2.0, 5.0, 5.0, 100.0, 40.0, 120.0, 80.0, 2.0, 5.0, 2.5, 2.0, 6.0, 2.0, 6.0, 2.0, 2.0, 6.0, 5.0, 5.0,
            4.0, 1.0, 2.0, 3.0, 1.0, 1.0, 1.0, 1.0, 5.0, 3.0, 4.0, 4.0,
        ];
        let mut s = 0x9E37_79B9_7F4A_7C15u64;
        for _ in 0..4 * 61 {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            raw.push(0.2 + 5.0 * (s >> 11) as f64 / (1u64 << 53) as f64);
        }
        validate_links(&raw).unwrap()
    }

    #[test]
    fn lanes_agree_with_the_scalar_sweep_in_status_everywhere_and_to_1e12_rad() {
        let links = linkages();
        let mut t2 = default_angles(361);
        t2[17] = f64::NAN;
        t2[200] = f64::INFINITY;
        let (mut worst, mut nit_diffs, mut points) = (0.0f64, 0, 0);
        for mode in [Mode::Open, Mode::Crossed] {
            for predictor in [Predictor::Quadratic, Predictor::Tangent, Predictor::Previous] {
                for (tol, max_iter) in [(1e-9, 100), (1e-6, 100), (1e-13, 3)] {
                    let newton = NewtonOptions { tol, max_iter, ..NewtonOptions::default() };
                    let opts = SweepOptions { mode, newton, predictor, method: Method::Newton };
                    let (a, b, s, k) = scalar(&links, &t2, &opts);
                    let (x, y, u, m) = lanes(&links, &t2, &opts);
                    let bad_status = s.iter().zip(&u).filter(|(p, q)| p != q).count();
                    let bad_nit = k.iter().zip(&m).filter(|(p, q)| p != q).count();
                    assert_eq!(bad_status, 0, "{mode:?} {predictor:?} {tol}");
                    // the step count can differ by one where the last correction lies within
                    // rounding of tol (a point in ~10^4 at tol 1e-9, in ~10^3 at 1e-13)
                    let far = k.iter().zip(&m).filter(|(p, q)| p.abs_diff(**q) > 1).count();
                    assert!(far == 0 && bad_nit * 500 <= k.len(), "{mode:?} {predictor:?} {tol}: {bad_nit}");
                    nit_diffs += bad_nit;
                    points += k.len();
                    for i in 0..a.len() {
                        assert_eq!(a[i].is_nan(), x[i].is_nan());
                        if !a[i].is_nan() {
                            worst = worst.max(wrap_angle(a[i] - x[i]).abs()).max(wrap_angle(b[i] - y[i]).abs());
                        }
                    }
                }
            }
        }
        assert!(worst <= 1e-12, "worst {worst:e} rad");
        eprintln!("SIMD Newton vs scalar: worst {worst:e} rad, nit differs by 1 at {nit_diffs} of {points} points");
    }

    type Row = (Vec<f64>, Vec<f64>, Vec<i8>, Vec<u32>, Vec<f64>);

    fn out(x: &mut Row) -> SweepOut<'_> {
        let (theta3, theta4, status, nit, residual) = x;
        SweepOut { theta3, theta4, status, nit, residual }
    }

    #[test]
    fn single_sweep_agrees_with_the_scalar_sweep_in_status_everywhere_and_to_1e12_rad() {
        let links = linkages();
        let mut t2 = default_angles(361);
        t2[17] = f64::NAN;
        t2[200] = f64::INFINITY;
        let trig: Vec<(f64, f64)> = t2.iter().map(|t| t.sin_cos()).collect();
        let n = t2.len();
        let (mut worst, mut nit_diffs, mut points) = (0.0f64, 0, 0);
        for mode in [Mode::Open, Mode::Crossed] {
            for predictor in [Predictor::Quadratic, Predictor::Tangent, Predictor::Previous] {
                for guess in [None, Some([1.0, 2.0])] {
                    let opts =
                        SweepOptions { mode, newton: NewtonOptions::default(), predictor, method: Method::Newton };
                    for fb in &links {
                        let mut a: Row = (vec![0.0; n], vec![0.0; n], vec![0i8; n], vec![0u32; n], vec![0.0; n]);
                        let mut b = a.clone();
                        crate::fourbar::scalar::newton_sweep(
                            fb,
                            &t2,
                            &trig,
                            guess,
                            &opts,
                            out(&mut a),
                            None,
                            &Poll::new(&crate::Never),
                        )
                        .unwrap();
                        super::super::row::newton_row(
                            fb,
                            &t2,
                            &trig,
                            guess,
                            &opts,
                            out(&mut b),
                            None,
                            &Poll::new(&crate::Never),
                        )
                        .unwrap();
                        assert_eq!(a.2, b.2, "{mode:?} {predictor:?} {:?}", fb.lengths());
                        nit_diffs += a.3.iter().zip(&b.3).filter(|(p, q)| p != q).count();
                        points += n;
                        for i in 0..n {
                            assert_eq!(a.0[i].is_nan(), b.0[i].is_nan());
                            if !a.0[i].is_nan() {
                                worst =
                                    worst.max(wrap_angle(a.0[i] - b.0[i]).abs()).max(wrap_angle(a.1[i] - b.1[i]).abs());
                            }
                        }
                    }
                }
            }
        }
        assert!(worst <= 1e-12 && nit_diffs * 1000 <= points, "worst {worst:e} rad, nit {nit_diffs}");
        eprintln!("SIMD single sweep vs scalar: worst {worst:e} rad, nit differs at {nit_diffs} of {points} points");
    }
}
