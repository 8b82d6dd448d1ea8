//! Scenes from a sketch: [`assemble_sketch`] turns `lengths` and roughly drawn points into
//! the exact assembly nearest the sketch, refusing to pass a dead point on the way.

// Inside: this file is the entry; `given` parses the lengths, `rows` makes the conditions
// (each moving link's shape; the rule for sliders is there), `system` follows the sketch
// to the given lengths by Newton continuation.
mod given;
mod rows;
mod system;

use crate::error::Error;
use crate::interrupt::Interrupt;
use crate::scene::build::validate::structure;
use crate::scene::model::SceneSpec;
use crate::scene::vec2::Xy;
use given::Given;
pub use given::LengthSpec;
use rows::rows;
use system::System;

/// A sketch assembled: the exact pose and how far each point moved to reach it.
#[derive(Clone, Debug, PartialEq)]
pub struct Sketched {
    /// Exact coordinates, in the order of the spec's points (scene units).
    pub points: Vec<Xy>,
    /// Distance from each sketched point to its exact place (scene units; 0 for ground).
    pub moved: Vec<f64>,
}

/// Most moving points a sketch may have: it is assembled with dense matrices (cubic time;
/// about a tenth of a second per factorisation at this size).
pub const MAX_SKETCH_POINTS: usize = 500;

/// Assembles the sketch `spec` with `lengths`: each moving link's shape from its listed
/// distances (sides as sketched), slots and prismatic pairs placed by their listed
/// distances from their lines, ground and the sketched input held, and the sketch (an exact
/// assembly of its own lengths) followed while those lengths move to the given ones.
///
/// The rule for sliders, which distances alone cannot say: a slot's pin lies on its line
/// unless `lengths` gives its distance from it (`[pin, slot, e]`, on the side it is
/// sketched); a prismatic pair holds two points of its sliding link at given distances from
/// its guide's line (`[point, pair, d]`, exactly two such entries), or, with none given,
/// the sliding link's first two listed points on the line (a rod in its barrel).
///
/// Errors
/// name the entry: `lengths[k]` for an entry that is malformed or contradicts another,
/// `links.X` for a link whose lengths leave it non-rigid or cannot close, `slots.X` or
/// `prismatic.X` for a joint the lengths do not place; the spec itself is checked as
/// [`Scene::new`](crate::scene::Scene::new) checks it, except the rank at the (sketched) pose. `interrupt` is asked
/// once per continuation step (Ctrl-C from Python).
pub fn assemble_sketch(spec: SceneSpec, lengths: &[LengthSpec], interrupt: &dyn Interrupt) -> Result<Sketched, Error> {
    let sc = structure(spec)?;
    let fixed: Vec<bool> = sc.point_links.iter().map(|l| l.contains(&sc.ground)).collect();
    let moving = fixed.iter().filter(|f| !**f).count();
    if moving > MAX_SKETCH_POINTS {
        return Err(Error::scene(
            "lengths",
            format!("the sketch has {moving} moving points; a sketch may have at most {MAX_SKETCH_POINTS}"),
        ));
    }
    let given = Given::parse(&sc, &fixed, lengths)?;
    let rows = rows(&sc, &fixed, &given)?;
    let sys = System::new(&sc, &fixed, rows);
    if sys.rows_len != sys.n {
        // Gruebler's count is 1 (checked), so this is a link welded to ground or the like
        return Err(Error::scene(
            "mobility",
            format!(
                "the sketch has {} unknown coordinates but {} conditions; a one-degree-of-freedom scene with \
                 its input held has as many",
                sys.n, sys.rows_len
            ),
        ));
    }
    let x = sys.solve(&sc, interrupt)?;
    let mut points = sc.drawn.clone();
    let mut moved = vec![0.0; points.len()];
    for (p, c) in sys.col.iter().enumerate() {
        if let Some(c) = *c {
            let d = [x[c] - sc.xy[p][0], x[c + 1] - sc.xy[p][1]];
            points[p] = [sc.drawn[p][0] + sc.scale * d[0], sc.drawn[p][1] + sc.scale * d[1]];
            moved[p] = sc.scale * d[0].hypot(d[1]);
        }
    }
    Ok(Sketched { points, moved })
}

#[cfg(test)]
mod tests;
