//! One operation of a plan for sliders at one input value: the closed forms of
//! [`super::slide`] and the fused guide of a linear input (arms and shapes that change with
//! the input s), with first and second derivatives by the input when asked. The sweep
//! (continuation) and the assemblies (every side) both call it, so they agree bit for bit.

use super::dyad::{Dyad, DyadOut};
use super::op::Op;
use super::slide::{LineLine, Solved};
use crate::scene::vec2::{add, cdiv, cmul, cross, dot, scale, solve2, sub, Xy};

/// Positions, first and second derivatives by the input, indexed by point.
pub(crate) type Known<'a> = [&'a [Xy]; 3];

impl Op {
    /// True for the operations with two solutions (a side to choose and carry).
    pub(crate) fn sided(&self) -> bool {
        matches!(self, Op::Dyad(_) | Op::StrokeDyad(..) | Op::Rrp(_) | Op::Rpr(_))
    }

    /// The drawn side of a sided operation.
    pub(crate) fn drawn_side(&self) -> f64 {
        match self {
            Op::Dyad(d) | Op::StrokeDyad(d, _) => d.side,
            Op::Rrp(r) => r.side,
            Op::Rpr(r) => r.side,
            _ => 1.0,
        }
    }

    /// Solves a slider or stroke operation at input `s` on `side` from the known points
    /// `k` (derivatives too when `rates`). `None` where it cannot close (a dead point passed,
    /// or no assembly). Panics on the other operations (their callers solve them inline).
    pub(crate) fn solve_slider(&self, s: f64, k: Known<'_>, side: f64, rates: bool) -> Option<Solved> {
        match self {
            Op::StrokeCarry { a, b, num, den, .. } => {
                let d = add(den[0], scale(den[1], s));
                let m = stroke_ratio(num, den, s);
                let ab: [Xy; 3] = [0, 1, 2].map(|o| sub(k[o][*b], k[o][*a]));
                let mut x = [add(k[0][*a], cmul(m, ab[0])), [f64::NAN; 2], [f64::NAN; 2]];
                if rates {
                    let m1 = cdiv(sub(num[1], cmul(m, den[1])), d);
                    let m2 = scale(cdiv(cmul(m1, den[1]), d), -2.0);
                    x[1] = add(k[1][*a], add(cmul(m1, ab[0]), cmul(m, ab[1])));
                    x[2] = add(k[2][*a], add(add(cmul(m2, ab[0]), scale(cmul(m1, ab[1]), 2.0)), cmul(m, ab[2])));
                }
                Some(Solved { x, det: 1.0 })
            }
            Op::Offset { base, a, b, m, .. } => {
                let x = [0, 1, 2].map(|o| add(k[o][*base], cmul(*m, sub(k[o][*b], k[o][*a]))));
                Some(Solved { x, det: 1.0 })
            }
            Op::StrokeDyad(d, arms) => stroke_dyad(d, arms, s, k, side, rates),
            Op::Rrp(r) => {
                let l = r.line.at(k);
                r.solve([k[0][r.k], k[1][r.k], k[2][r.k]], &l, side, rates)
            }
            Op::Pp(pp) => {
                let (l1, l2) = (pp.lines[0].at(k), pp.lines[1].at(k));
                let out = pp.solve(&l1, &l2, rates);
                out.x[0][0].is_finite().then_some(out)
            }
            Op::Rpr(r) => r.solve([k[0][r.k], k[1][r.k], k[2][r.k]], [k[0][r.q], k[1][r.q], k[2][r.q]], side, rates),
            _ => unreachable!("solve_slider is for slider and stroke operations"),
        }
    }

    /// The position alone (no rates) of a slider or stroke operation at input `s` on
    /// `side`, and its conditioning (1 for the carries), from the known points' positions
    /// `at(point)`: what [`Op::solve_slider`] places, bit for bit. `None` where it cannot
    /// close. Panics on the other operations.
    #[inline(always)]
    pub(crate) fn place_slider(&self, s: f64, at: impl Fn(usize) -> Xy, side: f64) -> Option<(Xy, f64)> {
        match self {
            Op::StrokeCarry { a, b, num, den, .. } => {
                let ka = at(*a);
                Some((add(ka, cmul(stroke_ratio(num, den, s), sub(at(*b), ka))), 1.0))
            }
            Op::Offset { base, a, b, m, .. } => Some((add(at(*base), cmul(*m, sub(at(*b), at(*a)))), 1.0)),
            Op::StrokeDyad(d, arms) => {
                let (ra, rb) = (radius(&arms[0], s).0, radius(&arms[1], s).0);
                match d.solve_radii(at(d.k1), at(d.k2), side, ra, rb) {
                    DyadOut::Solved(p, det) => Some((p, stroke_det(det, arms, [ra, rb]))),
                    _ => None,
                }
            }
            Op::Rrp(r) => {
                let (p, d) = r.line.place(at(r.line.base), at(r.line.a), at(r.line.b));
                r.place(at(r.k), p, d, side)
            }
            Op::Pp(pp) => {
                let [l1, l2] = &pp.lines;
                let (p1, d1) = l1.place(at(l1.base), at(l1.a), at(l1.b));
                let (p2, d2) = l2.place(at(l2.base), at(l2.a), at(l2.b));
                let (x, det) = LineLine::place(p1, d1, p2, d2);
                x[0].is_finite().then_some((x, det))
            }
            Op::Rpr(r) => r.place(at(r.k), at(r.q), side).map(|(x, det, _)| (x, det)),
            _ => unreachable!("place_slider is for slider and stroke operations"),
        }
    }

