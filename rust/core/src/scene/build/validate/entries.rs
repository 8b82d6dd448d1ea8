//! The scene's entries by name: points, links, the ground, the input and output links,
//! slots and prismatic pairs and a linear input, each checked against the others; the
//! error names the entry and says why.

use std::collections::HashMap;

use super::geometry::COINCIDENT;
use crate::error::Error;
use crate::scene::input::{Linear, LinearKind, Pivoted};
use crate::scene::model::{Link, Prismatic, PrismaticSpec, Slot, SlotSpec};
use crate::scene::vec2::{sub, Xy};

/// Indices by name.
pub(super) type Index<'a> = HashMap<&'a str, usize>;

/// The points by name (`names` and `drawn`: the spec's points taken apart, nothing copied).
/// Names must be distinct and coordinates finite: the error names the first point, in the
/// order given, that breaks either.
pub(super) fn points<'a>(names: &'a [String], drawn: &[Xy]) -> Result<Index<'a>, Error> {
    let mut index: Index<'_> = HashMap::with_capacity(names.len());
    for (i, (name, xy)) in names.iter().zip(drawn).enumerate() {
        if index.insert(name.as_str(), i).is_some() {
            return Err(Error::scene(format!("points.{name}"), "is given twice"));
        }
        if !xy.iter().all(|v| v.is_finite()) {
            return Err(Error::scene(format!("points.{name}"), format!("coordinates must be finite, got {xy:?}")));
        }
    }
    Ok(index)
}

/// The links by name and as lists of point indices.
pub(super) fn links<'s>(
    links: &'s [(String, Vec<String>)],
    index: &HashMap<&str, usize>,
    npoints: usize,
) -> Result<(Index<'s>, Vec<Link>), Error> {
    if links.is_empty() {
        return Err(Error::scene("links", "the scene has no links"));
    }
    let mut link_index: HashMap<&str, usize> = HashMap::with_capacity(links.len());
    let mut parsed = Vec::with_capacity(links.len());
    // the link (plus one) that last listed each point: a repeat within a link in O(1)
    let mut listed_by = vec![0usize; npoints];
    for (k, (name, pts)) in links.iter().enumerate() {
        let entry = format!("links.{name}");
        if link_index.insert(name.as_str(), k).is_some() {
            return Err(Error::scene(entry, "is given twice"));
        }
        if pts.len() < 2 {
            return Err(Error::scene(entry, format!("a link needs at least 2 points, got {}", pts.len())));
        }
        let mut idx = Vec::with_capacity(pts.len());
        for p in pts {
            let &i = index.get(p.as_str()).ok_or_else(|| Error::scene(&entry, format!("unknown point {p:?}")))?;
            if listed_by[i] == k + 1 {
                return Err(Error::scene(&entry, format!("lists point {p:?} twice")));
            }
            listed_by[i] = k + 1;
            idx.push(i);
        }
        parsed.push(Link { name: name.clone(), points: idx });
    }
    Ok((link_index, parsed))
}

/// What the entries that name points and links are checked against.
pub(super) struct Names<'a> {
    pub(super) index: &'a HashMap<&'a str, usize>,
    pub(super) link_index: &'a HashMap<&'a str, usize>,
    pub(super) parsed: &'a [Link],
    pub(super) drawn: &'a [Xy],
    pub(super) names: &'a [String],
    pub(super) point_links: &'a [Vec<usize>],
    /// The power of two the drawing is measured in, and its size in those units.
    pub(super) pre: f64,
    pub(super) size: f64,
}

