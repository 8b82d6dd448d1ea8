//! Every real assembly at one input angle: the plan's steps branched over all their
//! solutions. A dyad has two sides (none where it cannot close); a group's real solutions
//! come from the all-solutions homotopy on its loop equations ([`crate::solve::homotopy`]), two
//! runs with independent random gammas merged and polished by Newton.

use crate::error::{finite, try_grow, Error};
use crate::interrupt::{Interrupt, Poll};
use crate::scene::build::Plan;
use crate::scene::model::Scene;
use crate::scene::ops::DyadOut;
use crate::scene::ops::Group;
use crate::scene::ops::Op;
use crate::scene::vec2::{perp, Xy};
use crate::solve::homotopy::{quadric_solutions_polled, unit_circle_solutions_polled, HomotopyOptions};
use crate::solve::newton::NewtonOptions;
use crate::Status;

/// One real assembly.
#[derive(Clone, Debug, PartialEq)]
pub struct Assembly {
    /// Every point of the scene, scene coordinates (NaN for points the plan does not solve).
    pub points: Vec<Xy>,
    /// Signed conditioning of each step; `det` is their product.
    pub step_det: Vec<f64>,
    pub det: f64,
    /// Mode label: one token per step: a dyad's side ("+" / "-"); a group's elbows in
    /// parentheses, the sign of the angle at each of its joints ("(+-+-)"), followed by a
    /// letter in the rare case two of its solutions share them. A label changes only where
    /// a joint's two links fall in line.
    pub label: String,
}

/// A group's real solutions, with its finite complex roots, paths tracked and failed.
type Solved = (Vec<Vec<f64>>, usize, usize, usize);

/// All real assemblies at one input angle, with the group steps' complex solution counts.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Assemblies {
    pub list: Vec<Assembly>,
    /// For each group step (in plan order): the finite complex solutions found, one entry
    /// per homotopy call (a group below branching dyads is solved once per branch).
    pub complex_counts: Vec<Vec<usize>>,
    /// For each group step: the homotopy paths tracked, one entry per call (all runs).
    pub paths: Vec<Vec<usize>>,
    /// Homotopy paths that failed over all calls (0 when nothing was lost in tracking).
    pub failed_paths: usize,
    /// Branches where a dyad's known points coincide with equal links (the point anywhere
    /// on a circle), or a slot's point lies on its turning guide's pivot (the guide at any
    /// angle): a continuum of assemblies, not listed.
    pub continua: usize,
}

struct Walk<'p> {
    plan: &'p Plan,
    opts: HomotopyOptions,
    poll: Poll<'p>,
    u: Xy,
    /// The input value (a displacement for a linear input; the fused guide reads it).
    s: f64,
    out: Assemblies,
    /// group op index -> position in `out.complex_counts`
    group_slot: Vec<usize>,
}

impl Plan {
    /// Every real assembly at input angle `theta` (radians). `interrupt` is asked every
    /// few thousand homotopy steps and assemblies (Ctrl-C from Python).
    pub fn assemblies<'p>(
        &'p self,
        theta: f64,
        opts: &HomotopyOptions,
        interrupt: &'p dyn Interrupt,
    ) -> Result<Assemblies, Error> {
        finite("theta", theta)?;
        let mut group_slot = vec![usize::MAX; self.ops.len()];
        let mut groups = 0;
        for (i, op) in self.ops.iter().enumerate() {
            if matches!(op, Op::Group(_)) {
                group_slot[i] = groups;
                groups += 1;
            }
        }
        let (s, c) = theta.sin_cos();
        let mut w = Walk {
            plan: self,
            opts: *opts,
            poll: Poll::new(interrupt),
            u: [c, s],
            s: if self.linear { theta / self.scale } else { theta },
            out: Assemblies {
                complex_counts: vec![Vec::new(); groups],
                paths: vec![Vec::new(); groups],
                ..Default::default()
            },
            group_slot,
        };
        let mut pos = vec![[f64::NAN; 2]; self.npoints];
        for &(p, xy) in &self.fixed {
            pos[p] = xy;
        }
        w.walk(0, &mut pos, &mut Vec::new(), &mut Vec::new())?;
        Ok(w.out)
    }
}

