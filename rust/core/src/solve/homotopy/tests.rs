//! Tests of the homotopy against independent truths: circle intersections, the four-bar's
//! closed form, Bezout counts, the published assembly counts of the Stephenson triad and
//! the double butterfly, and real roots checked by the crate's own Newton solver.

use super::*;
use crate::rng::SplitMix64;
use crate::solve::newton::{self, NewtonOptions, System};
use crate::wrap_angle;
use crate::{FourBar, Mode};
use nalgebra::{SMatrix, SVector};
use std::collections::HashMap;
use std::f64::consts::PI;

type P = [f64; 2];
/// A mechanism's A, b from its drawn joints.
type Builder = fn(&HashMap<char, P>) -> (DMatrix<f64>, DVector<f64>);

fn sub(a: P, b: P) -> P {
    [a[0] - b[0], a[1] - b[1]]
}

/// Closure equations of a group: each loop `sum sign R(phi_link) v = d` gives 2 rows.
struct Group {
    n: usize,
    rows: Vec<(Vec<f64>, f64)>,
}

impl Group {
    fn new(n: usize) -> Self {
        Self { n, rows: Vec::new() }
    }

    /// R(phi) v = (c v_x - s v_y, s v_x + c v_y).
    fn lp(&mut self, terms: &[(usize, P, f64)], d: P) -> &mut Self {
        let n = self.n;
        let (mut rx, mut ry) = (vec![0.0; 2 * n], vec![0.0; 2 * n]);
        for &(j, v, sg) in terms {
            rx[j] += sg * v[0];
            rx[n + j] -= sg * v[1];
            ry[j] += sg * v[1];
            ry[n + j] += sg * v[0];
        }
        self.rows.push((rx, d[0]));
        self.rows.push((ry, d[1]));
        self
    }

    fn ab(&self) -> (DMatrix<f64>, DVector<f64>) {
        let m = self.rows.len();
        let a = DMatrix::from_fn(m, 2 * self.n, |i, j| self.rows[i].0[j]);
        let b = DVector::from_fn(m, |i, _| self.rows[i].1);
        (a, b)
    }
}

/// Random named joints in [-1, 1]^2.
fn joints(rng: &mut SplitMix64, names: &str) -> HashMap<char, P> {
    names.chars().map(|c| (c, [2.0 * rng.uniform() - 1.0, 2.0 * rng.uniform() - 1.0])).collect()
}

fn dyad(p: P, q: P, v1: P, v2: P) -> (DMatrix<f64>, DVector<f64>) {
    Group::new(2).lp(&[(0, v1, 1.0), (1, v2, -1.0)], sub(q, p)).ab()
}

/// Ternary T (J1 J2 J3) on binaries from known P1, P2, P3. Unknowns: T, B1, B2, B3.
fn triad(j: &HashMap<char, P>) -> (DMatrix<f64>, DVector<f64>) {
    let g = |c| j[&c];
    Group::new(4)
        .lp(
            &[(1, sub(g('1'), g('p')), 1.0), (0, sub(g('2'), g('1')), 1.0), (2, sub(g('2'), g('q')), -1.0)],
            sub(g('q'), g('p')),
        )
        .lp(
            &[(1, sub(g('1'), g('p')), 1.0), (0, sub(g('3'), g('1')), 1.0), (3, sub(g('3'), g('r')), -1.0)],
            sub(g('r'), g('p')),
        )
        .ab()
}

/// Two ternaries T1 (about known 3; joints 1, 2) and T2 (about known 6; joints 4, 5),
/// binaries 1-4 and 2-5. Unknowns: T1, T2, B1, B2.
fn stephenson3(j: &HashMap<char, P>) -> (DMatrix<f64>, DVector<f64>) {
    let g = |c| j[&c];
    Group::new(4)
        .lp(
            &[(0, sub(g('1'), g('3')), 1.0), (2, sub(g('4'), g('1')), 1.0), (1, sub(g('4'), g('6')), -1.0)],
            sub(g('6'), g('3')),
        )
        .lp(
            &[(0, sub(g('2'), g('3')), 1.0), (3, sub(g('5'), g('2')), 1.0), (1, sub(g('5'), g('6')), -1.0)],
            sub(g('6'), g('3')),
        )
        .ab()
}

