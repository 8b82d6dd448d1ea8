//! Scene validation: names, coordinates, links, ground/input/output, and mobility (the
//! Gruebler count, then the rank of the constraint Jacobian at the drawn pose, so that a
//! special geometry that moves although the count says it cannot is reported).

// Inside: this file is the entry; `entries` (the entries by name), `geometry` (size,
// coincidence, the solving frame) and `mobility` (count and rank) are its kernels.
mod entries;
mod geometry;
mod mobility;

use entries::Names;
use geometry::Frame;

use crate::error::Error;
use crate::scene::model::{Scene, SceneSpec};

/// Most points (and most links) a scene may have: loading stays near linear in its size,
/// so this bounds a file's memory and time (a million points load in seconds).
const MAX_ENTRIES: usize = 1_000_000;

pub(crate) fn scene(spec: SceneSpec) -> Result<Scene, Error> {
    let sc = structure(spec)?;
    mobility::rank_check(&sc)?;
    Ok(sc)
}

/// Everything [`scene`] checks but the rank at the drawn pose: names, coordinates, links,
/// joints, inputs and the Gruebler count. A sketch (whose pose is not yet an assembly) is
/// checked by this before it is assembled.
pub(crate) fn structure(spec: SceneSpec) -> Result<Scene, Error> {
    let SceneSpec { points, links, ground, input, output, slots, prismatic, linear_input } = spec;
    if points.is_empty() {
        return Err(Error::scene("points", "the scene has no points"));
    }
    for (what, n) in [("points", points.len()), ("links", links.len())] {
        if n > MAX_ENTRIES {
            return Err(Error::scene(what, format!("{n} entries; a scene may have at most {MAX_ENTRIES}")));
        }
    }
    let (names, drawn): (Vec<String>, Vec<_>) = points.into_iter().unzip();
    let index = entries::points(&names, &drawn)?;
    let (link_index, parsed) = entries::links(&links, &index, names.len())?;
    let (pre, size) = geometry::measure(&parsed, &drawn, &names)?;

    let mut point_links = vec![Vec::new(); names.len()];
    for (k, l) in parsed.iter().enumerate() {
        for &p in &l.points {
            point_links[p].push(k);
        }
    }
    if let Some(p) = point_links.iter().position(|l| l.is_empty()) {
        return Err(Error::scene(format!("points.{}", names[p]), "is on no link"));
    }

    let at = Names {
        index: &index,
        link_index: &link_index,
        parsed: &parsed,
        drawn: &drawn,
        names: &names,
        point_links: &point_links,
        pre,
        size,
    };
    let ground = at.link_of("ground", &ground)?;
    let output = output.as_ref().map(|o| at.pivoted(ground, "output", o)).transpose()?;
    let (mut slot_list, prism_list) = at.joints(ground, &slots, &prismatic)?;
    let linear = entries::linear_input(&linear_input, &slot_list, &prism_list, &drawn)?;
    let input = match linear {
        None => Some(at.pivoted(ground, "input", &input)?),
        Some(_) => None,
    };
    mobility::count(parsed.len(), &point_links, slot_list.len(), prism_list.len())?;

    let Frame { scale, origin, xy, theta0, linear } =
        geometry::frame(size * pre, &drawn, input, linear, &mut slot_list, &prism_list);
    Ok(Scene {
        names,
        drawn,
        xy,
        origin,
        scale,
        links: parsed,
        point_links,
        ground,
        input,
        output,
        slots: slot_list,
        prismatic: prism_list,
        linear,
        theta0,
        limits: Vec::new(),
    })
}

impl Scene {
    /// Validates a scene: every name, coordinate and link, the ground, input and output
    /// links, and mobility (Gruebler count and a rank check at the drawn pose). The error
    /// names the entry and says why.
    pub fn new(spec: SceneSpec) -> Result<Scene, Error> {
        scene(spec)
    }
}
