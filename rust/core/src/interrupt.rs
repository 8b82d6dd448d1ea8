//! Cooperative interruption of long kernel calls (Ctrl-C from Python): the caller passes
//! an [`Interrupt`]; the kernels count their work (Newton iterations, points) and ask it
//! once every [`CHECK_EVERY`] units, so an expensive check stays out of the hot loop.

use std::cell::Cell;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::Duration;

use crate::error::Error;

/// Asked periodically by long-running kernels whether to stop.
pub trait Interrupt: Sync {
    /// True when the computation should stop now (the kernel then returns
    /// [`Error::Interrupted`]).
    fn interrupted(&self) -> bool;
}

/// Never interrupts.
pub struct Never;

impl Interrupt for Never {
    #[inline]
    fn interrupted(&self) -> bool {
        false
    }
}

impl<F: Fn() -> bool + Sync> Interrupt for F {
    fn interrupted(&self) -> bool {
        self()
    }
}

/// Units of work (Newton iterations or points) between two questions to the [`Interrupt`].
pub const CHECK_EVERY: u32 = 4096;

/// A per-thread countdown in front of an [`Interrupt`]: [`Poll::tick`] is a decrement and
/// a branch, and asks the interrupt once every [`CHECK_EVERY`] ticks.
pub struct Poll<'a> {
    source: &'a dyn Interrupt,
    left: Cell<u32>,
}

impl<'a> Poll<'a> {
    /// A countdown asking `source`.
    pub fn new(source: &'a dyn Interrupt) -> Self {
        Poll { source, left: Cell::new(CHECK_EVERY) }
    }

    /// The interrupt this countdown asks (for work handed to other threads, which poll it
    /// through their own countdowns or a watcher).
    pub fn source(&self) -> &'a dyn Interrupt {
        self.source
    }

    /// Counts one unit of work; every [`CHECK_EVERY`] units, asks the interrupt.
    #[inline]
    pub fn tick(&self) -> Result<(), Error> {
        self.tick_n(1)
    }

    /// Counts `n` units of work at once (a block's): asks the interrupt where the
    /// countdown runs out within them.
    #[inline]
    pub fn tick_n(&self, n: usize) -> Result<(), Error> {
        let left = self.left.get() as usize;
        if left > n {
            self.left.set((left - n) as u32);
            return Ok(());
        }
        self.ask()
    }

    /// The rare part of [`Poll::tick`], out of line: the hot loops that tick keep only a
    /// decrement and a branch.
    #[cold]
    #[inline(never)]
    fn ask(&self) -> Result<(), Error> {
        self.left.set(CHECK_EVERY);
        if self.source.interrupted() {
            Err(Error::Interrupted)
        } else {
            Ok(())
        }
    }
}

/// How often the calling thread asks the interrupt while workers run.
const WATCH: Duration = Duration::from_millis(20);

/// Runs `work` on another thread while this thread asks `interrupt` every few
/// milliseconds: worker threads cannot take the caller's place (a signal handler, e.g.,
/// runs only on the main thread). `work` gets a flag to poll (set once interrupted) and
/// should return [`Error::Interrupted`] when it sees it.
pub fn watched<T: Send>(
    interrupt: &dyn Interrupt,
    work: impl FnOnce(&AtomicBool) -> Result<T, Error> + Send,
) -> Result<T, Error> {
    let stop = AtomicBool::new(false);
    let (done, finished) = mpsc::channel::<()>();
    std::thread::scope(|s| {
        let stop = &stop;
        let worker = s.spawn(move || {
            let out = work(stop);
            let _ = done.send(()); // the receiver outlives the scope: cannot fail
            out
        });
        while let Err(mpsc::RecvTimeoutError::Timeout) = finished.recv_timeout(WATCH) {
            if !stop.load(Ordering::Relaxed) && interrupt.interrupted() {
                stop.store(true, Ordering::Relaxed);
            }
        }
        let out = worker.join().unwrap_or_else(|p| std::panic::resume_unwind(p));
        if stop.load(Ordering::Relaxed) {
            return Err(Error::Interrupted);
        }
        out
    })
}

/// An [`Interrupt`] that reads a flag (what workers of [`watched`] poll).
pub struct Flag<'a>(pub &'a AtomicBool);

impl Interrupt for Flag<'_> {
    #[inline]
    fn interrupted(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicU32;

    #[test]
    fn poll_asks_once_every_check_every_ticks() {
        let asked = AtomicU32::new(0);
        let count = || {
            asked.fetch_add(1, Ordering::Relaxed);
            false
        };
        let p = Poll::new(&count);
        for _ in 0..3 * CHECK_EVERY {
            p.tick().unwrap();
        }
        assert_eq!(asked.load(Ordering::Relaxed), 3);
        let yes = || true;
        let p = Poll::new(&yes);
        let first_err = (1..=CHECK_EVERY).find(|_| p.tick().is_err());
        assert_eq!(first_err, Some(CHECK_EVERY));
    }

    #[test]
    fn watched_work_stops_when_interrupted() {
        let yes = || true;
        let out = watched(&yes, |stop| {
            while !stop.load(Ordering::Relaxed) {
                std::thread::yield_now();
            }
            Err::<(), _>(Error::Interrupted)
        });
        assert_eq!(out, Err(Error::Interrupted));
        assert_eq!(watched(&Never, |_| Ok(7)), Ok(7));
    }
}
