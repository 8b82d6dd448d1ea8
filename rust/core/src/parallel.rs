//! Thread pools for work across independent problems (rayon), with the caller's
//! interrupt watched from the calling thread while the workers run.

use std::sync::atomic::AtomicBool;
use std::sync::{Arc, Mutex};

use crate::error::Error;
use crate::interrupt::{watched, Interrupt};

/// Work (points times Newton steps) below which a batch runs without a watching thread:
/// it ends in tens of milliseconds anyway, and starting a thread would cost more.
const WATCH_ABOVE: u128 = 1 << 22;

/// Runs `work` on the pool of `threads` threads with the caller's `interrupt` watched
/// from this thread when the work is large ([`watched`]); `work` polls the flag it gets.
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
pub fn with_threads<T: Send>(threads: Option<usize>, f: impl FnOnce() -> T + Send) -> Result<T, Error> {
    match threads {
        None => Ok(f()),
        Some(0) => Err(Error::invalid("threads", "must be >= 1 or None", 0)),
        Some(t) => Ok(pool(t)?.install(f)),
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
