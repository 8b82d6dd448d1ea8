//! A shard of an atlas: entries start..start + count of (topology, seed), as columns,
//! built in parallel; entry i depends on (seed, i) alone.

use super::descriptor::DESCRIPTOR;
use super::draw::draw;
use super::Topology;
use crate::error::{try_zeros, Error};
use crate::interrupt::Interrupt;
use crate::parallel::prelude::*;

/// Entries built between two looks at the interrupt.
const CHUNK: usize = 1024;

/// The columns of a shard (row-major where a row has several values).
#[derive(Clone, Debug, Default)]
pub struct Shard {
    /// count x [`Topology::params`] parameters.
    pub params: Vec<f64>,
    /// count x [`Topology::signs`] assembly signs (+1 or -1).
    pub signs: Vec<i8>,
    /// The input turns fully.
    pub full_turn: Vec<bool>,
    /// The smallest transmission sine over the curve.
    pub conditioning: Vec<f64>,
    /// count x [`DESCRIPTOR`] descriptors.
    pub descriptor: Vec<f32>,
}

/// Entries `start..start + count` of the atlas of `topology` drawn from `seed`.
pub fn build_shard(
    topology: Topology,
    seed: u64,
    start: u64,
    count: usize,
    interrupt: &dyn Interrupt,
) -> Result<Shard, Error> {
    let (np, ns) = (topology.params(), topology.signs());
    let what = |cols: usize| move || format!("an atlas shard of {count} x {cols}");
    let mut out = Shard {
        params: try_zeros(what(np), count * np)?,
        signs: try_zeros(what(ns), count * ns)?,
        full_turn: vec![false; count],
        conditioning: try_zeros(what(1), count)?,
        descriptor: try_zeros(what(DESCRIPTOR), count * DESCRIPTOR)?,
    };
    let mut done = 0;
    while done < count {
        if interrupt.interrupted() {
            return Err(Error::Interrupted);
        }
        let n = CHUNK.min(count - done);
        let entries: Vec<_> = (0..n as u64)
            .collect::<Vec<_>>()
            .par_iter()
            .map(|&i| draw(topology, seed, start + done as u64 + i))
            .collect();
        for (j, e) in entries.into_iter().enumerate() {
            let i = done + j;
            let e = e.ok_or_else(|| Error::invalid("topology", "must give linkages that assemble", topology.name()))?;
            out.params[i * np..(i + 1) * np].copy_from_slice(&e.params[..np]);
            for (k, s) in e.signs[..ns].iter().enumerate() {
                out.signs[i * ns + k] = *s as i8;
            }
            out.full_turn[i] = e.curve.closed;
            out.conditioning[i] = e.curve.conditioning;
            out.descriptor[i * DESCRIPTOR..(i + 1) * DESCRIPTOR].copy_from_slice(&e.descriptor);
        }
        done += n;
    }
    Ok(out)
}