/// Double butterfly, ground bar A K, input ternary A B C given (input at A, a
/// ternary-bar joint). Unknowns: [B D E], [E H], [H I K], [D G], [F G I], [C F].
fn butterfly_bar_ground(j: &HashMap<char, P>) -> (DMatrix<f64>, DVector<f64>) {
    let g = |c| j[&c];
    let (r3, r4, r5, r6, r7, r8) = (0, 1, 2, 3, 4, 5);
    Group::new(6)
        .lp(
            &[(r3, sub(g('E'), g('B')), 1.0), (r4, sub(g('H'), g('E')), 1.0), (r5, sub(g('H'), g('K')), -1.0)],
            sub(g('K'), g('B')),
        )
        .lp(
            &[
                (r3, sub(g('D'), g('B')), 1.0),
                (r6, sub(g('G'), g('D')), 1.0),
                (r5, sub(g('I'), g('K')), -1.0),
                (r7, sub(g('G'), g('I')), -1.0),
            ],
            sub(g('K'), g('B')),
        )
        .lp(
            &[(r8, sub(g('F'), g('C')), 1.0), (r5, sub(g('I'), g('K')), -1.0), (r7, sub(g('F'), g('I')), -1.0)],
            sub(g('K'), g('C')),
        )
        .ab()
}

/// Ternary H I K grounded, its butterfly partner F G I given (input at the butterfly
/// hinge I). Unknowns: [A K], [A B C], [B D E], [E H], [D G], [C F].
fn butterfly_hinge_input(j: &HashMap<char, P>) -> (DMatrix<f64>, DVector<f64>) {
    let g = |c| j[&c];
    let (r1, r2, r3, r4, r6, r8) = (0, 1, 2, 3, 4, 5);
    Group::new(6)
        .lp(
            &[(r1, sub(g('A'), g('K')), 1.0), (r2, sub(g('C'), g('A')), 1.0), (r8, sub(g('C'), g('F')), -1.0)],
            sub(g('F'), g('K')),
        )
        .lp(
            &[
                (r1, sub(g('A'), g('K')), 1.0),
                (r2, sub(g('B'), g('A')), 1.0),
                (r3, sub(g('E'), g('B')), 1.0),
                (r4, sub(g('E'), g('H')), -1.0),
            ],
            sub(g('H'), g('K')),
        )
        .lp(
            &[
                (r1, sub(g('A'), g('K')), 1.0),
                (r2, sub(g('B'), g('A')), 1.0),
                (r3, sub(g('D'), g('B')), 1.0),
                (r6, sub(g('D'), g('G')), -1.0),
            ],
            sub(g('G'), g('K')),
        )
        .ab()
}

/// Ternary H I K grounded, bar E H given (input at H, a ternary-bar joint).
/// Unknowns: [A K], [A B C], [B D E], [D G], [F G I], [C F].
fn butterfly_ternary_ground_bar_input(j: &HashMap<char, P>) -> (DMatrix<f64>, DVector<f64>) {
    let g = |c| j[&c];
    let (r1, r2, r3, r6, r7, r8) = (0, 1, 2, 3, 4, 5);
    Group::new(6)
        .lp(
            &[(r1, sub(g('A'), g('K')), 1.0), (r2, sub(g('B'), g('A')), 1.0), (r3, sub(g('B'), g('E')), -1.0)],
            sub(g('E'), g('K')),
        )
        .lp(
            &[
                (r1, sub(g('A'), g('K')), 1.0),
                (r2, sub(g('C'), g('A')), 1.0),
                (r8, sub(g('F'), g('C')), 1.0),
                (r7, sub(g('F'), g('I')), -1.0),
            ],
            sub(g('I'), g('K')),
        )
        .lp(
            &[(r3, sub(g('D'), g('E')), 1.0), (r6, sub(g('G'), g('D')), 1.0), (r7, sub(g('G'), g('I')), -1.0)],
            sub(g('I'), g('E')),
        )
        .ab()
}

const BUTTERFLY: &str = "ABCDEFGHIK";

