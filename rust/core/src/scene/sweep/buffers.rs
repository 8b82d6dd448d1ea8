//! The output buffers of a scene sweep, owned: allocated once for a plan and N input
//! values (fallibly), lent to [`Plan::sweep`] as a [`SceneSweepOut`], then handed on.

use super::options::SceneSweepOut;
use crate::error::{try_zeros, Error, Zeroed};
use crate::scene::build::Plan;

/// (N, P, 2) point rates and (N, L) link rates.
pub type Rates = (Vec<f64>, Vec<f64>);

/// A sweep's 11 outputs over N input values with P reported points, L reported link
/// angles and S steps (row-major; see [`SceneSweepOut`] for what each holds).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SceneSweepBuffers {
    /// (N, P, 2) positions.
    pub points: Vec<f64>,
    /// (N, L) link angles.
    pub angles: Vec<f64>,
    /// (N,) statuses.
    pub status: Vec<i8>,
    /// (N,) Newton steps.
    pub nit: Vec<u32>,
    /// (N,) signed conditioning.
    pub det: Vec<f64>,
    /// (N,) dead points that stop the motion.
    pub limit: Vec<f64>,
    /// (N, S) each step's status.
    pub step_status: Vec<i8>,
    /// (N, S) each step's signed conditioning.
    pub step_det: Vec<f64>,
    /// (N, P) each reported point's status.
    pub point_status: Vec<i8>,
    /// (N, P, 2) velocities and (N, L) angular velocities, when asked for.
    pub velocity: Option<Rates>,
    /// (N, P, 2) accelerations and (N, L) angular accelerations, when asked for.
    pub acceleration: Option<Rates>,
}

impl SceneSweepBuffers {
    /// Zeroed buffers for a sweep of `plan` over `n` values, with velocities and
    /// accelerations when `rates`; an [`Error::Allocation`] naming "scene sweep outputs"
    /// when memory is short.
    pub fn new(plan: &Plan, n: usize, rates: bool) -> Result<Self, Error> {
        Self::named(plan, n, rates, &|len| format!("scene sweep outputs of {len} values"))
    }

    /// [`SceneSweepBuffers::new`] naming a failed allocation `what(len)`.
    pub fn named(plan: &Plan, n: usize, rates: bool, what: &dyn Fn(usize) -> String) -> Result<Self, Error> {
        let (np, nl, ns) = (plan.points().len(), plan.links().len(), plan.steps().len());
        let too_big = || Error::Allocation { what: what(usize::MAX), bytes: u128::MAX };
        let npn = n.checked_mul(2 * np).ok_or_else(too_big)?;
        let nln = n.checked_mul(nl).ok_or_else(too_big)?;
        let nsn = n.checked_mul(ns).ok_or_else(too_big)?;
        fn zeros<T: Zeroed>(len: usize, what: &dyn Fn(usize) -> String) -> Result<Vec<T>, Error> {
            try_zeros(|| what(len), len)
        }
        let rate = || -> Result<Option<Rates>, Error> {
            Ok(if rates { Some((zeros(npn, what)?, zeros(nln, what)?)) } else { None })
        };
        Ok(Self {
            points: zeros(npn, what)?,
            angles: zeros(nln, what)?,
            status: zeros(n, what)?,
            nit: zeros(n, what)?,
            det: zeros(n, what)?,
            limit: zeros(n, what)?,
            step_status: zeros(nsn, what)?,
            step_det: zeros(nsn, what)?,
            point_status: zeros(npn / 2, what)?,
            velocity: rate()?,
            acceleration: rate()?,
        })
    }

    /// The buffers lent to a sweep.
    pub fn out(&mut self) -> SceneSweepOut<'_> {
        SceneSweepOut {
            points: &mut self.points,
            angles: &mut self.angles,
            status: &mut self.status,
            nit: &mut self.nit,
            det: &mut self.det,
            limit: &mut self.limit,
            step_status: &mut self.step_status,
            step_det: &mut self.step_det,
            point_status: &mut self.point_status,
            velocity: self.velocity.as_mut().map(|(v, w)| (&mut v[..], &mut w[..])),
            acceleration: self.acceleration.as_mut().map(|(v, w)| (&mut v[..], &mut w[..])),
        }
    }

    /// The real-valued outputs in a fixed order (points, angles, det, limit, step_det,
    /// then the rates given): for comparing two sweeps.
    pub fn reals(&self) -> Vec<&[f64]> {
        let mut v: Vec<&[f64]> = vec![&self.points, &self.angles, &self.det, &self.limit, &self.step_det];
        for (a, b) in self.velocity.iter().chain(&self.acceleration) {
            v.push(a);
            v.push(b);
        }
        v
    }
}
