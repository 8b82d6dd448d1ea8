//! Many linkages at once: rayon-parallel over linkages (a sweep itself is sequential),
//! each row written straight into caller-owned (M, N) row-major output slices, with no
//! allocation per linkage.

use std::sync::atomic::AtomicBool;
use std::sync::{Arc, Mutex};

use rayon::prelude::*;

use crate::arrays::closed_form_trig;
use crate::error::Error;
use crate::fourbar::{FourBar, Mode};
use crate::interrupt::{watched, Flag, Interrupt, Poll};
use crate::sweep::{sin_cos, sweep_unchecked, SweepOptions, SweepOut};

/// (M, N) row-major outputs of a batch sweep.
pub struct BatchOut<'a> {
    pub theta3: &'a mut [f64],
    pub theta4: &'a mut [f64],
    pub status: &'a mut [i8],
    pub nit: &'a mut [u32],
    pub residual: &'a mut [f64],
}

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

/// Work (points times Newton steps) below which a batch runs without a watching thread:
/// it ends in tens of milliseconds anyway, and starting a thread would cost more.
const WATCH_ABOVE: u128 = 1 << 22;

/// Runs `work` on the pool with the caller's `interrupt` watched from this thread when
/// the work is large ([`watched`]); `work` polls the flag it gets.
pub(crate) fn run<T: Send>(
    threads: Option<usize>,
    size: u128,
    interrupt: &dyn Interrupt,
    work: impl FnOnce(&AtomicBool) -> Result<T, Error> + Send,
) -> Result<T, Error> {
    if size < WATCH_ABOVE {
        return with_threads(threads, || work(&AtomicBool::new(false)))?;
    }
    watched(interrupt, |stop| with_threads(threads, || work(stop))?)
}

/// Pools by thread count, built once: starting threads costs more than a small batch.
static POOLS: Mutex<Vec<(usize, Arc<rayon::ThreadPool>)>> = Mutex::new(Vec::new());

fn pool(threads: usize) -> Result<Arc<rayon::ThreadPool>, Error> {
    let mut pools = POOLS.lock().unwrap_or_else(|e| e.into_inner());
    if let Some((_, p)) = pools.iter().find(|(t, _)| *t == threads) {
        return Ok(p.clone());
    }
    let p = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| Error::invalid("threads", "could not start a thread pool", e))?;
    let p = Arc::new(p);
    pools.push((threads, p.clone()));
    Ok(p)
}

/// Runs `f` on a pool of `threads` threads (None: rayon's global pool, all cores).
pub fn with_threads<T: Send>(threads: Option<usize>, f: impl FnOnce() -> T + Send) -> Result<T, Error> {
    match threads {
        None => Ok(f()),
        Some(0) => Err(Error::invalid("threads", "must be >= 1 or None", 0)),
        Some(t) => Ok(pool(t)?.install(f)),
    }
}

fn check(name: &str, got: usize, expected: usize) -> Result<(), Error> {
    if got == expected {
        Ok(())
    } else {
        Err(Error::Shape { name: name.into(), got, expected })
    }
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
    check("theta3", out.theta3.len(), mn)?;
    check("theta4", out.theta4.len(), mn)?;
    check("status", out.status.len(), mn)?;
    check("nit", out.nit.len(), mn)?;
    check("residual", out.residual.len(), mn)?;
    if n == 0 {
        return Ok(());
    }
    if opts.method == crate::sweep::Method::Newton && crate::simd::enabled() {
        return crate::simd::newton::sweep_batch(links, theta2, opts, out, threads, interrupt);
    }
    let trig = sin_cos(theta2)?;
    let size = mn as u128 * (u128::from(opts.newton.max_iter) + 1);
    run(threads, size, interrupt, |stop| {
        out.theta3
            .par_chunks_mut(n)
            .zip(out.theta4.par_chunks_mut(n))
            .zip(out.status.par_chunks_mut(n))
            .zip(out.nit.par_chunks_mut(n))
            .zip(out.residual.par_chunks_mut(n))
            .zip(links.par_iter())
            .try_for_each(|(((((theta3, theta4), status), nit), residual), fb)| {
                let row = SweepOut { theta3, theta4, status, nit, residual };
                let flag = Flag(stop);
                sweep_unchecked(fb, theta2, &trig, None, opts, row, None, &Poll::new(&flag))
            })
    })
}

/// Closed form of `mode` for every linkage at the same crank angles. The status array is
/// optional: callers that only want the angles skip its memory.
#[allow(clippy::too_many_arguments)]
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
    check("theta3", theta3.len(), mn)?;
    check("theta4", theta4.len(), mn)?;
    if let Some(s) = &status {
        check("status", s.len(), mn)?;
    }
    if n == 0 {
        return Ok(());
    }
    let trig = sin_cos(theta2)?;
    let rows = theta3.par_chunks_mut(n).zip(theta4.par_chunks_mut(n)).zip(links.par_iter());
    // a row is checked as a whole: closed-form points cost nanoseconds
    let go = |stop: &AtomicBool| if Flag(stop).interrupted() { Err(Error::Interrupted) } else { Ok(()) };
    run(threads, mn as u128, interrupt, |stop| match status {
        Some(status) => rows.zip(status.par_chunks_mut(n)).try_for_each(|(((t3, t4), fb), st)| {
            go(stop)?;
            closed_form_trig(fb, theta2, &trig, mode, singular, t3, t4, Some(st));
            Ok(())
        }),
        None => rows.try_for_each(|((t3, t4), fb)| {
            go(stop)?;
            closed_form_trig(fb, theta2, &trig, mode, singular, t3, t4, None);
            Ok(())
        }),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::newton::NewtonOptions;
    use crate::sweep::{default_angles, sweep_into, Predictor};

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
            method: crate::sweep::Method::Newton,
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
        assert!(with_threads(Some(0), || ()).is_err());
    }
}
