//! The plain-data description of a scene's Newton-Euler system and of its loads, as the
//! forces kernel reads it: links, the unknowns (columns) and the unit forces and couples
//! that carry them, the guide lines, the block-triangular order of the equations, and the
//! loads by index. Checked once here ([`Model::new`]); the kernel then trusts it.

use crate::error::Error;

/// The direction a unit force of a column acts along.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Direction {
    /// The x axis (a pin's first column).
    X,
    /// The y axis (a pin's second column).
    Y,
    /// A line's unit normal (its direction turned +90 degrees).
    Normal(usize),
    /// Along a line, from its first point to its second.
    Along(usize),
}

/// A column's unit force on a link: `sign` times a unit force along `dir` at point `point`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UnitForce {
    /// The link it acts on (moving links first, ground last).
    pub link: usize,
    /// The unknown (column) it carries.
    pub column: usize,
    /// +1 or -1.
    pub sign: f64,
    /// Where it acts.
    pub point: usize,
    /// Along what.
    pub dir: Direction,
}

/// A column's unit couple on a link.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UnitCouple {
    /// The link it acts on.
    pub link: usize,
    /// The unknown it carries.
    pub column: usize,
    /// +1 or -1.
    pub sign: f64,
}

/// A guide line: the link that carries it and its two points (direction a -> b).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Line {
    /// The guide link.
    pub guide: usize,
    /// First point.
    pub a: usize,
    /// Second point.
    pub b: usize,
}

/// One block of the block-triangular order: its equations (rows), its unknowns (columns,
/// as many) and the unknowns solved before that its rows read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Block {
    /// Equation rows (3 per moving link: force x, force y, moment).
    pub rows: Vec<usize>,
    /// Unknowns found by this block.
    pub columns: Vec<usize>,
    /// Earlier unknowns its rows read.
    pub prior: Vec<usize>,
}

/// A value over the input coordinate: constant (no `input`) or a table, linear in between,
/// periodic over `period` for an angle input, held at the ends otherwise.
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    xs: Vec<f64>,
    ys: Vec<f64>,
    width: usize,
    period: Option<f64>,
}

impl Table {
    /// `values` holds `width` numbers (constant, `input` empty) or `width` per input value.
    pub fn new(name: &str, input: &[f64], values: &[f64], width: usize, period: Option<f64>) -> Result<Self, Error> {
        if input.is_empty() {
            if values.len() != width {
                return Err(Error::array(name, format!("must hold {width} values, got {}", values.len())));
            }
            return Ok(Table { xs: Vec::new(), ys: values.to_vec(), width, period: None });
        }
        if values.len() != width * input.len() {
            return Err(Error::array(name, format!("must hold {width} values per input value")));
        }
        if input.iter().chain(values).any(|v| !v.is_finite()) {
            return Err(Error::array(name, "must be finite"));
        }
        let mut rows: Vec<(f64, &[f64])> = input.iter().copied().zip(values.chunks(width)).collect();
        let Some(p) = period else {
            return Ok(Table::from_rows(&rows, width, None));
        };
        // as NumPy's periodic interp: the abscissae taken modulo the period, sorted, and
        // the table closed by its last point one period before and its first one after
        for r in &mut rows {
            r.0 = r.0.rem_euclid(p);
        }
        rows.sort_by(|a, b| a.0.total_cmp(&b.0));
        let (first, last) = (rows[0], rows[rows.len() - 1]);
        rows.insert(0, (last.0 - p, last.1));
        rows.push((first.0 + p, first.1));
        Ok(Table::from_rows(&rows, width, Some(p)))
    }

    fn from_rows(rows: &[(f64, &[f64])], width: usize, period: Option<f64>) -> Self {
        Table {
            xs: rows.iter().map(|r| r.0).collect(),
            ys: rows.iter().flat_map(|r| r.1.iter().copied()).collect(),
            width,
            period,
        }
    }

    /// Both components of a vector table at input `x`.
    #[inline]
    pub fn at2(&self, x: f64) -> [f64; 2] {
        let n = self.xs.len();
        if n == 0 {
            return [self.ys[0], self.ys[1]];
        }
        let x = self.period.map_or(x, |p| x.rem_euclid(p));
        if x <= self.xs[0] || n == 1 {
            return [self.ys[0], self.ys[1]];
        }
        if x >= self.xs[n - 1] {
            return [self.ys[2 * n - 2], self.ys[2 * n - 1]];
        }
        let j = self.xs.partition_point(|&v| v <= x) - 1;
        let (x0, x1) = (self.xs[j], self.xs[j + 1]);
        let y = |k: usize| {
            let (y0, y1) = (self.ys[j * 2 + k], self.ys[(j + 1) * 2 + k]);
            (y1 - y0) / (x1 - x0) * (x - x0) + y0
        };
        [y(0), y(1)]
    }

