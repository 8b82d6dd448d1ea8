//! Building a group: its links' rotation classes and columns, its edges (sliding ones
//! included), the spanning tree from the anchors and a closure per loop.

use super::{Closure, Group, Node, Reader, Term, Turn, HELD, MAX};
use crate::scene::input::LinearKind;
use crate::scene::model::Scene;
use crate::scene::vec2::{self, cdiv, cmul, dot, sub, Xy};
use crate::solve::newton;

/// Union-find root.
fn root(parent: &mut [usize], mut l: usize) -> usize {
    while parent[l] != l {
        parent[l] = parent[parent[l]];
        l = parent[l];
    }
    l
}

impl Group {
    /// The group of `links` over the known points, rigid (no unknown left free), with its
    /// slots and prismatic pairs; `None` when they are not one connected rigid group over
    /// the known points, when it has more than [`MAX`] unknowns, or when it is singular as
    /// drawn. A linear input's joint is not part of it (its displacement is the input).
    pub(crate) fn build(sc: &Scene, links: &[usize], known: &[bool]) -> Option<Group> {
        Self::build_form(sc, links, known, Form::Rigid)
    }

    /// [`Group::build`] with the linear input's own joint among the links, its displacement
    /// held at the input ([`Group::held`]): a cylinder pushing a point of a group's link.
    pub(crate) fn build_held(sc: &Scene, links: &[usize], known: &[bool]) -> Option<Group> {
        Self::build_form(sc, links, known, Form::Held).filter(|g| g.held.is_some())
    }

    fn build_form(sc: &Scene, links: &[usize], known: &[bool], form: Form) -> Option<Group> {
        let mut g = Self::tree_form(sc, links, known, form)?;
        let n = g.n();
        if n == 0 || n > MAX || n % 2 == 1 {
            return None;
        }
        // (a held displacement is 0 as drawn)
        let anchors = g.with_held(|p| sc.xy[p], 0.0);
        let det = g.conditioning_with(&[0.0; MAX][..n], &anchors);
        if !(det.abs() >= newton::SINGULAR_THRESHOLD) {
            return None;
        }
        g.sign = det.signum();
        Some(g)
    }

    /// The joints of a set of links: the slots and prismatic pairs that act on it (and the
    /// linear input's joint only for a whole-linkage `chain`).
    fn joints_of(sc: &Scene, inset: &[bool], known: &[bool], chain: bool) -> (Vec<usize>, Vec<usize>) {
        // (`chain`: the input's joint included, as a whole-linkage chain or a held group has it)
        let all_known = |l: usize| sc.links[l].points.iter().all(|&p| known[p]);
        let is_input = |k: LinearKind, i: usize| sc.linear.is_some_and(|l| l.kind == k && l.index == i);
        let slots = (0..sc.slots.len())
            .filter(|&i| {
                let s = &sc.slots[i];
                let p_ok = known[s.point] || sc.point_links[s.point].iter().any(|&l| inset[l]);
                let g_ok = inset[s.guide] || all_known(s.guide);
                p_ok && g_ok && (inset[s.guide] || !known[s.point]) && (chain || !is_input(LinearKind::Slot, i))
            })
            .collect();
        let prismatic = (0..sc.prismatic.len())
            .filter(|&i| {
                let p = &sc.prismatic[i];
                let ok = |l: usize| inset[l] || all_known(l);
                ok(p.link)
                    && ok(p.guide)
                    && (inset[p.link] || inset[p.guide])
                    && (chain || !is_input(LinearKind::Prismatic, i))
            })
            .collect();
        (slots, prismatic)
    }

    /// Constraints minus freedoms of a set of links over the known points (Gruebler's count
    /// with its slots and prismatic pairs): 0 for a rigid group.
    pub(crate) fn freedom(sc: &Scene, links: &[usize], known: &[bool]) -> i64 {
        Self::freedom_form(sc, links, known, false)
    }

