//! Thread pools for work across independent problems (rayon), with the caller's
//! interrupt watched from the calling thread while the workers run.
//!
//! Without the `parallel` feature (targets with no threads: WebAssembly in a browser)
//! the same calls run sequentially on the calling thread, and [`prelude`] gives the
//! slices the `par_*` iterators of rayon as plain sequential ones, so the batches read
//! the same either way and give the same results.

use std::sync::atomic::AtomicBool;
#[cfg(feature = "parallel")]
use std::sync::{Arc, Mutex};

use crate::error::Error;
#[cfg(feature = "parallel")]
use crate::interrupt::watched;
use crate::interrupt::Interrupt;

/// rayon's parallel iterators (with the `parallel` feature), or sequential stand-ins with
/// the same names.
#[cfg(feature = "parallel")]
pub mod prelude {
    pub use rayon::prelude::*;
}

/// rayon's parallel iterators (with the `parallel` feature), or sequential stand-ins with
/// the same names.
#[cfg(not(feature = "parallel"))]
pub mod prelude {
    /// `par_iter` and `par_chunks` of a slice, as its sequential `iter` and `chunks`.
    pub trait ParallelSlice<T> {
        /// Sequential [`slice::iter`].
        fn par_iter(&self) -> std::slice::Iter<'_, T>;
        /// Sequential [`slice::chunks`].
        fn par_chunks(&self, n: usize) -> std::slice::Chunks<'_, T>;
    }

    impl<T> ParallelSlice<T> for [T] {
        fn par_iter(&self) -> std::slice::Iter<'_, T> {
            self.iter()
        }
        fn par_chunks(&self, n: usize) -> std::slice::Chunks<'_, T> {
            self.chunks(n)
        }
    }

    /// `par_chunks_mut` of a slice, as its sequential `chunks_mut`.
    pub trait ParallelSliceMut<T> {
        /// Sequential [`slice::chunks_mut`].
        fn par_chunks_mut(&mut self, n: usize) -> std::slice::ChunksMut<'_, T>;
    }

    impl<T> ParallelSliceMut<T> for [T] {
        fn par_chunks_mut(&mut self, n: usize) -> std::slice::ChunksMut<'_, T> {
            self.chunks_mut(n)
        }
    }
}

/// Work (points times Newton steps) below which a batch runs without a watching thread:
/// it ends in tens of milliseconds anyway, and starting a thread would cost more.
#[cfg(feature = "parallel")]
const WATCH_ABOVE: u128 = 1 << 22;

/// Runs `work` on the pool of `threads` threads with the caller's `interrupt` watched
/// from this thread when the work is large ([`watched`]); `work` polls the flag it gets.
#[cfg(feature = "parallel")]
pub fn run<T: Send>(
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

/// Runs `work` on the calling thread (no `parallel` feature: no threads to watch from);
/// `interrupt` is asked once before it starts.
#[cfg(not(feature = "parallel"))]
pub fn run<T: Send>(
    threads: Option<usize>,
    _size: u128,
    interrupt: &dyn Interrupt,
    work: impl FnOnce(&AtomicBool) -> Result<T, Error> + Send,
) -> Result<T, Error> {
    if interrupt.interrupted() {
        return Err(Error::Interrupted);
    }
    with_threads(threads, || work(&AtomicBool::new(false)))?
}

/// Pools by thread count, built once: starting threads costs more than a small batch.
#[cfg(feature = "parallel")]
static POOLS: Mutex<Vec<(usize, Arc<rayon::ThreadPool>)>> = Mutex::new(Vec::new());

#[cfg(feature = "parallel")]
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

/// Whether this thread is one of rayon's workers (work started here must not wait on a
/// watcher thread: it could wait for workers that are all waiting too).
pub fn in_worker() -> bool {
    #[cfg(feature = "parallel")]
    {
        rayon::current_thread_index().is_some()
    }
    #[cfg(not(feature = "parallel"))]
    {
        false
    }
}

/// Validates a thread count as the caller gives it: None (all cores) or an integer >= 1.
pub fn threads(n: Option<i64>) -> Result<Option<usize>, Error> {
    match n {
        None => Ok(None),
        Some(t) => usize::try_from(t)
            .ok()
            .filter(|&t| t >= 1)
            .map(Some)
            .ok_or_else(|| Error::invalid("threads", "must be >= 1 or None", t)),
    }
}

/// Runs `f` on a pool of `threads` threads (None: rayon's global pool, all cores).
#[cfg(feature = "parallel")]
pub fn with_threads<T: Send>(threads: Option<usize>, f: impl FnOnce() -> T + Send) -> Result<T, Error> {
    match threads {
        None => Ok(f()),
        Some(0) => Err(Error::invalid("threads", "must be >= 1 or None", 0)),
        Some(t) => Ok(pool(t)?.install(f)),
    }
}

/// Runs `f` on the calling thread (no `parallel` feature); the thread count is still
/// checked, so misuse is refused the same way.
#[cfg(not(feature = "parallel"))]
pub fn with_threads<T: Send>(threads: Option<usize>, f: impl FnOnce() -> T + Send) -> Result<T, Error> {
    match threads {
        Some(0) => Err(Error::invalid("threads", "must be >= 1 or None", 0)),
        _ => Ok(f()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zero_threads_is_refused() {
        assert!(with_threads(Some(0), || ()).unwrap_err().to_string().starts_with("threads "));
        assert_eq!(threads(None), Ok(None));
        assert_eq!(threads(Some(3)), Ok(Some(3)));
        for bad in [0, -2] {
            assert_eq!(threads(Some(bad)).unwrap_err().to_string(), format!("threads must be >= 1 or None, got {bad}"));
        }
        assert_eq!(with_threads(Some(1), || 3).unwrap(), 3);
    }
}