    /// The value at input `x`, component `k`.
    #[inline]
    pub fn at(&self, x: f64, k: usize) -> f64 {
        let w = self.width;
        let n = self.xs.len();
        if n == 0 {
            return self.ys[k];
        }
        let x = self.period.map_or(x, |p| x.rem_euclid(p));
        if x <= self.xs[0] || n == 1 {
            return self.ys[k];
        }
        if x >= self.xs[n - 1] {
            return self.ys[(n - 1) * w + k];
        }
        // the last abscissa not above x
        let j = self.xs.partition_point(|&v| v <= x) - 1;
        let (x0, x1) = (self.xs[j], self.xs[j + 1]);
        let (y0, y1) = (self.ys[j * w + k], self.ys[(j + 1) * w + k]);
        (y1 - y0) / (x1 - x0) * (x - x0) + y0
    }
}

/// A spring (`free_length` and `preload`) or damper (rate per speed) between two points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Element {
    /// The two points.
    pub a: usize,
    /// Second point.
    pub b: usize,
    /// The links that carry them (the first moving link holding each, else ground).
    pub link_a: usize,
    /// The link carrying `b`.
    pub link_b: usize,
    /// Stiffness, or damping.
    pub rate: f64,
    /// A spring's free length.
    pub free_length: f64,
    /// A spring's tension at its free length.
    pub preload: f64,
}

/// A link's mass: its centre is point `a` plus `arm` (as drawn) turned with the direction
/// a -> b (`drawn`, its unit vector as drawn).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mass {
    /// The moving link.
    pub link: usize,
    /// The point the centre is measured from.
    pub a: usize,
    /// A second point of the link (gives its turn).
    pub b: usize,
    /// The centre's offset from `a` as drawn.
    pub arm: [f64; 2],
    /// The unit direction a -> b as drawn.
    pub drawn: [f64; 2],
    /// Mass and moment of inertia about the centre, in the scene's force units (times the
    /// units' inertia factor).
    pub mass: f64,
    /// Moment of inertia.
    pub inertia: f64,
}

/// The loads, by index.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Loads {
    /// (link, point, force table of width 2).
    pub point_forces: Vec<(usize, usize, Table)>,
    /// (line, point, moving link, magnitude table): a force along a slot or prismatic pair,
    /// on the moving part, and back on the guide.
    pub line_forces: Vec<(usize, usize, usize, Table)>,
    /// (link, torque table).
    pub torques: Vec<(usize, Table)>,
    /// Linear springs.
    pub springs: Vec<Element>,
    /// Viscous dampers (`rate` is the damping).
    pub dampers: Vec<Element>,
    /// Gravitational acceleration.
    pub gravity: Option<[f64; 2]>,
    /// Link masses.
    pub masses: Vec<Mass>,
}

/// The output whose rate gives the mechanical advantage.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Output {
    /// A link's angle.
    Link(usize),
    /// A point's displacement along a line (line, point).
    Line(usize, usize),
}

/// A scene's Newton-Euler system with its loads.
#[derive(Clone, Debug, PartialEq)]
pub struct Model {
    pub(crate) points: usize,
    pub(crate) moving: usize,
    pub(crate) columns: usize,
    pub(crate) size: f64,
    pub(crate) refs: Vec<usize>,
    pub(crate) forces: Vec<UnitForce>,
    pub(crate) couples: Vec<UnitCouple>,
    pub(crate) lines: Vec<Line>,
    pub(crate) blocks: Vec<Block>,
    pub(crate) loads: Loads,
    pub(crate) output: Option<Output>,
    pub(crate) widest: usize,
    pub(crate) plans: Vec<Plan>,
}