/// Closure in the angles, for the crate's own Newton solver (the independent check).
struct Closure<'a, const N: usize> {
    a: &'a DMatrix<f64>,
    b: &'a DVector<f64>,
}

impl<const N: usize> System<N> for Closure<'_, N> {
    fn eval(&self, x: &SVector<f64, N>) -> (SVector<f64, N>, SMatrix<f64, N, N>) {
        let mut f = SVector::<f64, N>::zeros();
        let mut j = SMatrix::<f64, N, N>::zeros();
        let sc: [(f64, f64); N] = std::array::from_fn(|k| x[k].sin_cos());
        for i in 0..N {
            f[i] = -self.b[i];
            for (k, &(s, c)) in sc.iter().enumerate() {
                f[i] += self.a[(i, k)] * c + self.a[(i, N + k)] * s;
                j[(i, k)] = -self.a[(i, k)] * s + self.a[(i, N + k)] * c;
            }
        }
        (f, j)
    }
    fn scale(&self) -> f64 {
        self.a.amax()
    }
    fn normalize(&self, x: &mut SVector<f64, N>) {
        x.iter_mut().for_each(|v| *v = wrap_angle(*v));
    }
}

/// max |A z(phi) - b| on the original equations.
fn residual(a: &DMatrix<f64>, b: &DVector<f64>, phi: &[f64]) -> f64 {
    let z = DVector::from_iterator(2 * phi.len(), phi.iter().map(|p| p.cos()).chain(phi.iter().map(|p| p.sin())));
    (a * z - b).amax()
}

fn contains(real: &[Vec<f64>], phi: &[f64], tol: f64) -> bool {
    real.iter().any(|r| angles_close(r, phi, tol))
}

/// Every real root satisfies the original equations to 1e-12; every root found by
/// `starts` random Newton starts of the crate's solver is among them. Returns how
/// many distinct roots the starts found.
fn check_real<const N: usize>(a: &DMatrix<f64>, b: &DVector<f64>, sol: &Solutions, starts: usize, seed: u64) -> usize {
    for phi in &sol.real {
        assert_eq!(phi.len(), N);
        assert!(phi.iter().all(|p| *p > -PI && *p <= PI));
        let r = residual(a, b, phi);
        assert!(r <= 1e-12 * a.amax().max(1.0), "residual {r:e}");
    }
    // every complex root satisfies the closure and the circles; non-real roots pair up
    // with their conjugates
    let scale = a.amax().max(b.amax()).max(1.0);
    for z in &sol.complex {
        assert_eq!(z.len(), 2 * N);
        let zmax = z.iter().map(|v| v.norm()).fold(1.0, f64::max);
        for i in 0..N {
            let mut r = C::new(-b[i], 0.0);
            for k in 0..2 * N {
                r += z[k] * a[(i, k)];
            }
            assert!(r.norm() <= 1e-10 * scale * zmax, "closure residual {:e}", r.norm());
            let q = z[i] * z[i] + z[N + i] * z[N + i] - 1.0;
            assert!(q.norm() <= 1e-10 * zmax * zmax, "circle residual {:e}", q.norm());
        }
        let conj: Vec<C> = z.iter().map(|v| v.conj()).collect();
        assert!(sol.complex.iter().any(|w| w.iter().zip(&conj).all(|(p, q)| (p - q).norm() <= 1e-8 * zmax)));
    }
    let sys = Closure::<N> { a, b };
    let opts = NewtonOptions { tol: 1e-11, max_iter: 60, singular: 1e-8 };
    let mut rng = SplitMix64(seed);
    let mut found: Vec<Vec<f64>> = Vec::new();
    for _ in 0..starts {
        let x0 = SVector::<f64, N>::from_fn(|_, _| PI * (2.0 * rng.uniform() - 1.0));
        let out = newton::solve(&sys, x0, &opts, None);
        if out.status.is_success() {
            let phi: Vec<f64> = out.x.iter().map(|&v| wrap_angle(v)).collect();
            assert!(contains(&sol.real, &phi, 1e-7), "Newton found {phi:?}, not among {:?}", sol.real);
            if !contains(&found, &phi, 1e-7) {
                found.push(phi);
            }
        }
    }
    found.len()
}

