//! Many linkages at once: rayon-parallel over linkages (a sweep itself is sequential),
//! each row written straight into caller-owned (M, N) row-major output slices, with no
//! allocation per linkage.

use std::sync::atomic::AtomicBool;

use crate::parallel::prelude::*;

use super::model::{FourBar, Mode};
use super::options::{check_len, BatchOut, Method, Predictor, SweepOptions, SweepOut};
use super::row::{closed_form_trig, sin_cos_table, sweep_row};
use super::simd;
use crate::error::Error;
use crate::interrupt::{Flag, Interrupt, Poll};
use crate::parallel::run;

/// Validates an (M, 4) row-major array of lengths as [`FourBar::new`] does; errors name
/// the entry, e.g. `links[3, 1]`.
pub fn validate_links(links: &[f64]) -> Result<Vec<FourBar>, Error> {
    if !links.len().is_multiple_of(4) {
        return Err(Error::invalid("links", "must have shape (M, 4)", format!("{} values", links.len())));
    }
    links
        .chunks_exact(4)
        .enumerate()
        .map(|(i, r)| FourBar::validated([r[0], r[1], r[2], r[3]], |k| format!("links[{i}, {k}]")))
        .collect()
}

/// Sweeps every linkage over the same crank angles. A large batch is watched from the
/// calling thread, which asks `interrupt` every few milliseconds; interrupted, it
/// returns [`Error::Interrupted`].
pub fn sweep_batch(
    links: &[FourBar],
    theta2: &[f64],
    opts: &SweepOptions,
    out: BatchOut<'_>,
    threads: Option<usize>,
    interrupt: &dyn Interrupt,
) -> Result<(), Error> {
    let n = theta2.len();
    let mn = links.len() * n;
    check_len("theta3", out.theta3.len(), mn)?;
    check_len("theta4", out.theta4.len(), mn)?;
    check_len("status", out.status.len(), mn)?;
    check_len("nit", out.nit.len(), mn)?;
    check_len("residual", out.residual.len(), mn)?;
    if n == 0 {
        return Ok(());
    }
    let lock_step = opts.method == Method::Newton && opts.predictor != Predictor::ClosedForm && crate::simd::enabled();
    sweep_groups(links, theta2, opts, out, threads, interrupt, lock_step)
}

/// [`sweep_batch`] once the output lengths are checked and there is at least one angle:
/// rayon-parallel over rows, or with `lock_step` (Newton with continuation on the SIMD
/// path) over groups of [`simd::W`] linkages, solved in lock-step by the lane kernel (a
/// last group of fewer rows runs row by row).
pub(crate) fn sweep_groups(
    links: &[FourBar],
    theta2: &[f64],
    opts: &SweepOptions,
    out: BatchOut<'_>,
    threads: Option<usize>,
    interrupt: &dyn Interrupt,
    lock_step: bool,
) -> Result<(), Error> {
    let n = theta2.len();
    let mn = links.len() * n;
    let trig = sin_cos_table(theta2)?;
    let rows = if lock_step { simd::W } else { 1 };
    let g = rows * n;
    let size = mn as u128 * (u128::from(opts.newton.max_iter) + 1);
    // in lock-step, the interrupt is also asked between groups of W rows (and every few
    // thousand points of a last group, row by row)
    run(threads, size, interrupt, |stop| {
        let flag = Flag(stop);
        out.theta3
            .par_chunks_mut(g)
            .zip(out.theta4.par_chunks_mut(g))
            .zip(out.status.par_chunks_mut(g))
            .zip(out.nit.par_chunks_mut(g))
            .zip(out.residual.par_chunks_mut(g))
            .zip(links.par_chunks(rows))
            .try_for_each(|(((((t3, t4), st), nit), res), fbs)| {
                if lock_step && flag.interrupted() {
                    return Err(Error::Interrupted);
                }
                if lock_step && fbs.len() == simd::W {
                    return simd::batch::group(fbs, theta2, &trig, opts, t3, t4, st, nit, res, &Poll::new(&flag));
                }
                let rows = t3.chunks_mut(n).zip(t4.chunks_mut(n)).zip(st.chunks_mut(n));
                let rows = rows.zip(nit.chunks_mut(n)).zip(res.chunks_mut(n)).zip(fbs);
                for (((((theta3, theta4), status), nit), residual), fb) in rows {
                    let row = SweepOut { theta3, theta4, status, nit, residual };
                    sweep_row(fb, theta2, &trig, None, opts, row, None, &Poll::new(&flag))?;
                }
                Ok(())
            })
    })
}