/// How one block is eliminated: first the unknowns that a pure force row (only axis unit
/// forces: entries +-1) pins down and that no other force row of the block reads (the
/// outer pins of a dyad), by those rows, exactly; then the rest (a dyad's middle pin) by
/// a small dense solve with partial pivoting. Indices are local to the block.
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub(crate) struct Plan {
    /// (row, column) of each exact pivot.
    pub statics: Vec<(usize, usize)>,
    /// The rows and columns left for the dense solve (as many).
    pub rest_rows: Vec<usize>,
    pub rest_cols: Vec<usize>,
    /// The block's entries in the full matrix (row-major, `columns` wide), row-major.
    pub entries: Vec<usize>,
    /// (local row, entry in the full matrix, unknown) of what the rows read from earlier
    /// blocks.
    pub prior: Vec<(usize, usize, usize)>,
}

impl Plan {
    fn of(block: &Block, forces: &[UnitForce], couples: &[UnitCouple], k: usize) -> Plan {
        let m = block.rows.len();
        let entries = block.rows.iter().flat_map(|&r| block.columns.iter().map(move |&c| r * k + c)).collect();
        let prior = (0..m).flat_map(|i| block.prior.iter().map(move |&c| (i, block.rows[i] * k + c, c))).collect();
        // each local row's columns, and whether it is a pure force row
        let mut reads = vec![vec![false; m]; m];
        let mut pure = vec![true; m];
        let local_col = |c: usize| block.columns.iter().position(|&x| x == c);
        for (i, &r) in block.rows.iter().enumerate() {
            let (link, axis) = (r / 3, r % 3);
            pure[i] = axis != 2;
            for f in forces.iter().filter(|f| f.link == link) {
                let hits = match (f.dir, axis) {
                    (_, 2) => true,
                    (Direction::X, 0) | (Direction::Y, 1) => true,
                    (Direction::X, _) | (Direction::Y, _) => false,
                    _ => {
                        pure[i] = false;
                        true
                    }
                };
                if hits {
                    // (an earlier unknown is on the right-hand side already)
                    if let Some(j) = local_col(f.column) {
                        reads[i][j] = true;
                    }
                    if f.sign == 0.0 {
                        pure[i] = false;
                    }
                }
            }
            if axis == 2 {
                for c in couples.iter().filter(|c| c.link == link) {
                    if let Some(j) = local_col(c.column) {
                        reads[i][j] = true;
                    }
                }
            }
        }
        let force_rows: Vec<usize> = (0..m).filter(|&i| block.rows[i] % 3 != 2).collect();
        let mut taken = vec![false; m];
        let mut statics = Vec::new();
        for &i in force_rows.iter().filter(|&&i| pure[i]) {
            let only_here = |j: usize| force_rows.iter().all(|&q| q == i || !reads[q][j]);
            if let Some(j) = (0..m).find(|&j| reads[i][j] && !taken[j] && only_here(j)) {
                taken[j] = true;
                statics.push((i, j));
            }
        }
        let is_static_row = |i: usize| statics.iter().any(|s| s.0 == i);
        Plan {
            rest_rows: (0..m).filter(|&i| !is_static_row(i)).collect(),
            rest_cols: (0..m).filter(|&j| !taken[j]).collect(),
            statics,
            entries,
            prior,
        }
    }
}

/// The parts of a [`Model`] (see its fields' namesakes there).
#[derive(Clone, Debug, Default)]
pub struct Parts {
    /// Number of points.
    pub points: usize,
    /// Number of moving links (ground is link `moving`).
    pub moving: usize,
    /// Number of unknowns; the input effort is the last.
    pub columns: usize,
    /// The drawing's size (moment rows are divided by it).
    pub size: f64,
    /// Each link's reference point (moments are taken about it), ground last.
    pub refs: Vec<usize>,
    /// Unit forces.
    pub forces: Vec<UnitForce>,
    /// Unit couples.
    pub couples: Vec<UnitCouple>,
    /// Guide lines.
    pub lines: Vec<Line>,
    /// The equations' block-triangular order.
    pub blocks: Vec<Block>,
    /// The loads.
    pub loads: Loads,
    /// The output, if declared.
    pub output: Option<Output>,
}

