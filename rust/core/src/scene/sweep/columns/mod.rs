//! The sweep of a plan with no group: each operation over a block of input values at a
//! time, on columns of coordinates, the rows of the outputs written once per block.

// Inside: `entry` runs the blocks, on `blocks` (one operation over a block) and `rows`
// (the outputs' rows); `frame` (the columns and their helpers) is their leaf.
mod blocks;
mod entry;
mod frame;
mod rows;

pub(crate) use entry::sweep;

#[cfg(test)]
mod tests;
