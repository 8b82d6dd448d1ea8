//! A scene's [`Parts`] from the core's own scene and the file's loads, for callers with no
//! Python layer (the browser): the same unknowns, unit forces, lines, block order and loads
//! by index that `planarkin.forces.Structure` lays out, in the same order. A leaf of the
//! subject beside [`super::model`].

use super::model::{Block, Direction, Element, Line, Loads, Mass, Output, Parts, Table, UnitCouple, UnitForce};
use crate::error::Error;
use crate::scene::format::{self, Center, Drive, Profile, Target, Units};
use crate::scene::{LinearKind, Scene};

/// Each known unit in SI (metres, newtons, kilograms), as `planarkin.forces._units`.
const LENGTH: [(&str, f64); 7] =
    [("m", 1.0), ("mm", 1e-3), ("cm", 1e-2), ("km", 1e3), ("um", 1e-6), ("in", 0.0254), ("ft", 0.3048)];
const FORCE: [(&str, f64); 5] = [("N", 1.0), ("kN", 1e3), ("mN", 1e-3), ("MN", 1e6), ("lbf", 4.4482216152605)];
const MASS: [(&str, f64); 4] = [("kg", 1.0), ("g", 1e-3), ("t", 1e3), ("lb", 0.45359237)];

/// mass x length / time^2 in the scene's force units (1 where a unit is not known here).
pub fn inertia_factor(length: Option<&str>, table: Option<&Units>) -> f64 {
    let length = table.and_then(|t| t.length.as_deref()).or(length).unwrap_or("m");
    let force = table.and_then(|t| t.force.as_deref()).unwrap_or("N");
    let mass = table.and_then(|t| t.mass.as_deref()).unwrap_or("kg");
    let find = |t: &[(&str, f64)], k: &str| t.iter().find(|e| e.0 == k).map(|e| e.1);
    match (find(&LENGTH, length), find(&FORCE, force), find(&MASS, mass)) {
        (Some(l), Some(f), Some(m)) => m * l / f,
        _ => 1.0,
    }
}

fn table(name: &str, p: &Profile, period: Option<f64>) -> Result<Table, Error> {
    Table::new(name, p.input.as_deref().unwrap_or(&[]), &p.values, p.width, period)
}

