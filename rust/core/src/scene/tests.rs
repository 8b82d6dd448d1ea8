//! Scene tests against independent truths: the four-bar's closed form, loop closure by
//! substitution, rigidity.

use super::vec2::{cross, sub};
use super::*;
use crate::error::Error;
use crate::interrupt::Never;
use crate::solve::homotopy::HomotopyOptions;
use crate::solve::newton::NewtonOptions;
use crate::{FourBar, Mode};

fn spec(points: &[(&str, Xy)], links: &[(&str, &[&str])], ground: &str, input: (&str, &str)) -> SceneSpec {
    SceneSpec {
        points: points.iter().map(|(n, p)| (n.to_string(), *p)).collect(),
        links: links.iter().map(|(n, ps)| (n.to_string(), ps.iter().map(|p| p.to_string()).collect())).collect(),
        ground: ground.into(),
        input: (input.0.into(), input.1.into()),
        output: None,
        ..Default::default()
    }
}

pub(crate) fn fourbar(mode: f64) -> SceneSpec {
    let b = [4.0, mode * 21f64.sqrt()];
    spec(
        &[("O2", [0.0, 0.0]), ("O4", [6.0, 0.0]), ("A", [2.0, 0.0]), ("B", b)],
        &[("ground", &["O2", "O4"]), ("crank", &["O2", "A"]), ("coupler", &["A", "B"]), ("rocker", &["O4", "B"])],
        "ground",
        ("crank", "O2"),
    )
}

/// A sweep's outputs.
type Run = SceneSweepBuffers;

fn run(plan: &Plan, theta: &[f64]) -> Run {
    let mut r = SceneSweepBuffers::new(plan, theta.len(), false).unwrap();
    let opts = SceneSweepOptions::new(NewtonOptions::default(), 0.05, None).unwrap();
    plan.sweep(theta, &opts, r.out(), &crate::interrupt::Never).unwrap();
    r
}

fn grid(n: usize) -> Vec<f64> {
    (0..n).map(|k| k as f64 * std::f64::consts::TAU / (n - 1) as f64).collect()
}

#[test]
fn fourbar_scene_matches_the_closed_form_in_both_modes() {
    for (sign, mode) in [(1.0, Mode::Open), (-1.0, Mode::Crossed)] {
        let sc = Scene::new(fourbar(sign)).unwrap();
        let names = ["coupler".to_string(), "rocker".to_string()];
        let plan = sc.plan(Some(&names)).unwrap();
        assert_eq!(plan.steps().len(), 1);
        assert_eq!(plan.steps()[0].kind, StepKind::Dyad);
        let theta = grid(361);
        let r = run(&plan, &theta);
        let fb = FourBar::new(6.0, 2.0, 5.0, 5.0).unwrap();
        for (k, &t) in theta.iter().enumerate() {
            let crate::ClosedForm::Solved { theta3, theta4, .. } = fb.closed_form(t, mode) else { panic!() };
            assert_eq!(r.status[k], 0);
            assert!((r.angles[2 * k] - theta3).abs() < 1e-12, "{k}");
            assert!((r.angles[2 * k + 1] - theta4).abs() < 1e-12, "{k}");
            assert!(r.det[k] * sign > 0.0);
        }
    }
}

/// Stephenson III: ground B3 = (j3, j7), input B4 pivoted at j7 driving j6; the links
/// T1 = (j3, j1, j2), B1 = (j1, j4), T2 = (j4, j5, j6), B2 = (j2, j5) form one group.
fn stephenson() -> SceneSpec {
    spec(
        &[
            ("j3", [0.0, 0.0]),
            ("j7", [4.0, 0.0]),
            ("j6", [4.6, 1.2]),
            ("j1", [0.4, 2.0]),
            ("j2", [1.6, 1.5]),
            ("j4", [2.2, 3.1]),
            ("j5", [3.1, 2.4]),
        ],
        &[
            ("B3", &["j3", "j7"]),
            ("B4", &["j7", "j6"]),
            ("T1", &["j3", "j1", "j2"]),
            ("B1", &["j1", "j4"]),
            ("T2", &["j4", "j5", "j6"]),
            ("B2", &["j2", "j5"]),
        ],
        "B3",
        ("B4", "j7"),
    )
}

