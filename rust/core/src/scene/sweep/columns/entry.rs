//! The sweep of a plan with no group (dyads, sliders' closed forms, rigid carries and the
//! input): nothing carries over from one input value to the next, so each operation runs
//! over a block of values at a time, on columns of coordinates (tight loops, no per-value
//! dispatch), and the rows of the outputs are written once per block. Every operation is
//! solved on its drawn side with the closed forms the continuation calls, so a
//! certified column sweep gives that path's numbers (the input's sin and cos excepted:
//! the polynomial ones, within 2 ulp, where the SIMD kernels are on).

// the column loops index several arrays (and an offset into each) by the same angle
#![allow(clippy::needless_range_loop)]

use super::blocks::{carry_block, dyad_block, input_block, rrp_fixed_line_block, slider_block, slider_rates_block};
use super::frame::{note, Columns, Scratch, B, OK};
use super::rows::write_block;
use crate::error::Error;
use crate::interrupt::Poll;
use crate::scene::build::Plan;
use crate::scene::ops::Op;
use crate::scene::sweep::options::{SceneSweepOptions, SceneSweepOut};
use crate::scene::vec2::unit;

/// The column sweep of `plan` over `theta` into `out`, compiled for AVX2 where the SIMD
/// kernels are on (the same operations on 4 lanes, without fused multiply-adds: the same
/// numbers as the baseline build).
pub(crate) fn sweep(
    plan: &Plan,
    theta: &[f64],
    opts: &SceneSweepOptions,
    out: &mut SceneSweepOut<'_>,
    poll: &Poll<'_>,
) -> Result<(), Error> {
    #[cfg(target_arch = "x86_64")]
    if crate::simd::enabled() {
        // SAFETY: the SIMD kernels are on only where the CPU has AVX2 (and FMA).
        return unsafe { sweep_avx2(plan, theta, opts, out, poll) };
    }
    sweep_body(plan, theta, opts, out, poll)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn sweep_avx2(
    plan: &Plan,
    theta: &[f64],
    opts: &SceneSweepOptions,
    out: &mut SceneSweepOut<'_>,
    poll: &Poll<'_>,
) -> Result<(), Error> {
    sweep_body(plan, theta, opts, out, poll)
}

#[inline(always)]
fn sweep_body(
    plan: &Plan,
    theta: &[f64],
    opts: &SceneSweepOptions,
    out: &mut SceneSweepOut<'_>,
    poll: &Poll<'_>,
) -> Result<(), Error> {
    let np = plan.npoints;
    // velocities and accelerations go together: both come with `omega`
    let vel = opts.omega.is_some();
    let nv = if vel { np * B } else { 0 };
    let ns = plan.steps.len();
    // the block's columns and the steps' conditioning and statuses in two allocations
    let mut reals = vec![0.0; 2 * np * B + 4 * nv + ns * B];
    let mut codes = vec![OK; np * B + ns * B];
    let (cols, sdet) = reals.split_at_mut(2 * np * B + 4 * nv);
    let (st, sst) = codes.split_at_mut(np * B);
    sdet.fill(1.0);
    let mut c = Columns::carve(cols, st, np * B, nv);
    for &(p, xy) in &plan.fixed {
        c.x[p * B..(p + 1) * B].fill(xy[0]);
        c.y[p * B..(p + 1) * B].fill(xy[1]);
    }
    // the step an operation opens (none: a carry), and whether a point is fixed in ground
    let step_of = |i: usize| plan.step_op.iter().position(|&o| o == i);
    let fixed = |p: usize| plan.fixed.iter().any(|&(q, _)| q == p);
    let angle = plan.ops.iter().any(|o| matches!(o, Op::Input { .. }));
    let mut scratch =
        vel.then(|| Scratch { pos: vec![[0.0; 2]; np], vel: vec![[0.0; 2]; np], acc: vec![[0.0; 2]; np] });
    // the conditioning and status of an operation that opens no step (a carry)
    let (mut cdet, mut cst) = ([1.0; B], [OK; B]);
    let mut first_bad = [OK; B];
    let mut trig = [(0.0, 1.0); B];
    let mut sv = [0.0; B];
    for (b, block) in theta.chunks(B).enumerate() {
        poll.tick_n(block.len())?;
        let m = block.len();
        let k0 = b * B;
        first_bad[..m].fill(OK);
        if angle {
            crate::simd::sin_cos_block(block, &mut trig[..m]);
        }
        if plan.linear {
            // the fused guide reads the displacement in the solving frame
            for j in 0..m {
                sv[j] = block[j] / plan.scale;
            }
        }
        for (i, op) in plan.ops.iter().enumerate() {
            match op {
                Op::Input { q, lam, mu } => {
                    input_block(plan.pivot, (*q, *lam, *mu), &mut c, &trig, block, vel);
                    note(&mut first_bad[..m], &c.st[q * B..q * B + m]);
                }
                Op::Carry { q, a, b: bb, m: ratio } => {
                    carry_block((*q, *a, *bb), *ratio, &mut c, m, vel);
                    note(&mut first_bad[..m], &c.st[q * B..q * B + m]);
                }
                Op::Dyad(d) => {
                    let s = step_of(i).expect("a dyad opens a step");
                    dyad_block(d, &mut c, m, opts.closed_form_singular(), vel, &mut sdet[s * B..], &mut sst[s * B..]);
                    note(&mut first_bad[..m], &sst[s * B..s * B + m]);
                }
                Op::Group(_) => unreachable!("the column sweep runs plans with no group"),
                op => {
                    let (det, st) = match step_of(i) {
                        None => (&mut cdet[..], &mut cst[..]),
                        Some(s) => (&mut sdet[s * B..], &mut sst[s * B..]),
                    };
                    let sv = if plan.linear { &sv[..m] } else { &block[..m] };
                    let singular = opts.closed_form_singular();
                    match (scratch.as_mut(), op) {
                        // a slot on a line fixed in ground (a slider-crank's): the line once
                        (None, Op::Rrp(r)) if r.line.inputs().iter().all(|&p| fixed(p)) => {
                            let l = &r.line;
                            let (p, d) = l.place(c.point(l.base, 0), c.point(l.a, 0), c.point(l.b, 0));
                            rrp_fixed_line_block(r, p, unit(d), &mut c, m, singular, det, st);
                        }
                        // (the inputs found here, once a block: most plans have no such op)
                        (None, _) => slider_block(op, &op.inputs(), &mut c, sv, singular, det, st),
                        (Some(k), _) => slider_rates_block(op, &op.inputs(), &mut c, sv, singular, k, det, st),
                    }
                    note(&mut first_bad[..m], &st[..m]);
                }
            }
        }
        write_block(plan, &c, sdet, sst, &first_bad, k0, m, opts, out);
    }
    Ok(())
}