fn solve(a: &DMatrix<f64>, b: &DVector<f64>) -> Solutions {
    unit_circle_solutions(a, b, &HomotopyOptions::default()).unwrap()
}

#[test]
fn homotopy_dyad_matches_circle_intersection() {
    let (p, q) = ([0.1, -0.2], [1.3, 0.25]);
    let (r1, r2, a1, a2) = (1.0_f64, 0.8_f64, 0.3_f64, -1.1_f64);
    let v1 = [r1 * a1.cos(), r1 * a1.sin()];
    let v2 = [r2 * a2.cos(), r2 * a2.sin()];
    let (a, b) = dyad(p, q, v1, v2);
    let sol = solve(&a, &b);
    assert_eq!(sol.complex.len(), 2);
    assert_eq!(sol.real.len(), 2);
    // two runs of C(2, 1) = 2 paths (the isotropic start system; total degree: 2^2)
    assert_eq!(sol.paths, 4);
    // closed form: J = P + a e +- h e_perp
    let u = sub(q, p);
    let d = (u[0] * u[0] + u[1] * u[1]).sqrt();
    let e = [u[0] / d, u[1] / d];
    let along = (r1 * r1 - r2 * r2 + d * d) / (2.0 * d);
    let h = (r1 * r1 - along * along).sqrt();
    for sg in [1.0, -1.0] {
        let jx = [p[0] + along * e[0] - sg * h * e[1], p[1] + along * e[1] + sg * h * e[0]];
        let phi1 = wrap_angle((jx[1] - p[1]).atan2(jx[0] - p[0]) - a1);
        let phi2 = wrap_angle((jx[1] - q[1]).atan2(jx[0] - q[0]) - a2);
        assert!(contains(&sol.real, &[phi1, phi2], 1e-12), "{phi1} {phi2} not in {:?}", sol.real);
    }
    assert_eq!(check_real::<2>(&a, &b, &sol, 2000, 1), 2);
}

#[test]
fn homotopy_dyad_that_cannot_close_has_two_complex_roots_and_no_real() {
    let (a, b) = dyad([0.0, 0.0], [2.5, 0.3], [1.0, 0.0], [0.0, 0.9]);
    let sol = solve(&a, &b);
    assert_eq!(sol.complex.len(), 2);
    assert!(sol.real.is_empty());
    // the two roots are complex conjugates, each on the circles
    for z in &sol.complex {
        assert!(z.iter().any(|v| v.im.abs() > 1e-3));
        for j in 0..2 {
            assert!((z[j] * z[j] + z[2 + j] * z[2 + j] - 1.0).norm() < 1e-12);
        }
    }
    assert_eq!(check_real::<2>(&a, &b, &sol, 500, 2), 0);
}

#[test]
fn homotopy_fourbar_with_given_crank_matches_the_closed_form() {
    let fb = FourBar::new(2.0, 0.7, 1.8, 1.5).unwrap();
    for theta2 in [0.3, 1.7, -2.4] {
        let (s2, c2) = f64::sin_cos(theta2);
        let crank = [0.7 * c2, 0.7 * s2];
        // coupler A->B (r3, 0) turned by theta3; rocker O4->B (r4, 0) turned by theta4
        let (a, b) = dyad(crank, [2.0, 0.0], [1.8, 0.0], [1.5, 0.0]);
        let sol = solve(&a, &b);
        assert_eq!(sol.complex.len(), 2);
        assert_eq!(sol.real.len(), 2);
        for mode in [Mode::Open, Mode::Crossed] {
            let crate::ClosedForm::Solved { theta3, theta4, .. } = fb.closed_form(theta2, mode) else { panic!() };
            assert!(contains(&sol.real, &[theta3, theta4], 1e-12), "{theta3} {theta4} not in {:?}", sol.real);
        }
    }
}

#[test]
fn homotopy_stephenson_triad_has_six_roots() {
    for seed in 0..4 {
        let mut rng = SplitMix64(100 + seed);
        let j = joints(&mut rng, "123pqr");
        let (a, b) = triad(&j);
        let sol = solve(&a, &b);
        eprintln!(
            "triad seed {seed}: {} complex, {} real, per run {:?}, failed {:?}, infinite {}",
            sol.complex.len(),
            sol.real.len(),
            sol.per_run_found,
            sol.per_run_failed,
            sol.infinite
        );
        assert_eq!(sol.complex.len(), 6, "seed {seed}: {:?}", sol.per_run_found);
        assert!(contains(&sol.real, &[0.0; 4], 1e-12), "drawn pose missing");
        assert!(sol.real.len().is_multiple_of(2));
        check_real::<4>(&a, &b, &sol, 2000, seed);
    }
}