impl Names<'_> {
    pub(super) fn link_of(&self, entry: &str, name: &str) -> Result<usize, Error> {
        self.link_index.get(name).copied().ok_or_else(|| Error::scene(entry, format!("{name:?} is not a link")))
    }

    fn point_of(&self, entry: &str, name: &str) -> Result<usize, Error> {
        self.index.get(name).copied().ok_or_else(|| Error::scene(entry, format!("unknown point {name:?}")))
    }

    /// An input or output link pinned to ground at `pivot`, with its tip.
    pub(super) fn pivoted(
        &self,
        ground: usize,
        what: &str,
        (link, pivot): &(String, String),
    ) -> Result<Pivoted, Error> {
        let parsed = self.parsed;
        let l = self.link_of(&format!("{what}.link"), link)?;
        if l == ground {
            return Err(Error::scene(format!("{what}.link"), format!("{link:?} is the ground link")));
        }
        let entry = format!("{what}.pivot");
        let &p =
            self.index.get(pivot.as_str()).ok_or_else(|| Error::scene(&entry, format!("unknown point {pivot:?}")))?;
        if !parsed[l].points.contains(&p) {
            return Err(Error::scene(entry, format!("{pivot:?} is not a point of link {link:?}")));
        }
        if !parsed[ground].points.contains(&p) {
            return Err(Error::scene(
                entry,
                format!(
                    "{pivot:?} is not on the ground link {:?}: the {what} must be pinned to ground",
                    parsed[ground].name
                ),
            ));
        }
        let tip = *parsed[l].points.iter().find(|&&q| q != p).expect("a link has >= 2 distinct points");
        Ok(Pivoted { link: l, pivot: p, tip })
    }

    /// A joint's line: two points of its guide that do not coincide.
    fn line_of(&self, entry: &str, guide: usize, line: &(String, String)) -> Result<(usize, usize), Error> {
        let (parsed, drawn, pre) = (self.parsed, self.drawn, self.pre);
        let (a, b) =
            (self.point_of(&format!("{entry}.line"), &line.0)?, self.point_of(&format!("{entry}.line"), &line.1)?);
        for (n, p) in [(&line.0, a), (&line.1, b)] {
            if !parsed[guide].points.contains(&p) {
                return Err(Error::scene(
                    format!("{entry}.line"),
                    format!("{n:?} is not a point of the guide {:?}", parsed[guide].name),
                ));
            }
        }
        let d = sub(drawn[b], drawn[a]);
        if !((d[0] / pre).hypot(d[1] / pre) > COINCIDENT * self.size) {
            return Err(Error::scene(
                format!("{entry}.line"),
                format!("points {:?} and {:?} coincide", line.0, line.1),
            ));
        }
        Ok((a, b))
    }

    /// Slots and prismatic pairs: names (one namespace), their links and line points (the
    /// slots' offsets come once the frame is fixed).
    pub(super) fn joints(
        &self,
        ground: usize,
        slots: &[(String, SlotSpec)],
        prismatic: &[(String, PrismaticSpec)],
    ) -> Result<(Vec<Slot>, Vec<Prismatic>), Error> {
        let (parsed, names, point_links) = (self.parsed, self.names, self.point_links);
        let mut joint_names: HashMap<&str, &str> = HashMap::new();
        let mut slot_list = Vec::with_capacity(slots.len());
        for (name, sp) in slots {
            let entry = format!("slots.{name}");
            if joint_names.insert(name.as_str(), "slot").is_some() {
                return Err(Error::scene(entry, "is given twice"));
            }
            let point = self.point_of(&format!("{entry}.point"), &sp.point)?;
            let guide = self.link_of(&format!("{entry}.guide"), &sp.guide)?;
            if parsed[guide].points.contains(&point) {
                return Err(Error::scene(
                    format!("{entry}.point"),
                    format!("{:?} is a point of its guide {:?}: it could not move along the line", sp.point, sp.guide),
                ));
            }
            if point_links[point].iter().all(|&l| l == ground) {
                return Err(Error::scene(format!("{entry}.point"), format!("{:?} is on no moving link", sp.point)));
            }
            let line = self.line_of(&entry, guide, &sp.line)?;
            slot_list.push(Slot { name: name.clone(), point, guide, line, offset: 0.0 });
        }
        let mut prism_list = Vec::with_capacity(prismatic.len());
        for (name, sp) in prismatic {
            let entry = format!("prismatic.{name}");
            if joint_names.insert(name.as_str(), "prismatic").is_some() {
                return Err(Error::scene(
                    entry,
                    "is given twice (names of slots and prismatic pairs are one namespace)",
                ));
            }
            let link = self.link_of(&format!("{entry}.link"), &sp.link)?;
            let guide = self.link_of(&format!("{entry}.guide"), &sp.guide)?;
            if link == guide {
                return Err(Error::scene(format!("{entry}.guide"), format!("{:?} cannot guide itself", sp.link)));
            }
            if let Some(&p) = parsed[link].points.iter().find(|p| parsed[guide].points.contains(p)) {
                return Err(Error::scene(
                    format!("{entry}.link"),
                    format!(
                        "{:?} and its guide {:?} share point {:?}: they could not slide",
                        sp.link, sp.guide, names[p]
                    ),
                ));
            }
            let line = self.line_of(&entry, guide, &sp.line)?;
            prism_list.push(Prismatic { name: name.clone(), link, guide, line });
        }
        Ok((slot_list, prism_list))
    }
}

/// The linear input by name, its direction as drawn (not yet unit).
pub(super) fn linear_input(
    linear_input: &Option<(LinearKind, String)>,
    slot_list: &[Slot],
    prism_list: &[Prismatic],
    drawn: &[Xy],
) -> Result<Option<Linear>, Error> {
    Ok(match linear_input {
        None => None,
        Some((kind, name)) => {
            let (key, found) = match kind {
                LinearKind::Slot => ("slot", slot_list.iter().position(|s| &s.name == name)),
                LinearKind::Prismatic => ("prismatic", prism_list.iter().position(|s| &s.name == name)),
            };
            let index =
                found.ok_or_else(|| Error::scene(format!("input.{key}"), format!("{name:?} is not a {key}")))?;
            let (guide, line) = match kind {
                LinearKind::Slot => (slot_list[index].guide, slot_list[index].line),
                LinearKind::Prismatic => (prism_list[index].guide, prism_list[index].line),
            };
            Some(Linear { kind: *kind, index, guide, dir: sub(drawn[line.1], drawn[line.0]) })
        }
    })
}