impl Model {
    /// Checks the indices (every one in range, the blocks covering each equation and
    /// unknown once, square) and the numbers (finite).
    pub fn new(p: Parts) -> Result<Self, Error> {
        let links = p.moving + 1;
        let bad = |what: &str, req: &str| Err(Error::array(what, req.to_string()));
        if !(p.size.is_finite() && p.size > 0.0) {
            return bad("size", "must be finite and > 0");
        }
        if p.columns != 3 * p.moving || p.columns == 0 {
            return bad("columns", "must be three per moving link (a one-degree-of-freedom scene)");
        }
        if p.refs.len() != links || p.refs.iter().any(|&r| r >= p.points) {
            return bad("refs", "must give a point of each link, ground last");
        }
        let line_ok = |j: usize| j < p.lines.len();
        for f in &p.forces {
            let dir_ok = match f.dir {
                Direction::Normal(j) | Direction::Along(j) => line_ok(j),
                _ => true,
            };
            if f.link >= links || f.column >= p.columns || f.point >= p.points || !dir_ok || !f.sign.is_finite() {
                return bad("forces", "must name links, columns, points and lines in range");
            }
        }
        if p.couples.iter().any(|c| c.link >= links || c.column >= p.columns || !c.sign.is_finite()) {
            return bad("couples", "must name links and columns in range");
        }
        if p.lines.iter().any(|l| l.guide >= links || l.a >= p.points || l.b >= p.points) {
            return bad("lines", "must name links and points in range");
        }
        let mut row_seen = vec![false; p.columns];
        let mut col_seen = vec![false; p.columns];
        for b in &p.blocks {
            if b.rows.len() != b.columns.len() || b.rows.is_empty() {
                return bad("blocks", "must be square and not empty");
            }
            for &r in &b.rows {
                if r >= p.columns || std::mem::replace(&mut row_seen[r], true) {
                    return bad("blocks", "must take each equation once");
                }
            }
            if b.prior.iter().any(|&c| c >= p.columns || !col_seen[c]) {
                return bad("blocks", "must read only unknowns found by earlier blocks");
            }
            for &c in &b.columns {
                if c >= p.columns || std::mem::replace(&mut col_seen[c], true) {
                    return bad("blocks", "must find each unknown once");
                }
            }
        }
        if !row_seen.iter().all(|&s| s) {
            return bad("blocks", "must take every equation");
        }
        let l = &p.loads;
        let pt = |i: usize| i < p.points;
        let mv = |k: usize| k < links;
        if l.point_forces.iter().any(|(k, q, t)| !mv(*k) || !pt(*q) || t.width != 2)
            || l.line_forces.iter().any(|(j, q, k, t)| !line_ok(*j) || !pt(*q) || !mv(*k) || t.width != 1)
            || l.torques.iter().any(|(k, t)| !mv(*k) || t.width != 1)
            || l.springs.iter().chain(&l.dampers).any(|e| {
                !(pt(e.a)
                    && pt(e.b)
                    && mv(e.link_a)
                    && mv(e.link_b)
                    && e.rate.is_finite()
                    && e.free_length.is_finite()
                    && e.preload.is_finite())
            })
            || l.masses.iter().any(|m| {
                m.link >= p.moving
                    || !pt(m.a)
                    || !pt(m.b)
                    || !m.arm.iter().chain(&m.drawn).chain(&[m.mass, m.inertia]).all(|v| v.is_finite())
            })
            || l.gravity.is_some_and(|g| !g.iter().all(|v| v.is_finite()))
        {
            return bad("loads", "must name links, points and lines in range, with finite numbers");
        }
        match p.output {
            Some(Output::Link(k)) if k >= links => return bad("output", "must name a link in range"),
            Some(Output::Line(j, q)) if !line_ok(j) || !pt(q) => return bad("output", "must name a line and point"),
            _ => {}
        }
        let widest = p.blocks.iter().map(|b| b.rows.len()).max().unwrap_or(0);
        let plans = p.blocks.iter().map(|b| Plan::of(b, &p.forces, &p.couples, p.columns)).collect();
        Ok(Model {
            points: p.points,
            moving: p.moving,
            columns: p.columns,
            size: p.size,
            refs: p.refs,
            forces: p.forces,
            couples: p.couples,
            lines: p.lines,
            blocks: p.blocks,
            loads: p.loads,
            output: p.output,
            widest,
            plans,
        })
    }

    /// Number of unknowns (the input effort last).
    pub fn columns(&self) -> usize {
        self.columns
    }

    /// Number of points a pose holds.
    pub fn points(&self) -> usize {
        self.points
    }

    /// Number of moving links.
    pub fn moving(&self) -> usize {
        self.moving
    }

    /// Whether an output is declared (the mechanical advantage is then computed).
    pub fn has_output(&self) -> bool {
        self.output.is_some()
    }
}