#[test]
fn stephenson_group_closes_and_stays_rigid() {
    let sp = stephenson();
    let sc = Scene::new(sp.clone()).unwrap();
    let plan = sc.plan(None).unwrap();
    assert_eq!(plan.steps().len(), 1);
    assert_eq!(plan.steps()[0].kind, StepKind::Group);
    assert_eq!(plan.steps()[0].unknowns.len(), 4);
    let theta: Vec<f64> = (0..41).map(|k| sc.input_angle() + k as f64 * 0.01).collect();
    let r = run(&plan, &theta);
    let np = plan.points().len();
    let at = |k: usize, name: &str| {
        let j = plan.points().iter().position(|&p| sc.point_names()[p] == name).unwrap();
        [r.points[2 * (k * np + j)], r.points[2 * (k * np + j) + 1]]
    };
    let d = |a: Xy, b: Xy| ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt();
    let drawn = |name: &str| sp.points.iter().find(|p| p.0 == name).unwrap().1;
    for k in 0..theta.len() {
        assert_eq!(r.status[k], 0, "{k}");
        for (_, pts) in &sp.links {
            for (i, a) in pts.iter().enumerate() {
                for b in &pts[i + 1..] {
                    let err = (d(at(k, a), at(k, b)) - d(drawn(a), drawn(b))).abs();
                    assert!(err < 1e-12, "{k} {a} {b} {err}");
                }
            }
        }
        // orientation of each ternary kept
        let tri = |a: &str, b: &str, c: &str, f: &dyn Fn(&str) -> Xy| cross(sub(f(b), f(a)), sub(f(c), f(a)));
        let now = |n: &str| at(k, n);
        assert!(tri("j3", "j1", "j2", &now) * tri("j3", "j1", "j2", &drawn) > 0.0);
        assert!(tri("j4", "j5", "j6", &now) * tri("j4", "j5", "j6", &drawn) > 0.0);
    }
    assert!(r.nit[1..].iter().all(|&n| n <= 3), "{:?}", r.nit);
}

#[test]
fn validation_names_the_entry() {
    let mut s = fourbar(1.0);
    s.links[2].1.push("Q".into());
    assert_eq!(Scene::new(s).unwrap_err().to_string(), "links.coupler: unknown point \"Q\"");
    let mut s = fourbar(1.0);
    s.input.1 = "A".into();
    assert!(Scene::new(s).unwrap_err().to_string().starts_with("input.pivot: \"A\" is not on the ground link"));
    let mut s = fourbar(1.0);
    s.links.push(("brace".into(), vec!["A".into(), "O4".into()]));
    assert!(Scene::new(s).unwrap_err().to_string().starts_with("mobility: Gruebler"));
    // drawn at a dead point: A, B, O4 in line
    let mut s = fourbar(1.0);
    s.points[3].1 = [2.0 + 5.0 * (4.0 / 5.0f64), 0.0];
    s.points[1].1 = [2.0 + 5.0 + 5.0 - 0.0, 0.0];
    let e = Scene::new(s).unwrap_err().to_string();
    assert!(e.starts_with("mobility: the constraint Jacobian"), "{e}");
}

fn four_bar_lengths(r: [f64; 4], mode: f64, t2: f64) -> SceneSpec {
    let fb = FourBar::new(r[0], r[1], r[2], r[3]).unwrap();
    let m = if mode > 0.0 { Mode::Open } else { Mode::Crossed };
    let crate::ClosedForm::Solved { theta3, .. } = fb.closed_form(t2, m) else { panic!("not assemblable") };
    let a = [r[1] * t2.cos(), r[1] * t2.sin()];
    let b = [a[0] + r[2] * theta3.cos(), a[1] + r[2] * theta3.sin()];
    spec(
        &[("O2", [0.0, 0.0]), ("O4", [r[0], 0.0]), ("A", a), ("B", b)],
        &[("ground", &["O2", "O4"]), ("crank", &["O2", "A"]), ("coupler", &["A", "B"]), ("rocker", &["O4", "B"])],
        "ground",
        ("crank", "O2"),
    )
}