    /// [`Group::freedom`] with the linear input's joint counted, and its displacement as
    /// one more constraint (the input holds it): 0 for a rigid held group.
    pub(crate) fn freedom_held(sc: &Scene, links: &[usize], known: &[bool]) -> i64 {
        Self::freedom_form(sc, links, known, true)
    }

    fn freedom_form(sc: &Scene, links: &[usize], known: &[bool], held: bool) -> i64 {
        let mut inset = vec![false; sc.links.len()];
        for &l in links {
            inset[l] = true;
        }
        // links at each point (a count per point: the compiler asks this of many subsets)
        let mut m = vec![0i64; sc.xy.len()];
        for &l in links {
            for &p in &sc.links[l].points {
                m[p] += 1;
            }
        }
        let c: i64 = m
            .iter()
            .enumerate()
            .filter(|&(_, &k)| k > 0)
            .map(|(p, &k)| if known[p] { 2 * k } else { 2 * (k - 1) })
            .sum();
        let (slots, prismatic) = Self::joints_of(sc, &inset, known, held);
        let is_input = |k: LinearKind, i: usize| sc.linear.is_some_and(|l| l.kind == k && l.index == i);
        let holds = slots.iter().any(|&i| is_input(LinearKind::Slot, i))
            || prismatic.iter().any(|&i| is_input(LinearKind::Prismatic, i));
        3 * links.len() as i64 - c - slots.len() as i64 - 2 * prismatic.len() as i64 - i64::from(holds)
    }

    /// The spanning tree and closures of `links` over the known points, with the slots and
    /// prismatic pairs acting on them. A `chain` (the whole linkage over the ground, as
    /// tracing uses it) leaves one unknown free, the input (its link's rotation, or the
    /// linear input's displacement); otherwise the group must be rigid. Any size: the caller
    /// checks what it needs.
    pub(crate) fn tree(sc: &Scene, links: &[usize], known: &[bool], chain: bool) -> Option<Group> {
        Self::tree_form(sc, links, known, if chain { Form::Chain } else { Form::Rigid })
    }

    fn tree_form(sc: &Scene, links: &[usize], known: &[bool], form: Form) -> Option<Group> {
        let chain = form == Form::Chain;
        let nl = sc.links.len();
        let mut inset = vec![false; nl];
        for &l in links {
            inset[l] = true;
        }
        let (slots, prismatic) = Self::joints_of(sc, &inset, known, form != Form::Rigid);

        let mut readers = Vec::new();
        let mut cls = Classes::new(sc, links, known, &prismatic, &mut readers)?;
        let nrot = readers.len();

        // anchors: the known points the edges start from or read rotations off
        let mut anchors: Vec<usize> = Vec::new();
        for &l in links {
            for &p in &sc.links[l].points {
                if known[p] {
                    anchor_index(&mut anchors, p);
                }
            }
        }
        let Edges { edges, leaves, nslides, mut input, held } =
            Edges::new(sc, links, known, (&slots, &prismatic), form, &mut cls, &mut anchors, &mut readers);
        if chain && input.is_none() {
            let pv = sc.input?;
            input = match cls.turn_of(&sc.xy, pv.link, &mut anchors).0 {
                Turn::Col(c) => Some(c),
                Turn::Known(..) => return None,
            };
        }

        let (mut nodes, closures, gp) = spanning(&anchors, &edges)?;
        let joints = nodes.len();
        for (c, y, t) in leaves {
            let &gc = gp.get(&c)?;
            nodes.push(Node { point: y, base: gc, term: t });
        }
        let ncols = nrot + nslides;
        if 2 * closures.len() + usize::from(chain) != ncols {
            return None;
        }
        let elbows = elbows(sc, links, &nodes[..joints]);
        // the readers of displacements use anchor indices for known turns: keep them valid
        Some(Group {
            links: links.to_vec(),
            nrot,
            anchors,
            nodes,
            joints,
            closures,
            readers,
            elbows,
            sign: 0.0,
            input: if chain { input } else { None },
            held,
        })
    }
}

