//! Atlases of normalised coupler curves for path synthesis: random linkages of a topology
//! drawn reproducibly from a seed ([`draw()`]), their coupler curves in closed form
//! ([`pose`], [`coupler_curve`]; the Stephenson III by the scene solver), a descriptor of
//! each curve invariant to translation, rotation, scale, start point and direction
//! ([`describe`]), a shard of entries built in parallel ([`build_shard`]), and the
//! placement of a candidate's curve onto a target ([`match_curve`]).
//!
//! Every entry is a function of (seed, index) alone, so an atlas is the same bit for bit
//! however its shards are cut or spread over workers.

mod chain;
mod curve;
mod descriptor;
mod draw;
mod matching;
mod scene_chain;
mod shape;
mod shard;

pub use chain::{pose, pose_names, Pose, MAX_POINTS};
pub use curve::{coupler_curve, Curve, COARSE, SAMPLES};
pub use descriptor::{describe, resample, DESCRIPTOR, HARMONICS, RESAMPLED};
pub use draw::{draw, Entry};
pub use matching::{match_curve, match_curves, match_many, Placement, Search, FRACTIONS};
pub use scene_chain::{stephenson3_spec, STEPHENSON3_POINTS};
pub use shard::{build_shard, Shard};

use crate::error::Error;

/// The linkages an atlas holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Topology {
    /// Ground O2 (0, 0) - O4 (1, 0); crank O2-A, coupler A-B with the tracer P on it,
    /// rocker O4-B. Parameters: r2, r3, r4 (crank, coupler, rocker over the ground), u, v
    /// (P = A + u (B - A) + v perp(B - A)); one assembly sign.
    FourBar,
    /// Crank O2-A of length 1 about (0, 0), coupler A-B, B sliding on the line y = e.
    /// Parameters: r3 (coupler over crank), e (offset), u, v; one assembly sign.
    SliderCrank,
    /// Watt II: the four-bar O2-A-B-O4 (as [`Topology::FourBar`]) whose rocker is a
    /// ternary link O4-B-C (C at r4c from O4, turned beta from O4-B) driving the second
    /// four-bar O4-C-D-O6 (O6 at (x6, y6)); the tracer P on the coupler C-D. Parameters:
    /// r2, r3, r4, r4c, beta, x6, y6, r5 (C-D), r6 (O6-D), u, v; two assembly signs.
    Watt2,
    /// Stephenson III: ground j3 (0, 0) - j7 (1, 0), the input crank j7-j6 on the ternary
    /// T2 {j4, j5, j6, P}, which two binaries (j1-j4, j2-j5) join to the ternary T1
    /// {j1, j2, j3} pivoted at j3: T1, T2 and the binaries form one Newton group, solved by
    /// the scene solver. Parameters: the drawn j6, j1, j2, j4, j5 and the tracer P (x, y
    /// each); no signs (the drawing is the assembly).
    Stephenson3,
}

impl Topology {
    /// Every topology, in the order of their codes.
    pub const ALL: [Topology; 4] = [Topology::FourBar, Topology::SliderCrank, Topology::Watt2, Topology::Stephenson3];

    /// The name used in files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Topology::FourBar => "four-bar",
            Topology::SliderCrank => "slider-crank",
            Topology::Watt2 => "watt2",
            Topology::Stephenson3 => "stephenson3",
        }
    }

    /// The topology named `name`, or an error naming `topology`.
    pub fn from_name(name: &str) -> Result<Topology, Error> {
        Topology::ALL.into_iter().find(|t| t.name() == name).ok_or_else(|| {
            Error::invalid("topology", "must be one of four-bar, slider-crank, watt2, stephenson3", name)
        })
    }

    /// Number of parameters.
    pub fn params(self) -> usize {
        match self {
            Topology::FourBar => 5,
            Topology::SliderCrank => 4,
            Topology::Watt2 => 11,
            Topology::Stephenson3 => 12,
        }
    }

    /// Number of assembly signs (one per dyad).
    pub fn signs(self) -> usize {
        match self {
            Topology::FourBar | Topology::SliderCrank => 1,
            Topology::Watt2 => 2,
            Topology::Stephenson3 => 0,
        }
    }
}

/// Most parameters of any topology.
pub const MAX_PARAMS: usize = 12;

#[cfg(test)]
mod tests;