/// Closed form of `mode` for every linkage at the same crank angles. The status array is
/// optional: callers that only want the angles skip its memory.
pub fn closed_form_batch(
    links: &[FourBar],
    theta2: &[f64],
    mode: Mode,
    singular: f64,
    theta3: &mut [f64],
    theta4: &mut [f64],
    status: Option<&mut [i8]>,
    threads: Option<usize>,
    interrupt: &dyn Interrupt,
) -> Result<(), Error> {
    let n = theta2.len();
    let mn = links.len() * n;
    check_len("theta3", theta3.len(), mn)?;
    check_len("theta4", theta4.len(), mn)?;
    if let Some(s) = &status {
        check_len("status", s.len(), mn)?;
    }
    if n == 0 {
        return Ok(());
    }
    let trig = sin_cos_table(theta2)?;
    let rows = theta3.par_chunks_mut(n).zip(theta4.par_chunks_mut(n)).zip(links.par_iter());
    // a row is checked as a whole: closed-form points cost nanoseconds
    let go = |stop: &AtomicBool| if Flag(stop).interrupted() { Err(Error::Interrupted) } else { Ok(()) };
    run(threads, mn as u128, interrupt, |stop| match status {
        Some(status) => rows.zip(status.par_chunks_mut(n)).try_for_each(|(((t3, t4), fb), st)| {
            go(stop)?;
            closed_form_trig(fb, theta2, &trig, mode, singular, t3, t4, Some(st));
            Ok(())
        }),
        // `{ rows }`: a temporary, so the sequential stand-in's `try_for_each(&mut self)` works too
        None => { rows }.try_for_each(|((t3, t4), fb)| {
            go(stop)?;
            closed_form_trig(fb, theta2, &trig, mode, singular, t3, t4, None);
            Ok(())
        }),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fourbar::{default_angles, sweep_into, Predictor};
    use crate::solve::newton::NewtonOptions;

    #[test]
    fn batch_rows_equal_single_sweeps_bit_for_bit_on_any_thread_count() {
        let raw = [6.0, 2.0, 5.0, 5.0, 100.0, 40.0, 120.0, 80.0, 2.0, 5.0, 2.5, 2.0];
        let links = validate_links(&raw).unwrap();
        let t2 = default_angles(361);
        let n = t2.len();
        let opts = SweepOptions {
            mode: Mode::Open,
            newton: NewtonOptions::default(),
            predictor: Predictor::Tangent,
            method: Method::Newton,
        };
        let run = |threads| {
            let mn = links.len() * n;
            let (mut a, mut b, mut s, mut k, mut r) =
                (vec![0.0; mn], vec![0.0; mn], vec![0i8; mn], vec![0u32; mn], vec![0.0; mn]);
            let out = BatchOut { theta3: &mut a, theta4: &mut b, status: &mut s, nit: &mut k, residual: &mut r };
            sweep_batch(&links, &t2, &opts, out, threads, &crate::Never).unwrap();
            (a, s, k)
        };
        let (a1, s1, k1) = run(Some(1));
        let (a2, s2, k2) = run(Some(2));
        assert_eq!(s1, s2);
        assert_eq!(k1, k2);
        assert!(a1.iter().zip(&a2).all(|(x, y)| x.to_bits() == y.to_bits()));
        for (m, fb) in links.iter().enumerate() {
            let (mut a, mut b, mut s, mut k, mut r) =
                (vec![0.0; n], vec![0.0; n], vec![0i8; n], vec![0u32; n], vec![0.0; n]);
            let out = SweepOut { theta3: &mut a, theta4: &mut b, status: &mut s, nit: &mut k, residual: &mut r };
            sweep_into(fb, &t2, None, &opts, out, None, &crate::Never).unwrap();
            assert_eq!(&s1[m * n..(m + 1) * n], &s[..]);
            assert!(a1[m * n..(m + 1) * n].iter().zip(&a).all(|(x, y)| x.to_bits() == y.to_bits()));
        }
    }

    #[test]
    fn invalid_links_name_the_entry() {
        let e = validate_links(&[6.0, 2.0, 5.0, 5.0, 1.0, 1.0, -1.0, 1.0]).unwrap_err().to_string();
        assert!(e.starts_with("links[1, 2] "), "{e}");
        assert!(validate_links(&[1.0, 2.0, 3.0]).is_err());
    }
}