#[test]
fn non_grashof_trace_turns_at_the_toggles_and_closes() {
    let r = [4.0, 3.0, 1.5, 2.0];
    let sc = Scene::new(four_bar_lengths(r, 1.0, 0.0)).unwrap();
    let tracer = Tracer::new(&sc).unwrap();
    let tr = tracer.trace_from(&sc.xy, &TraceOptions::default(), &Never).unwrap();
    assert!(tr.closed, "{} points", tr.theta.len());
    let np = sc.names.len();
    let m = tr.theta.len();
    for (p, q) in tr.points[..np].iter().zip(&tr.points[(m - 1) * np..]) {
        assert!((p[0] - q[0]).abs() < 1e-9 && (p[1] - q[1]).abs() < 1e-9);
    }
    let fb = FourBar::new(r[0], r[1], r[2], r[3]).unwrap();
    let toggles = fb.limits(Mode::Open).toggles;
    assert_eq!(tr.turning_points.len(), 2, "{:?}", tr.turning_points);
    for tp in &tr.turning_points {
        let w = crate::wrap_angle(*tp);
        assert!(toggles.iter().any(|t| (t - w).abs() < 1e-9), "{w} vs {toggles:?}");
    }
    let changes = tr.det.windows(2).filter(|w| w[0] * w[1] < 0.0).count();
    assert_eq!(changes, 2);
}

#[test]
fn crank_rocker_has_two_full_turn_circuits() {
    let sc = Scene::new(fourbar(1.0)).unwrap();
    let tracer = Tracer::new(&sc).unwrap();
    let (asm, circuits) = tracer.circuits(0.3, &HomotopyOptions::default(), &TraceOptions::default(), &Never).unwrap();
    assert_eq!(asm.list.len(), 2);
    assert_eq!(circuits.len(), 2);
    for c in &circuits {
        assert_eq!(c.assemblies.len(), 1);
        assert!(c.turning_points.is_empty());
        assert!((c.net_turn.abs() - std::f64::consts::TAU).abs() < 1e-9, "{}", c.net_turn);
    }
}

#[test]
fn stephenson_group_assemblies_close_their_loops() {
    // the Stephenson group (4 links): 6 complex solutions
    let sc = Scene::new(stephenson()).unwrap();
    let plan = sc.plan(None).unwrap();
    let a = plan.assemblies(sc.input_angle() + 0.1, &HomotopyOptions::default(), &Never).unwrap();
    assert_eq!(a.complex_counts, vec![vec![6]]);
    assert!(!a.list.is_empty() && a.list.len() <= 6 && a.list.len().is_multiple_of(2));
    let d = |a: Xy, b: Xy| ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt();
    let sp = stephenson();
    let drawn = |name: &str| sp.points.iter().find(|p| p.0 == name).unwrap().1;
    for asm in &a.list {
        for (_, pts) in &sp.links {
            for (i, p) in pts.iter().enumerate() {
                for q in &pts[i + 1..] {
                    let (ip, iq) = (sc.point_index(p).unwrap(), sc.point_index(q).unwrap());
                    let err = (d(asm.points[ip], asm.points[iq]) - d(drawn(p), drawn(q))).abs();
                    assert!(err < 1e-12, "{err}");
                }
            }
        }
    }
}

#[test]
fn long_calls_stop_when_interrupted() {
    let yes = || true;
    let sc = Scene::new(stephenson()).unwrap();
    // a group sweep with a tiny step: millions of continuation steps between two angles
    let plan = sc.plan(None).unwrap();
    let opts = SceneSweepOptions::new(NewtonOptions::default(), 1e-9, None).unwrap();
    let theta = [sc.input_angle() + 0.5];
    let mut out = SceneSweepBuffers::new(&plan, theta.len(), false).unwrap();
    assert_eq!(plan.sweep(&theta, &opts, out.out(), &yes), Err(Error::Interrupted));
    // a trace with a tiny step, and the circuits that trace
    let tiny = TraceOptions::new(1e-7, 1_000_000_000).unwrap();
    assert_eq!(sc.trace(None, &tiny, &yes), Err(Error::Interrupted));
    assert!(matches!(sc.circuits(sc.input_angle(), &HomotopyOptions::default(), &tiny, &yes), Err(Error::Interrupted)));
}