/// The rotation classes of a set of links (links joined by a prismatic pair turn
/// together), each either known (carried by two known points of one of its links) or
/// given a column.
struct Classes {
    parent: Vec<usize>,
    carrier: Vec<Option<(usize, usize)>>,
    col_of_class: Vec<Option<usize>>,
}

impl Classes {
    /// The classes of `links`; the rotation columns' readers go to `readers`. `None` when
    /// a link with an unknown rotation has a single point.
    fn new(
        sc: &Scene,
        links: &[usize],
        known: &[bool],
        prismatic: &[usize],
        readers: &mut Vec<Reader>,
    ) -> Option<Self> {
        let xy = &sc.xy;
        let nl = sc.links.len();
        let all_known = |l: usize| sc.links[l].points.iter().all(|&p| known[p]);
        // rotation classes: links joined by a prismatic pair turn together
        let mut parent: Vec<usize> = (0..nl).collect();
        for &i in prismatic {
            let (a, b) = (root(&mut parent, sc.prismatic[i].link), root(&mut parent, sc.prismatic[i].guide));
            parent[a] = b;
        }
        // a class is known when one of its links is (its two farthest points carry it)
        let mut carrier: Vec<Option<(usize, usize)>> = vec![None; nl];
        for l in (0..nl).filter(|&l| all_known(l) && sc.links[l].points.len() >= 2) {
            let r = root(&mut parent, l);
            if carrier[r].is_none() {
                let pts = &sc.links[l].points;
                let mut best = (pts[0], pts[1], -1.0);
                for (i, &a) in pts.iter().enumerate() {
                    for &b in &pts[i + 1..] {
                        let d = sub(xy[b], xy[a]);
                        if dot(d, d) > best.2 {
                            best = (a, b, dot(d, d));
                        }
                    }
                }
                carrier[r] = Some((best.0, best.1));
            }
        }
        // columns: unknown rotation classes in the order their links come, then slides
        let mut col_of_class: Vec<Option<usize>> = vec![None; nl];
        for &l in links {
            let r = root(&mut parent, l);
            if carrier[r].is_none() && col_of_class[r].is_none() {
                col_of_class[r] = Some(readers.len());
                let pts = &sc.links[l].points;
                let (a, b) = (pts[0], *pts.get(1)?);
                readers.push(Reader::Rotation { a, b, drawn: sub(xy[b], xy[a]) });
            }
        }
        Some(Classes { parent, carrier, col_of_class })
    }

    /// The turn of a link's class, and the factor that gives a drawn vector for it.
    fn turn_of(&mut self, xy: &[Xy], l: usize, anchors: &mut Vec<usize>) -> (Turn, Xy) {
        let r = root(&mut self.parent, l);
        match (self.col_of_class[r], self.carrier[r]) {
            (Some(c), _) => (Turn::Col(c), [1.0, 0.0]),
            (None, Some((a, b))) => {
                let h = sub(xy[b], xy[a]);
                (Turn::Known(anchor_index(anchors, a), anchor_index(anchors, b)), cdiv([1.0, 0.0], h))
            }
            (None, None) => unreachable!("every class has a column or a carrier"),
        }
    }
}

/// A group's edges: the sliding ones (slots, then prismatic pairs, each with its column
/// and reader) and each link's star from its centre, where those to a point of no other
/// link are `leaves` (carried, not joints); `input`: a linear input's column.
struct Edges {
    edges: Vec<(usize, usize, Term)>,
    leaves: Vec<(usize, usize, Term)>,
    nslides: usize,
    input: Option<usize>,
    /// The linear input's joint held at the input (a held group): its edge.
    held: Option<(usize, usize, Term)>,
}

/// What a set of links is built into: a rigid group (the input's joint left out), a rigid
/// group with the input's joint held at the input, or the whole linkage as a chain with
/// the input free.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Form {
    Rigid,
    Held,
    Chain,
}