/// The parts of `scene`'s Newton-Euler system under `loads` (names checked by the file
/// format), with `output` as the file declares it and `factor` the units' inertia factor.
pub fn parts(
    scene: &Scene,
    input: &Drive,
    loads: &format::Loads,
    output: Option<&Drive>,
    factor: f64,
) -> Result<Parts, Error> {
    let names = scene.point_names();
    let np = names.len();
    let links = scene.links();
    let ground = scene.ground();
    let moving: Vec<usize> = (0..links.len()).filter(|&l| l != ground).collect();
    let nm = moving.len();
    // model link index of each scene link: the moving ones in scene order, ground last
    let mut lidx = vec![nm; links.len()];
    for (i, &l) in moving.iter().enumerate() {
        lidx[l] = i;
    }
    let point =
        |n: &str| names.iter().position(|p| p == n).ok_or_else(|| Error::scene("loads", format!("no point {n:?}")));
    let link =
        |n: &str| links.iter().position(|l| l.name == n).ok_or_else(|| Error::scene("loads", format!("no link {n:?}")));
    let on = |p: usize| -> Vec<usize> { (0..links.len()).filter(|&l| links[l].points.contains(&p)).collect() };
    let carrier = |p: usize| moving.iter().find(|&&l| links[l].points.contains(&p)).map_or(nm, |&l| lidx[l]);
    let mut refs = vec![0; nm + 1];
    for (l, lk) in links.iter().enumerate() {
        refs[lidx[l]] = lk.points[0];
    }
    let mut columns = 0usize;
    let mut forces = Vec::new();
    let mut couples = Vec::new();
    for p in 0..np {
        let here = on(p);
        for &other in here.iter().skip(1) {
            for dir in [Direction::X, Direction::Y] {
                forces.push(UnitForce { link: lidx[other], column: columns, sign: 1.0, point: p, dir });
                forces.push(UnitForce { link: lidx[here[0]], column: columns, sign: -1.0, point: p, dir });
                columns += 1;
            }
        }
    }
    let mut lines = Vec::new();
    // (line, point, moving link) of each slot and prismatic pair
    let mut slot_of = Vec::new();
    for s in scene.slots() {
        let holder = on(s.point).into_iter().find(|&l| l != s.guide).unwrap_or(ground);
        let j = lines.len();
        lines.push(Line { guide: lidx[s.guide], a: s.line.0, b: s.line.1 });
        slot_of.push((j, s.point, lidx[holder]));
        forces.push(UnitForce {
            link: lidx[holder],
            column: columns,
            sign: 1.0,
            point: s.point,
            dir: Direction::Normal(j),
        });
        forces.push(UnitForce {
            link: lidx[s.guide],
            column: columns,
            sign: -1.0,
            point: s.point,
            dir: Direction::Normal(j),
        });
        columns += 1;
    }
    let mut prismatic_of = Vec::new();
    for p in scene.prismatic() {
        let j = lines.len();
        lines.push(Line { guide: lidx[p.guide], a: p.line.0, b: p.line.1 });
        let r = links[p.link].points[0];
        prismatic_of.push((j, r, lidx[p.link]));
        forces.push(UnitForce { link: lidx[p.link], column: columns, sign: 1.0, point: r, dir: Direction::Normal(j) });
        forces.push(UnitForce {
            link: lidx[p.guide],
            column: columns,
            sign: -1.0,
            point: r,
            dir: Direction::Normal(j),
        });
        couples.push(UnitCouple { link: lidx[p.link], column: columns + 1, sign: 1.0 });
        couples.push(UnitCouple { link: lidx[p.guide], column: columns + 1, sign: -1.0 });
        columns += 2;
    }
    let line_of = |kind: LinearKind, name: &str| -> Result<(usize, usize, usize), Error> {
        let found = match kind {
            LinearKind::Slot => scene.slots().iter().position(|s| s.name == name).map(|i| slot_of[i]),
            LinearKind::Prismatic => scene.prismatic().iter().position(|s| s.name == name).map(|i| prismatic_of[i]),
        };
        found.ok_or_else(|| Error::scene("loads", format!("no slot or prismatic pair {name:?}")))
    };
    let angle = matches!(input, Drive::Angle { .. });
    match input {
        Drive::Angle { link: name, .. } => {
            let l = lidx[link(name)?];
            couples.push(UnitCouple { link: l, column: columns, sign: 1.0 });
            couples.push(UnitCouple { link: nm, column: columns, sign: -1.0 });
        }
        Drive::Linear { kind, name } => {
            let (j, pt, carrier) = line_of(*kind, name)?;
            let guide = lines[j].guide;
            forces.push(UnitForce { link: carrier, column: columns, sign: 1.0, point: pt, dir: Direction::Along(j) });
            forces.push(UnitForce { link: guide, column: columns, sign: -1.0, point: pt, dir: Direction::Along(j) });
        }
    }
    columns += 1;
    if columns != 3 * nm {
        return Err(Error::scene("scene", "forces need a one-degree-of-freedom scene without redundant constraints"));
    }
    let blocks = block_order(nm, columns, &forces, &couples)
        .ok_or_else(|| Error::scene("scene", "statically indeterminate: a constraint's reaction is not fixed"))?;
    let period = angle.then_some(std::f64::consts::TAU);
    let mut l = Loads { gravity: loads.gravity, ..Loads::default() };
    for (target, profile) in &loads.forces {
        match target {
            Target::Point(p) => {
                let q = point(p)?;
                l.point_forces.push((carrier(q), q, table("forces", profile, period)?));
            }
            Target::Slot(n) => {
                let (j, q, k) = line_of(LinearKind::Slot, n)?;
                l.line_forces.push((j, q, k, table("forces", profile, period)?));
            }
            Target::Prismatic(n) => {
                let (j, q, k) = line_of(LinearKind::Prismatic, n)?;
                l.line_forces.push((j, q, k, table("forces", profile, period)?));
            }
        }
    }
    for (name, profile) in &loads.torques {
        l.torques.push((lidx[link(name)?], table("torques", profile, period)?));
    }
    let element = |e: &format::Element| -> Result<Element, Error> {
        let (a, b) = (point(&e.between.0)?, point(&e.between.1)?);
        Ok(Element {
            a,
            b,
            link_a: carrier(a),
            link_b: carrier(b),
            rate: e.rate,
            free_length: e.free_length.unwrap_or(0.0),
            preload: e.preload,
        })
    };
    l.springs = loads.springs.iter().map(element).collect::<Result<_, _>>()?;
    l.dampers = loads.dampers.iter().map(element).collect::<Result<_, _>>()?;
    let drawn = scene.drawn();
    for (name, m) in &loads.masses {
        let s = link(name)?;
        if s == ground {
            continue;
        }
        let pts = &links[s].points;
        let (a, b, arm) = match &m.center {
            Center::Point(c) => {
                let c = point(c)?;
                (c, if pts[0] == c { pts[1] } else { pts[0] }, [0.0, 0.0])
            }
            Center::At(xy) => (pts[0], pts[1], [xy[0] - drawn[pts[0]][0], xy[1] - drawn[pts[0]][1]]),
        };
        let d = [drawn[b][0] - drawn[a][0], drawn[b][1] - drawn[a][1]];
        let len = (d[0] * d[0] + d[1] * d[1]).sqrt();
        l.masses.push(Mass {
            link: lidx[s],
            a,
            b,
            arm,
            drawn: [d[0] / len, d[1] / len],
            mass: factor * m.mass,
            inertia: factor * m.inertia,
        });
    }
    let out = match output {
        None => None,
        Some(Drive::Angle { link: name, .. }) => Some(Output::Link(lidx[link(name)?])),
        Some(Drive::Linear { kind, name }) => {
            let (j, q, _) = line_of(*kind, name)?;
            Some(Output::Line(j, q))
        }
    };
    let size = format::size(drawn);
    Ok(Parts {
        points: np,
        moving: nm,
        columns,
        size: if size > 0.0 { size } else { 1.0 },
        refs,
        forces,
        couples,
        lines,
        blocks,
        loads: l,
        output: out,
    })
}