    /// Signed conditioning of a slider step at positions `pos`.
    pub(crate) fn slider_det_at(&self, s: f64, pos: &[Xy]) -> f64 {
        let zero = vec![[0.0; 2]; pos.len()];
        let k: Known<'_> = [pos, &zero, &zero];
        match self {
            Op::StrokeDyad(d, arms) => {
                let (r1, r2) = (radius(&arms[0], s).0, radius(&arms[1], s).0);
                stroke_det(cross(sub(pos[d.k1], pos[d.p]), sub(pos[d.k2], pos[d.p])) / (r1 * r2), arms, [r1, r2])
            }
            Op::Rrp(r) => r.det_at(pos[r.p], pos[r.k], &r.line.at(k)),
            Op::Pp(pp) => {
                let (l1, l2) = (pp.lines[0].at(k), pp.lines[1].at(k));
                let (d1, d2) = (l1.d[0], l2.d[0]);
                cross(d1, d2) / (dot(d1, d1) * dot(d2, d2)).sqrt()
            }
            Op::Rpr(r) => r.det_at(pos[r.t], pos[r.k], pos[r.q]),
            _ => 1.0,
        }
    }
}

/// A fused guide's shape ratio m(s) = (num0 + s num1) / (den0 + s den1) (complex).
#[inline]
pub(crate) fn stroke_ratio(num: &[Xy; 2], den: &[Xy; 2], s: f64) -> Xy {
    cdiv(add(num[0], scale(num[1], s)), add(den[0], scale(den[1], s)))
}

/// An arm's length |e0 + s e1| and its first and second derivatives by s.
#[inline]
/// A stroke dyad's conditioning: the dyad's, times how far each stroked arm is from zero
/// length relative to its drawn length (at zero length the cylinder's direction, and the
/// fused body's rotation with it, is undefined: a degenerate case, 0 there).
fn stroke_det(det: f64, arms: &[[Xy; 2]; 2], radii: [f64; 2]) -> f64 {
    let mut det = det;
    for (arm, r) in arms.iter().zip(radii) {
        if arm[1] != [0.0; 2] {
            det *= (r / dot(arm[0], arm[0]).sqrt()).min(1.0);
        }
    }
    det
}

pub(crate) fn radius(arm: &[Xy; 2], s: f64) -> (f64, f64, f64) {
    let e = add(arm[0], scale(arm[1], s));
    let r = dot(e, e).sqrt();
    let r1 = dot(arm[1], e) / r;
    let r2 = (dot(arm[1], arm[1]) - r1 * r1) / r;
    (r, r1, r2)
}

fn stroke_dyad(d: &Dyad, arms: &[[Xy; 2]; 2], s: f64, k: Known<'_>, side: f64, rates: bool) -> Option<Solved> {
    let (ra, rb) = (radius(&arms[0], s), radius(&arms[1], s));
    let (a, b) = (k[0][d.k1], k[0][d.k2]);
    let DyadOut::Solved(p, det) = d.solve_radii(a, b, side, ra.0, rb.0) else { return None };
    let det = stroke_det(det, arms, [ra.0, rb.0]);
    let mut x = [p, [f64::NAN; 2], [f64::NAN; 2]];
    if rates {
        // (p - k_i) . (v - v_i) = r_i r_i' and, one order up,
        // (p - k_i) . (w - w_i) + |v - v_i|^2 = r_i'^2 + r_i r_i''
        let (e1, e2) = (sub(p, a), sub(p, b));
        let (va, vb) = (k[1][d.k1], k[1][d.k2]);
        if let Some(v) = solve2(e1, e2, dot(e1, va) + ra.0 * ra.1, dot(e2, vb) + rb.0 * rb.1) {
            let (d1, d2) = (sub(v, va), sub(v, vb));
            let c1 = dot(e1, k[2][d.k1]) - dot(d1, d1) + ra.1 * ra.1 + ra.0 * ra.2;
            let c2 = dot(e2, k[2][d.k2]) - dot(d2, d2) + rb.1 * rb.1 + rb.0 * rb.2;
            x[1] = v;
            x[2] = solve2(e1, e2, c1, c2).unwrap_or([f64::NAN; 2]);
        }
    }
    Some(Solved { x, det })
}
