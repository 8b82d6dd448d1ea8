//! A group's closures in the homotopy's form: `A z = b` in the rotations' (cos, sin),
//! with the quadrics of its sliders, and the unknowns from a root.

use super::{Group, Reader, Turn, HELD};
use crate::scene::vec2::{cmul, sub, Xy};
use crate::solve::homotopy::Quadric;

impl Group {
    /// The closures as `A z = b`, z = (cos phi_1..cos phi_N, sin phi_1..sin phi_N):
    /// M v = (c v_x - s v_y, s v_x + c v_y), b = -(a_plus - a_minus); `None` for a group
    /// with slides or known turns (no such form).
    pub(crate) fn linear_form(&self, anchors: &[Xy]) -> Option<(nalgebra::DMatrix<f64>, nalgebra::DVector<f64>)> {
        if self.has_slides() {
            return None;
        }
        let (m, n) = (2 * self.closures.len(), self.n());
        let mut a = nalgebra::DMatrix::zeros(m, 2 * n);
        let mut b = nalgebra::DVector::zeros(m);
        for (c, cl) in self.closures.iter().enumerate() {
            for t in &cl.terms {
                let Turn::Col(k) = t.turn else { return None };
                let u = t.v;
                a[(2 * c, k)] += u[0];
                a[(2 * c, n + k)] -= u[1];
                a[(2 * c + 1, k)] += u[1];
                a[(2 * c + 1, n + k)] += u[0];
            }
            let d = sub(anchors[cl.plus], anchors[cl.minus]);
            b[2 * c] = -d[0];
            b[2 * c + 1] = -d[1];
        }
        Some((a, b))
    }

    /// The closures of a group with sliders as `A z = b` with quadrics, for the homotopy:
    /// z holds each rotation column's (cos, sin) (cosines first, as in
    /// [`Group::linear_form`]), then per displacement column either (s cos, s sin) of its
    /// guide's unknown rotation, parallel to that (cos, sin) (a bilinear quadric), or s
    /// itself where its guide's rotation is known.
    pub(crate) fn homotopy_form(
        &self,
        anchors: &[Xy],
    ) -> (nalgebra::DMatrix<f64>, nalgebra::DVector<f64>, Vec<Quadric>) {
        let (nr, n) = (self.nrot, self.n());
        // where each slide column's variables start, and its guide's rotation column
        let mut at = vec![0usize; n];
        let mut next = 2 * nr;
        let mut quads: Vec<Quadric> = (0..nr).map(|r| Quadric::Circle { c: r, s: nr + r }).collect();
        for (k, r) in self.readers.iter().enumerate().skip(nr) {
            let Reader::Slide { term, .. } = r else { unreachable!("columns after the rotations slide") };
            at[k] = next;
            match term.turn {
                Turn::Col(g) => {
                    // (e, f) = s (c, s_g): e s_g = f c
                    quads.push(Quadric::Bilinear { a: next, b: nr + g, c: next + 1, d: g });
                    next += 2;
                }
                Turn::Known(..) => next += 1,
            }
        }
        let m = 2 * self.closures.len();
        let mut a = nalgebra::DMatrix::zeros(m, next);
        let mut b = nalgebra::DVector::zeros(m);
        let held = self.held_of(anchors);
        for (c, cl) in self.closures.iter().enumerate() {
            let mut rhs = sub(anchors[cl.plus], anchors[cl.minus]);
            let (rx, ry) = (2 * c, 2 * c + 1);
            for t in &cl.terms {
                // a held slide is part of the edge's vector (the input is given)
                let (v, slide) = match t.slide {
                    Some((HELD, _)) => (t.arm(&[], held), None),
                    other => (t.v, other),
                };
                match t.turn {
                    Turn::Col(g) => {
                        a[(rx, g)] += v[0];
                        a[(rx, nr + g)] -= v[1];
                        a[(ry, g)] += v[1];
                        a[(ry, nr + g)] += v[0];
                        if let Some((k, d)) = slide {
                            let (e, f) = (at[k], at[k] + 1);
                            a[(rx, e)] += d[0];
                            a[(rx, f)] -= d[1];
                            a[(ry, e)] += d[1];
                            a[(ry, f)] += d[0];
                        }
                    }
                    Turn::Known(ia, ib) => {
                        let mm = sub(anchors[ib], anchors[ia]);
                        let w = cmul(mm, v);
                        rhs = [rhs[0] + w[0], rhs[1] + w[1]];
                        if let Some((k, d)) = slide {
                            let md = cmul(mm, d);
                            a[(rx, at[k])] += md[0];
                            a[(ry, at[k])] += md[1];
                        }
                    }
                }
            }
            b[rx] = -rhs[0];
            b[ry] = -rhs[1];
        }
        (a, b, quads)
    }

    /// The unknowns (real parts) from a root `z` of [`Group::homotopy_form`].
    pub(crate) fn unknowns_of_root(&self, z: &[nalgebra::Complex<f64>]) -> Vec<f64> {
        let nr = self.nrot;
        let mut x: Vec<f64> = (0..nr).map(|r| z[nr + r].re.atan2(z[r].re)).collect();
        let mut next = 2 * nr;
        for r in self.readers.iter().skip(nr) {
            let Reader::Slide { term, .. } = r else { unreachable!("columns after the rotations slide") };
            match term.turn {
                Turn::Col(g) => {
                    // s = (s cos, s sin) . (cos, sin)
                    let (sin, cos) = x[g].sin_cos();
                    x.push(z[next].re * cos + z[next + 1].re * sin);
                    next += 2;
                }
                Turn::Known(..) => {
                    x.push(z[next].re);
                    next += 1;
                }
            }
        }
        x
    }
}