impl Walk<'_> {
    fn walk(&mut self, i: usize, pos: &mut [Xy], dets: &mut Vec<f64>, labels: &mut Vec<String>) -> Result<(), Error> {
        let plan = self.plan;
        self.poll.tick()?;
        let Some(op) = plan.ops.get(i) else {
            return self.emit(pos, dets, labels);
        };
        match op {
            Op::Input { q, lam, mu } => {
                let (u, pu, p) = (self.u, perp(self.u), plan.pivot);
                pos[*q] = [p[0] + lam * u[0] + mu * pu[0], p[1] + lam * u[1] + mu * pu[1]];
                self.walk(i + 1, pos, dets, labels)
            }
            Op::Carry { q, a, b, m } => {
                let (pa, pb) = (pos[*a], pos[*b]);
                let d = [pb[0] - pa[0], pb[1] - pa[1]];
                pos[*q] = [pa[0] + m[0] * d[0] - m[1] * d[1], pa[1] + m[1] * d[0] + m[0] * d[1]];
                self.walk(i + 1, pos, dets, labels)
            }
            Op::Dyad(d) => {
                for side in [1.0, -1.0] {
                    let out = d.solve_side(pos[d.k1], pos[d.k2], side);
                    if out == DyadOut::Indeterminate && side > 0.0 {
                        self.out.continua += 1;
                    }
                    if let DyadOut::Solved(p, det) = out {
                        if det == 0.0 && side < 0.0 {
                            continue; // a double root: one assembly, not two
                        }
                        pos[d.p] = p;
                        dets.push(det);
                        labels.push(if side > 0.0 { "+".into() } else { "-".into() });
                        self.walk(i + 1, pos, dets, labels)?;
                        dets.pop();
                        labels.pop();
                    }
                }
                Ok(())
            }
            Op::Group(g) => self.group(i, g, pos, dets, labels),
            Op::Rpr(r) if r.on_pivot(pos[r.k], pos[r.q]) => {
                // a slot's point on its guide's pivot: the guide at any angle, not listed
                self.out.continua += 1;
                Ok(())
            }
            op => {
                // sliders: two sides where there are two, one solution otherwise
                let sides: &[f64] = if op.sided() { &[1.0, -1.0] } else { &[1.0] };
                let zero = vec![[0.0; 2]; pos.len()];
                for &side in sides {
                    let Some(out) = op.solve_slider(self.s, [&*pos, &zero, &zero], side, false) else { continue };
                    if out.det == 0.0 && side < 0.0 {
                        continue; // a double root: one assembly, not two
                    }
                    for p in op.outputs() {
                        pos[p] = out.x[0];
                    }
                    if op.sided() {
                        dets.push(out.det);
                        labels.push(if side > 0.0 { "+".into() } else { "-".into() });
                    }
                    self.walk(i + 1, pos, dets, labels)?;
                    if op.sided() {
                        dets.pop();
                        labels.pop();
                    }
                }
                Ok(())
            }
        }
    }

    fn group(
        &mut self,
        i: usize,
        g: &crate::scene::ops::Group,
        pos: &mut [Xy],
        dets: &mut Vec<f64>,
        labels: &mut Vec<String>,
    ) -> Result<(), Error> {
        {
            {
                let anchors = g.with_held(|p| pos[p], self.s);
                let (real, count, paths, failed) = match g.linear_form(&anchors) {
                    Some((a, b)) => {
                        let sol = unit_circle_solutions_polled(&a, &b, &self.opts, &self.poll)?;
                        (sol.real, sol.complex.len(), sol.paths, sol.failed)
                    }
                    None => self.slider_group(g, &anchors)?,
                };
                self.out.complex_counts[self.group_slot[i]].push(count);
                self.out.paths[self.group_slot[i]].push(paths);
                self.out.failed_paths += failed;
                // each solution's elbows (the joints' assembly modes) label it
                let mut real: Vec<(String, f64, Vec<f64>)> = real
                    .into_iter()
                    .map(|phi| {
                        let mut at = pos.to_vec();
                        g.place(&phi, &anchors, |p, xy| at[p] = xy);
                        (g.elbow_label(|p| at[p]), g.conditioning_with(&phi, &anchors), phi)
                    })
                    .collect();
                real.sort_by(|x, y| x.0.cmp(&y.0).then(x.2[0].total_cmp(&y.2[0])));
                for k in 0..real.len() {
                    let (elbows, det, phi) = &real[k];
                    // solutions with the same elbows (rare) are told apart by a letter
                    let same = real.iter().filter(|r| &r.0 == elbows).count();
                    let nth = real[..k].iter().filter(|r| &r.0 == elbows).count();
                    let tag = if same > 1 { char::from(b'a' + (nth % 26) as u8).to_string() } else { String::new() };
                    g.place(phi, &anchors, |p, xy| pos[p] = xy);
                    dets.push(*det);
                    labels.push(format!("({elbows}){tag}"));
                    self.walk(i + 1, pos, dets, labels)?;
                    dets.pop();
                    labels.pop();
                }
                Ok(())
            }
        }
    }

    /// Every real assembly of a group with sliders: the homotopy's finite roots, the nearly
    /// real ones polished by the group's own Newton (kept where it converges next to the
    /// root); with the number of distinct finite roots, the paths tracked and those failed.
    fn slider_group(&self, g: &Group, anchors: &[Xy]) -> Result<Solved, Error> {
        let (a, b, quads) = g.homotopy_form(anchors);
        let roots = quadric_solutions_polled(&a, &b, &quads, &self.opts, &self.poll)?;
        // near a dead point the Jacobian's conditioning limits what rounding lets Newton
        // resolve (1e-14 there is PRECISION_LOSS, not a complex root): a looser tolerance
        // is tried before a nearly real root is called complex
        let tols = [1e-14, 1e-12, 1e-10];
        let n = g.n();
        let mut real: Vec<Vec<f64>> = Vec::new();
        let mut complex = 0;
        for z in &roots.complex {
            let zmax = z.iter().map(|v| v.norm()).fold(1.0, f64::max);
            let imag = z.iter().map(|v| v.im.abs()).fold(0.0, f64::max);
            let polished = (imag <= 1e-6 * zmax)
                .then(|| {
                    let guess = g.unknowns_of_root(z);
                    tols.iter().find_map(|&tol| {
                        let opts = NewtonOptions { tol, max_iter: 50, ..NewtonOptions::default() };
                        let out = g.solve(anchors, None, &guess, &opts, false);
                        let near = (0..n).all(|k| g.gap(k, out.phi[k], guess[k]).abs() <= 1e-4);
                        (out.status == Status::Converged && near).then(|| out.phi[..n].to_vec())
                    })
                })
                .flatten();
            match polished {
                Some(x) => {
                    if !real.iter().any(|r| (0..n).all(|k| g.gap(k, r[k], x[k]).abs() <= 1e-9)) {
                        real.push(x);
                    }
                }
                None => complex += 1,
            }
        }
        let count = complex + real.len();
        Ok((real, count, roots.paths, roots.failed))
    }

    fn emit(&mut self, pos: &[Xy], dets: &[f64], labels: &[String]) -> Result<(), Error> {
        let plan = self.plan;
        let n = self.out.list.len();
        try_grow(&mut self.out.list, 1, || format!("assemblies: a list of {} assemblies", n + 1))?;
        let points =
            pos.iter().map(|p| [p[0] * plan.scale + plan.origin[0], p[1] * plan.scale + plan.origin[1]]).collect();
        self.out.list.push(Assembly {
            points,
            step_det: dets.to_vec(),
            det: dets.iter().product(),
            label: labels.concat(),
        });
        Ok(())
    }
}

impl Scene {
    /// Every real assembly at input angle `theta` (every point solved). `interrupt` is
    /// asked every few thousand homotopy steps (Ctrl-C from Python).
    pub fn assemblies(
        &self,
        theta: f64,
        opts: &HomotopyOptions,
        interrupt: &dyn Interrupt,
    ) -> Result<Assemblies, Error> {
        self.plan(None)?.assemblies(theta, opts, interrupt)
    }
}