impl Edges {
    fn new(
        sc: &Scene,
        links: &[usize],
        known: &[bool],
        (slots, prismatic): (&[usize], &[usize]),
        form: Form,
        cls: &mut Classes,
        anchors: &mut Vec<usize>,
        readers: &mut Vec<Reader>,
    ) -> Self {
        let xy = &sc.xy;
        let nl = sc.links.len();
        let nrot = readers.len();
        // incidences: links in the set, then sliding edges
        let mut count = vec![0usize; sc.names.len()];
        for &l in links {
            for &p in &sc.links[l].points {
                count[p] += 1;
            }
        }
        let slot_points: Vec<usize> = slots.iter().map(|&i| sc.slots[i].point).collect();
        // a link's star centre: its first joint
        let centres: Vec<usize> = (0..nl)
            .map(|l| {
                let pts = &sc.links[l].points;
                pts.iter().copied().find(|&p| known[p] || count[p] >= 2 || slot_points.contains(&p)).unwrap_or(pts[0])
            })
            .collect();
        let mut edges: Vec<(usize, usize, Term)> = Vec::new();
        let mut slide_cols = Vec::new();
        let mut input = None;
        let mut held = None;
        let is_input = |k: LinearKind, i: usize| sc.linear.is_some_and(|l| l.kind == k && l.index == i);
        // a held input's displacement is no column: its slide reads the input instead
        let column = |is: bool, slide_cols: &mut Vec<usize>| {
            if is && form == Form::Held {
                HELD
            } else {
                let k = nrot + slide_cols.len();
                slide_cols.push(k);
                k
            }
        };
        for &i in slots {
            let s = &sc.slots[i];
            let (a, b) = s.line;
            let (turn, unit) = cls.turn_of(xy, s.guide, anchors);
            let d = vec2::unit(sub(xy[b], xy[a]));
            let k = column(is_input(LinearKind::Slot, i), &mut slide_cols);
            let term = Term { turn, v: cmul(unit, sub(xy[s.point], xy[a])), slide: Some((k, cmul(unit, d))) };
            if k == HELD {
                held = Some((a, s.point, term));
            } else if is_input(LinearKind::Slot, i) {
                input = Some(k);
            }
            // a known slot point (a crank pin in a slot of the group's link) anchors the group
            for p in [a, s.point] {
                if known[p] {
                    anchor_index(anchors, p);
                }
            }
            if k != HELD {
                readers.push(Reader::Slide { from: a, to: s.point, term });
            }
            edges.push((a, s.point, term));
        }
        for &i in prismatic {
            let pr = &sc.prismatic[i];
            let (a, b) = pr.line;
            let (turn, unit) = cls.turn_of(xy, pr.guide, anchors);
            let d = vec2::unit(sub(xy[b], xy[a]));
            let c = centres[pr.link];
            let k = column(is_input(LinearKind::Prismatic, i), &mut slide_cols);
            let term = Term { turn, v: cmul(unit, sub(xy[c], xy[a])), slide: Some((k, cmul(unit, d))) };
            if k == HELD {
                held = Some((a, c, term));
            } else if is_input(LinearKind::Prismatic, i) {
                input = Some(k);
            }
            for p in [a, c] {
                if known[p] {
                    anchor_index(anchors, p);
                }
            }
            if k != HELD {
                readers.push(Reader::Slide { from: a, to: c, term });
            }
            edges.push((a, c, term));
        }
        for &(a, c, _) in &edges {
            count[a] += 1;
            count[c] += 1;
        }
        let is_joint = |p: usize| known[p] || count[p] >= 2;
        let mut leaves: Vec<(usize, usize, Term)> = Vec::new();
        for &l in links {
            let c = centres[l];
            let (turn, unit) = cls.turn_of(xy, l, anchors);
            for &y in sc.links[l].points.iter().filter(|&&y| y != c) {
                let e = (c, y, Term { turn, v: cmul(unit, sub(xy[y], xy[c])), slide: None });
                if is_joint(y) {
                    edges.push(e);
                } else {
                    leaves.push(e);
                }
            }
        }
        Edges { edges, leaves, nslides: slide_cols.len(), input, held }
    }
}

