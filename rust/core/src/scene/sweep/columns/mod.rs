//! The sweep of a plan with no group (dyads, sliders' closed forms, rigid carries and the
//! input): nothing carries over from one input value to the next, so each operation runs
//! over a block of values at a time, on columns of coordinates (tight loops, no per-value
//! dispatch), and the rows of the outputs are written once per block.
//!
//! Inside: `entry` runs the blocks, on `blocks` (one operation over a block) and `rows`
//! (the outputs' rows); `frame` (the columns and their helpers) is their leaf.

mod blocks;
mod entry;
mod frame;
mod rows;

pub(crate) use entry::sweep;

#[cfg(test)]
mod tests;