#[test]
fn homotopy_stephenson3_group_has_six_roots() {
    for seed in 0..4 {
        let mut rng = SplitMix64(200 + seed);
        let j = joints(&mut rng, "123456");
        let (a, b) = stephenson3(&j);
        let sol = solve(&a, &b);
        eprintln!(
            "stephenson3 seed {seed}: {} complex, {} real, per run {:?}, failed {:?}, infinite {}",
            sol.complex.len(),
            sol.real.len(),
            sol.per_run_found,
            sol.per_run_failed,
            sol.infinite
        );
        assert_eq!(sol.complex.len(), 6, "seed {seed}: {:?}", sol.per_run_found);
        assert!(contains(&sol.real, &[0.0; 4], 1e-12), "drawn pose missing");
        check_real::<4>(&a, &b, &sol, 2000, seed);
    }
}

#[test]
fn homotopy_double_butterfly_counts() {
    for seed in 0..3 {
        let mut rng = SplitMix64(300 + seed);
        let j = joints(&mut rng, BUTTERFLY);
        for (name, build, expected) in [
            ("bar ground, input at A", butterfly_bar_ground as Builder, 16),
            ("ternary ground, input at hinge I", butterfly_hinge_input, 18),
            ("ternary ground, input at H", butterfly_ternary_ground_bar_input, 16),
        ] {
            let (a, b) = build(&j);
            let sol = solve(&a, &b);
            eprintln!(
                "seed {seed} {name}: {} complex, {} real, per run {:?}, failed {}, infinite {}",
                sol.complex.len(),
                sol.real.len(),
                sol.per_run_found,
                sol.failed,
                sol.infinite
            );
            assert_eq!(sol.complex.len(), expected, "{name}");
            assert!(contains(&sol.real, &[0.0; 6], 1e-12), "drawn pose missing");
            // 2000 Newton starts are slow in a debug build: every mechanism on the
            // first geometry, the bar-ground one on all
            if seed == 0 || expected == 16 && name.starts_with("bar") {
                let newton_found = check_real::<6>(&a, &b, &sol, 2000, seed);
                assert!(newton_found >= 1);
            } else {
                check_real::<6>(&a, &b, &sol, 0, seed);
            }
        }
    }
}

/// Random dense A (N x 2N) with b = A z(phi*): generic, so all 2^N roots are finite.
fn dense(n: usize, seed: u64) -> (DMatrix<f64>, DVector<f64>, Vec<f64>) {
    let mut rng = SplitMix64(seed);
    let a = DMatrix::from_fn(n, 2 * n, |_, _| 2.0 * rng.uniform() - 1.0);
    let phi: Vec<f64> = (0..n).map(|_| PI * (2.0 * rng.uniform() - 1.0)).collect();
    let z = DVector::from_iterator(2 * n, phi.iter().map(|p| p.cos()).chain(phi.iter().map(|p| p.sin())));
    let b = &a * z;
    (a, b, phi)
}

#[test]
fn homotopy_generic_dense_system_has_all_bezout_roots() {
    let (a, b, phi) = dense(6, 7);
    let sol = solve(&a, &b);
    assert_eq!(sol.complex.len(), 64, "{:?} failed {}", sol.per_run_found, sol.failed);
    assert!(contains(&sol.real, &phi, 1e-12));
    check_real::<6>(&a, &b, &sol, 2000, 7);
}