/// Each pin's (point, link, first column) in column order: the reaction on `link` (scene
/// indices) from the joint's first link, its x then y in that column and the next.
pub fn pins(scene: &Scene) -> Vec<(usize, usize, usize)> {
    let links = scene.links();
    let mut out = Vec::new();
    for p in 0..scene.point_names().len() {
        let here: Vec<usize> = (0..links.len()).filter(|&l| links[l].points.contains(&p)).collect();
        for &other in here.iter().skip(1) {
            out.push((p, other, 2 * out.len()));
        }
    }
    out
}

/// The moving links' equations in block-triangular order, as `Structure._blocks` finds
/// them (a matching of unknowns to equations by augmenting paths, then Tarjan's strongly
/// connected components of what each unknown's equation reads, those read first); None
/// without a perfect matching.
fn block_order(nm: usize, k: usize, forces: &[UnitForce], couples: &[UnitCouple]) -> Option<Vec<Block>> {
    let rows = 3 * nm;
    let mut s = vec![vec![false; k]; 3 * (nm + 1)];
    for f in forces {
        s[3 * f.link + 2][f.column] = true;
        if f.dir != Direction::Y {
            s[3 * f.link][f.column] = true;
        }
        if f.dir != Direction::X {
            s[3 * f.link + 1][f.column] = true;
        }
    }
    for c in couples {
        s[3 * c.link + 2][c.column] = true;
    }
    s.truncate(rows);
    let mut match_row = vec![usize::MAX; rows];
    fn augment(s: &[Vec<bool>], col: usize, seen: &mut [bool], match_row: &mut [usize]) -> bool {
        for r in 0..s.len() {
            if s[r][col] && !seen[r] {
                seen[r] = true;
                if match_row[r] == usize::MAX || augment(s, match_row[r], seen, match_row) {
                    match_row[r] = col;
                    return true;
                }
            }
        }
        false
    }
    for c in 0..k {
        if !augment(&s, c, &mut vec![false; rows], &mut match_row) {
            return None;
        }
    }
    let mut row_of = vec![0; k];
    for (r, &c) in match_row.iter().enumerate() {
        row_of[c] = r;
    }
    let reads: Vec<Vec<usize>> = (0..k).map(|c| (0..k).filter(|&x| x != c && s[row_of[c]][x]).collect()).collect();
    struct Tarjan<'a> {
        reads: &'a [Vec<usize>],
        index: Vec<usize>,
        low: Vec<usize>,
        count: usize,
        stack: Vec<usize>,
        on: Vec<bool>,
        order: Vec<Vec<usize>>,
    }
    impl Tarjan<'_> {
        fn visit(&mut self, v: usize) {
            self.index[v] = self.count;
            self.low[v] = self.count;
            self.count += 1;
            self.stack.push(v);
            self.on[v] = true;
            for i in 0..self.reads[v].len() {
                let u = self.reads[v][i];
                if self.index[u] == usize::MAX {
                    self.visit(u);
                    self.low[v] = self.low[v].min(self.low[u]);
                } else if self.on[u] {
                    self.low[v] = self.low[v].min(self.index[u]);
                }
            }
            if self.low[v] == self.index[v] {
                let mut comp = Vec::new();
                while let Some(u) = self.stack.pop() {
                    self.on[u] = false;
                    comp.push(u);
                    if u == v {
                        break;
                    }
                }
                comp.sort_unstable();
                self.order.push(comp);
            }
        }
    }
    let mut t = Tarjan {
        reads: &reads,
        index: vec![usize::MAX; k],
        low: vec![0; k],
        count: 0,
        stack: Vec::new(),
        on: vec![false; k],
        order: Vec::new(),
    };
    for v in 0..k {
        if t.index[v] == usize::MAX {
            t.visit(v);
        }
    }
    Some(
        t.order
            .into_iter()
            .map(|comp| {
                let rows: Vec<usize> = comp.iter().map(|&c| row_of[c]).collect();
                let prior = (0..k).filter(|&x| !comp.contains(&x) && rows.iter().any(|&r| s[r][x])).collect();
                Block { rows, columns: comp, prior }
            })
            .collect(),
    )
}
