//! A linear input's stroke: the interval of displacements the drawn pose reaches, both ends
//! dead points. The motion is followed out from the drawn pose both ways over displacements
//! of up to [`REACH`] sizes of the drawing; each end is bracketed between the last value
//! reached and the first not reached, and the
//! bracket is narrowed by sweeps of [`REFINE`] values inside it until it is a few
//! rounding errors wide: the end is the last value reached, the dead point itself (SINGULAR
//! there, as an angle input's dead point is: its rates are unbounded).

use super::buffers::SceneSweepBuffers;
use super::options::SceneSweepOptions;
use crate::error::Error;
use crate::interrupt::Interrupt;
use crate::scene::build::Plan;
use crate::Status;

/// How far the probe looks each way, in sizes of the drawing.
const REACH: f64 = 4.0;
/// Values in the probe sweep.
const PROBE: usize = 801;
/// Values per refining sweep (each narrows a bracket about this many times).
const REFINE: usize = 33;
/// Refining sweeps per end at most.
const ROUNDS: usize = 12;

/// Statuses of a sweep of a plan at input values `s`.
struct Probe {
    status: Vec<i8>,
}

impl Probe {
    /// The value `k` is reached from the drawn pose: solved, or at a dead point (SINGULAR:
    /// the stroke's end itself, within rounding, where the rates are unbounded).
    fn reached(&self, k: usize) -> bool {
        self.status[k] == Status::Converged.code() || self.status[k] == Status::Singular.code()
    }
}

impl Plan {
    fn probe(&self, s: &[f64], opts: &SceneSweepOptions, interrupt: &dyn Interrupt) -> Result<Probe, Error> {
        let what = |_: usize| "stroke probe".to_string();
        let mut b = SceneSweepBuffers::named(self, s.len(), false, &what)?;
        self.sweep(s, opts, b.out(), interrupt)?;
        Ok(Probe { status: b.status })
    }

    /// The stroke `(lo, hi)` (lo <= 0 <= hi) of a plan with a linear input, for a drawing of
    /// extent `size` (scene units). Errors where the input is an angle.
    pub fn stroke(&self, size: f64, opts: &SceneSweepOptions, interrupt: &dyn Interrupt) -> Result<(f64, f64), Error> {
        if !self.linear {
            return Err(Error::scene("input", "a stroke is a linear input's (this input is an angle)"));
        }
        let reach = REACH * size;
        let s: Vec<f64> = (0..PROBE).map(|k| -reach + 2.0 * reach * k as f64 / (PROBE - 1) as f64).collect();
        let p = self.probe(&s, opts, interrupt)?;
        let mut ends = [0.0; 2];
        for (e, below) in ends.iter_mut().zip([true, false]) {
            let dir = if below { -1.0 } else { 1.0 };
            // values out from the drawn pose on this side, nearest first
            let mut side: Vec<usize> = (0..PROBE).filter(|&k| s[k] * dir > 0.0).collect();
            side.sort_by(|&a, &b| (s[a] * dir).total_cmp(&(s[b] * dir)));
            let stop = side.iter().position(|&k| !p.reached(k));
            let Some(stop) = stop else {
                *e = side.last().map_or(0.0, |&k| s[k]); // reached to the end of the probe
                continue;
            };
            let reached = if stop == 0 { 0.0 } else { s[side[stop - 1]] };
            // (the sweep's own estimate of the dead point is only as fine as its smallest
            // step: the bracket is the probe's values)
            *e = self.refine(reached, s[side[stop]], size, opts, interrupt)?;
        }
        Ok((ends[0], ends[1]))
    }

    /// Narrows the bracket (`reached`, `beyond`) of a stroke's end: the last value reached.
    fn refine(
        &self,
        mut reached: f64,
        mut beyond: f64,
        size: f64,
        opts: &SceneSweepOptions,
        interrupt: &dyn Interrupt,
    ) -> Result<f64, Error> {
        for _ in 0..ROUNDS {
            if (beyond - reached).abs() <= 8.0 * f64::EPSILON * size {
                break;
            }
            // nearest the drawn pose first: the sweep follows them in order from it
            let s: Vec<f64> = (0..=REFINE).map(|k| reached + (beyond - reached) * k as f64 / (REFINE as f64)).collect();
            let p = self.probe(&s, opts, interrupt)?;
            let stop = (1..s.len()).find(|&k| !p.reached(k)).unwrap_or(s.len() - 1);
            if !p.reached(stop - 1) {
                break; // the start of the bracket no longer solves: keep what we have
            }
            let (r, b) = (s[stop - 1], s[stop]);
            if r == reached && b == beyond {
                break;
            }
            reached = r;
            beyond = b;
        }
        Ok(reached)
    }
}