/// N = 10: 1024 finite roots per run (release: a few seconds in debug is too slow).
#[test]
#[ignore]
fn homotopy_ten_links_dense() {
    let (a, b, phi) = dense(10, 11);
    let t = std::time::Instant::now();
    let sol = solve(&a, &b);
    eprintln!(
        "N = 10: {} complex, {} real, per run {:?}, failed {:?}, infinite {}, {:.0} ms",
        sol.complex.len(),
        sol.real.len(),
        sol.per_run_found,
        sol.per_run_failed,
        sol.infinite,
        t.elapsed().as_secs_f64() * 1e3
    );
    assert!(contains(&sol.real, &phi, 1e-12));
    check_real::<10>(&a, &b, &sol, 2000, 11);
    assert_eq!(sol.complex.len(), 1024);
}

/// A geometry (number 87 of the spread-length statistics set) where run 2 of the
/// default options has a path jump: two paths end on one root. Retracking those two
/// paths with finer steps recovers the lost root, so each run still finds all 16.
#[test]
fn homotopy_path_jump_is_detected_and_retracked() {
    let mut rng = SplitMix64(4444);
    let mut j = spread_joints(&mut rng, 1.0);
    for _ in 0..87 {
        j = spread_joints(&mut rng, 1.0);
    }
    let (a, b) = butterfly_bar_ground(&j);
    // (the total-degree start system: this geometry's jump is one of its paths)
    let sol = circle_solutions(&a, &b, &HomotopyOptions::default(), &Poll::new(&Never), false).unwrap();
    assert_eq!(sol.per_run_jumps, vec![0, 1]);
    assert_eq!(sol.per_run_found, vec![16, 16]);
    assert_eq!(sol.complex.len(), 16);
    check_real::<6>(&a, &b, &sol, 2000, 87);
}

/// Units do not matter: the same triad in metres, millimetres and kilometres gives the
/// same angles.
#[test]
fn homotopy_is_scale_invariant() {
    let mut rng = SplitMix64(100);
    let j = joints(&mut rng, "123pqr");
    let (a, b) = triad(&j);
    let base = solve(&a, &b);
    for f in [1e3, 1e-3] {
        let jf: HashMap<char, P> = j.iter().map(|(k, p)| (*k, [p[0] * f, p[1] * f])).collect();
        let (a, b) = triad(&jf);
        let sol = solve(&a, &b);
        assert_eq!(sol.complex.len(), 6);
        assert_eq!(sol.real.len(), base.real.len());
        assert!(sol.real.iter().all(|r| contains(&base.real, r, 1e-10)));
    }
}

/// A dyad far from closing: its two complex roots grow like the anchor distance d
/// (|cos phi| ~ d / r); both are found up to d = 1e5 (|z| ~ 7e4).
#[test]
fn homotopy_far_from_closing_dyad() {
    for d in [10.0, 1e2, 1e3, 1e4, 1e5] {
        let (a, b) = dyad([0.0, 0.0], [d, 0.0], [1.0, 0.0], [0.0, 0.7]);
        let sol = solve(&a, &b);
        let zmax = sol.complex.iter().flatten().map(|v| v.norm()).fold(0.0, f64::max);
        eprintln!("dyad, anchors {d:e} apart: {} complex roots (max |z| {zmax:.1e}), {} real, per run {:?}, failed {}, infinite {}", sol.complex.len(), sol.real.len(), sol.per_run_found, sol.failed, sol.infinite);
        assert!(sol.real.is_empty());
        assert_eq!(sol.complex.len(), 2);
    }
}

#[test]
fn homotopy_rejects_misuse() {
    let o = HomotopyOptions::default();
    let a = DMatrix::<f64>::zeros(2, 4);
    let b = DVector::<f64>::zeros(2);
    assert!(unit_circle_solutions(&a, &b, &o).is_err()); // zero rows: rank deficient
    let mut a = DMatrix::<f64>::from_row_slice(2, 4, &[1.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0]);
    assert!(unit_circle_solutions(&a, &b, &o).is_err()); // dependent rows
    a[(1, 3)] = 1.0;
    assert!(unit_circle_solutions(&a, &DVector::zeros(3), &o).is_err());
    assert!(unit_circle_solutions(&DMatrix::zeros(2, 3), &b, &o).is_err());
    assert!(unit_circle_solutions(&DMatrix::zeros(0, 0), &DVector::zeros(0), &o).is_err());
    let mut bad = a.clone();
    bad[(0, 0)] = f64::NAN;
    assert!(unit_circle_solutions(&bad, &b, &o).is_err());
    assert!(unit_circle_solutions(&a, &b, &HomotopyOptions { runs: 0, ..o }).is_err());
    assert!(unit_circle_solutions(&a, &b, &HomotopyOptions { max_step: 0.0, ..o }).is_err());
    assert!(unit_circle_solutions(&DMatrix::zeros(17, 34), &DVector::zeros(17), &o).is_err());
    let mut huge = DVector::zeros(2);
    huge[0] = 1e300;
    let tiny = DMatrix::from_row_slice(2, 4, &[1e-300, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0]);
    assert!(unit_circle_solutions(&tiny, &huge, &o).is_err());
    assert!(unit_circle_solutions(&a, &b, &o).is_ok());
}

