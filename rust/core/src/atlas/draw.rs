//! Random linkages of a topology, each a function of (seed, index) alone: a SplitMix64
//! stream keyed by both, redrawn until the linkage has a coupler curve with extent.
//!
//! The ranges cover every Grashof and Barker class of the four-bar: link ratios
//! log-uniform in [1/5, 5] against the ground, the coupler point anywhere within a plate
//! three coupler lengths wide, both assemblies.

use std::f64::consts::TAU;

use super::curve::{coupler_curve, Curve, SAMPLES};
use super::descriptor::{describe, DESCRIPTOR};
use super::{Topology, MAX_PARAMS};
use crate::rng::SplitMix64 as Rng;

/// Draws tried for one entry before it is given up (never met in practice: about half
/// of all draws assemble somewhere).
const MAX_DRAWS: u32 = 10_000;

/// One atlas entry.
#[derive(Clone, Debug)]
pub struct Entry {
    /// The parameters ([`Topology`] says which); unused ones are NaN.
    pub params: [f64; MAX_PARAMS],
    /// The assembly signs (+1 or -1); unused ones are 0.
    pub signs: [f64; 2],
    /// Its coupler curve.
    pub curve: Curve,
    /// The curve's descriptor.
    pub descriptor: [f32; DESCRIPTOR],
    /// How many draws it took.
    pub draws: u32,
}

/// Uniform in [lo, hi).
fn uniform(r: &mut Rng, lo: f64, hi: f64) -> f64 {
    lo + (hi - lo) * r.uniform()
}

fn log_uniform(r: &mut Rng, lo: f64, hi: f64) -> f64 {
    uniform(r, lo.ln(), hi.ln()).exp()
}

fn sign(r: &mut Rng) -> f64 {
    if r.next_u64() >> 63 == 0 {
        1.0
    } else {
        -1.0
    }
}

/// Entry `index` of the atlas of `topology` drawn from `seed`; None only if
/// 10 000 draws all failed.
pub fn draw(topology: Topology, seed: u64, index: u64) -> Option<Entry> {
    let mut rng = Rng(seed ^ Rng(index ^ 0xD1B5_4A32_D192_ED03).next_u64());
    for draws in 1..=MAX_DRAWS {
        let mut params = [f64::NAN; MAX_PARAMS];
        let mut signs = [0.0; 2];
        let ratio = |r: &mut Rng| log_uniform(r, 0.2, 5.0);
        match topology {
            Topology::FourBar => {
                for slot in params.iter_mut().take(3) {
                    *slot = ratio(&mut rng);
                }
                params[3] = uniform(&mut rng, -1.0, 2.0);
                params[4] = uniform(&mut rng, -1.5, 1.5);
                signs[0] = sign(&mut rng);
            }
            Topology::SliderCrank => {
                params[0] = log_uniform(&mut rng, 1.05, 6.0);
                params[1] = uniform(&mut rng, -1.5, 1.5);
                params[2] = uniform(&mut rng, -1.0, 2.0);
                params[3] = uniform(&mut rng, -1.5, 1.5);
                signs[0] = sign(&mut rng);
            }
            Topology::Watt2 => {
                for slot in params.iter_mut().take(4) {
                    *slot = ratio(&mut rng);
                }
                params[4] = uniform(&mut rng, 0.0, TAU);
                params[5] = uniform(&mut rng, -1.0, 3.0);
                params[6] = uniform(&mut rng, -2.0, 2.0);
                params[7] = ratio(&mut rng);
                params[8] = ratio(&mut rng);
                params[9] = uniform(&mut rng, -1.0, 2.0);
                params[10] = uniform(&mut rng, -1.5, 1.5);
                signs = [sign(&mut rng), sign(&mut rng)];
            }
            Topology::Stephenson3 => {
                // the crank tip near its pivot j7 (1, 0), the other points on a plate
                let (r, phi) = (log_uniform(&mut rng, 0.15, 0.8), uniform(&mut rng, 0.0, TAU));
                params[0] = 1.0 + r * phi.cos();
                params[1] = r * phi.sin();
                for k in 1..6 {
                    params[2 * k] = uniform(&mut rng, -1.0, 2.5);
                    params[2 * k + 1] = uniform(&mut rng, -1.5, 2.0);
                }
            }
        }
        let n = topology.params();
        let Some(curve) = coupler_curve(topology, &params[..n], &signs, SAMPLES) else {
            continue;
        };
        let mut descriptor = [0.0f32; DESCRIPTOR];
        if describe(&curve.points, curve.closed, &mut descriptor) {
            return Some(Entry { params, signs, curve, descriptor, draws });
        }
    }
    None
}