/// A spanning tree's nodes, its closures, and each point's group index.
type Spanning = (Vec<Node>, Vec<Closure>, std::collections::HashMap<usize, usize>);

/// Breadth-first from the anchors: the nodes reached (each from its base by one term),
/// a closure per edge that meets a point reached already, and each point's group index;
/// `None` when some edge is not connected to the known points.
fn spanning(anchors: &[usize], edges: &[(usize, usize, Term)]) -> Option<Spanning> {
    // breadth-first from the anchors; paths hold the terms from a point's anchor
    let na = anchors.len();
    let mut gp = std::collections::HashMap::<usize, usize>::new();
    for (i, &a) in anchors.iter().enumerate() {
        gp.insert(a, i);
    }
    let mut rootp: Vec<usize> = (0..na).collect();
    let mut path: Vec<Vec<Term>> = vec![Vec::new(); na];
    let mut nodes = Vec::new();
    let mut used = vec![false; edges.len()];
    let mut closures = Vec::new();
    let mut queue: std::collections::VecDeque<usize> = anchors.iter().copied().collect();
    while let Some(x) = queue.pop_front() {
        let gx = gp[&x];
        for (e, &(from, to, term)) in edges.iter().enumerate() {
            if used[e] || (from != x && to != x) {
                continue;
            }
            used[e] = true;
            let (y, t) = if from == x { (to, term) } else { (from, term.neg()) };
            match gp.get(&y) {
                Some(&gy) => {
                    // closure: anchor(x) + path(x) + t - anchor(y) - path(y) = 0
                    let mut terms = path[gx].clone();
                    terms.push(t);
                    terms.extend(path[gy].iter().map(|t| t.neg()));
                    closures.push(Closure { plus: rootp[gx], minus: rootp[gy], terms: merged(terms) });
                }
                None => {
                    let gy = na + nodes.len();
                    gp.insert(y, gy);
                    nodes.push(Node { point: y, base: gx, term: t });
                    rootp.push(rootp[gx]);
                    let mut p = path[gx].clone();
                    p.push(t);
                    path.push(p);
                    queue.push_back(y);
                }
            }
        }
    }
    if used.contains(&false) {
        return None; // a part not connected to the known points
    }
    Some((nodes, closures, gp))
}

/// Per joint of two or more of `links`: (joint, a point of the first link, a point of the
/// second), whose cross product's sign is the joint's elbow.
fn elbows(sc: &Scene, links: &[usize], joints: &[Node]) -> Vec<(usize, usize, usize)> {
    let mut elbows = Vec::new();
    for nd in joints {
        let on: Vec<usize> =
            links.iter().copied().filter(|&l| sc.links[l].points.contains(&nd.point)).take(2).collect();
        if let [l1, l2] = on[..] {
            let other = |l: usize| sc.links[l].points.iter().copied().find(|&q| q != nd.point);
            if let (Some(a), Some(b)) = (other(l1), other(l2)) {
                elbows.push((nd.point, a, b));
            }
        }
    }
    elbows
}

/// Index of scene point `p` among the anchors, adding it if new.
fn anchor_index(anchors: &mut Vec<usize>, p: usize) -> usize {
    match anchors.iter().position(|&q| q == p) {
        Some(i) => i,
        None => {
            anchors.push(p);
            anchors.len() - 1
        }
    }
}

/// Terms turning with one rotation column and not sliding are summed into one (the loop
/// equations' coefficient of that link): fewer terms per evaluation.
fn merged(terms: Vec<Term>) -> Vec<Term> {
    let mut out: Vec<Term> = Vec::with_capacity(terms.len());
    for t in terms {
        if t.slide.is_none() {
            if let Some(o) = out.iter_mut().find(|o| o.slide.is_none() && o.turn == t.turn) {
                o.v = [o.v[0] + t.v[0], o.v[1] + t.v[1]];
                continue;
            }
        }
        out.push(t);
    }
    out.retain(|t| t.slide.is_some() || t.v != [0.0; 2]);
    out
}