#[test]
fn homotopy_degenerate_input_neither_panics_nor_hangs() {
    // parallelogram-like dyad with coincident anchors and equal links: a circle of
    // solutions (not isolated), and a step budget of 1 step per path
    let (a, b) = dyad([0.0, 0.0], [0.0, 0.0], [1.0, 0.0], [1.0, 0.0]);
    let r = unit_circle_solutions(&a, &b, &HomotopyOptions::default());
    eprintln!("coincident anchors, equal links: {r:?}");
    assert!(r.is_ok());
    let (a, b) = dyad([0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [1.0, 0.0]);
    let sol = unit_circle_solutions(&a, &b, &HomotopyOptions { max_steps: 1, ..Default::default() }).unwrap();
    assert_eq!(sol.failed + sol.infinite, sol.paths);
    // tangent circles: a double real root
    let (a, b) = dyad([0.0, 0.0], [2.0, 0.0], [1.0, 0.0], [1.0, 0.0]);
    let sol = unit_circle_solutions(&a, &b, &HomotopyOptions::default()).unwrap();
    eprintln!("tangent circles: real {:?}, complex {}, failed {}", sol.real, sol.complex.len(), sol.failed);
    // the double root (0, pi) is found to about sqrt(eps), possibly twice
    assert!(!sol.real.is_empty());
    assert!(sol.real.iter().all(|r| angles_close(r, &[0.0, PI], 1e-7)));
}

/// Random double-butterfly joints, each scaled by 10^U(-spread, spread).
fn spread_joints(rng: &mut SplitMix64, spread: f64) -> HashMap<char, P> {
    let mut j = joints(rng, BUTTERFLY);
    for c in BUTTERFLY.chars() {
        let f = 10f64.powf(spread * (2.0 * rng.uniform() - 1.0));
        let p = j.get_mut(&c).unwrap();
        *p = [p[0] * f, p[1] * f];
    }
    j
}

#[test]
fn homotopy_stops_when_interrupted() {
    let mut rng = SplitMix64(300);
    let (a, b) = butterfly_hinge_input(&joints(&mut rng, BUTTERFLY));
    let yes = || true;
    // (16 runs: enough steps that the poll, asked every 4096, is asked at all)
    let r = unit_circle_solutions_polled(&a, &b, &HomotopyOptions::new(1, 16).unwrap(), &Poll::new(&yes));
    assert_eq!(r, Err(Error::Interrupted));
    let opts = HomotopyOptions::new(7, 1).unwrap();
    assert_eq!((opts.seed, opts.runs), (7, 1));
    for bad in [0, 17, -1] {
        let e = HomotopyOptions::new(7, bad).unwrap_err().to_string();
        assert!(e.starts_with("runs must be an integer in 1..=16"), "{e}");
    }
}

/// The paths of a run are tracked on all cores: the solutions (roots, their order, the
/// paths' accounting and steps) are the same, bit for bit, on one thread and on all.
#[test]
fn homotopy_is_the_same_on_one_thread_and_on_all() {
    let mut rng = SplitMix64(301);
    let j = joints(&mut rng, BUTTERFLY);
    for build in [butterfly_bar_ground as Builder, butterfly_hinge_input] {
        let (a, b) = build(&j);
        let all = solve(&a, &b);
        let one = crate::parallel::with_threads(Some(1), || solve(&a, &b)).unwrap();
        assert!(all.paths >= PARALLEL_PATHS, "{}", all.paths);
        assert_eq!(all, one);
    }
}
