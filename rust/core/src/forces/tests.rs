//! A single link on a ground pivot (a pendulum) under gravity, worked by hand: the torque
//! that holds it is m g (L/2) cos(theta), the pin carries its weight, and a constant
//! angular acceleration adds (I + m (L/2)^2) alpha. Tables interpolate as NumPy's interp.

use super::*;
use crate::status::Status;

const L: f64 = 2.0;
const M: f64 = 3.0;
const I: f64 = 0.7;
const G: f64 = 9.81;

/// Points O (pivot) and A (tip); links crank (moving, 0) and ground (1); unknowns: the
/// pin at O on the crank (x, y) and the input torque.
fn pendulum(torque_table: Option<Table>) -> Model {
    let pin = |c, sign, link, dir| UnitForce { link, column: c, sign, point: 0, dir };
    let mut loads = Loads {
        gravity: Some([0.0, -G]),
        masses: vec![Mass { link: 0, a: 0, b: 1, arm: [L / 2.0, 0.0], drawn: [1.0, 0.0], mass: M, inertia: I }],
        ..Loads::default()
    };
    if let Some(t) = torque_table {
        loads.torques.push((0, t));
    }
    Model::new(Parts {
        points: 2,
        moving: 1,
        columns: 3,
        size: L,
        refs: vec![0, 0],
        forces: vec![
            pin(0, 1.0, 0, Direction::X),
            pin(0, -1.0, 1, Direction::X),
            pin(1, 1.0, 0, Direction::Y),
            pin(1, -1.0, 1, Direction::Y),
        ],
        couples: vec![UnitCouple { link: 0, column: 2, sign: 1.0 }, UnitCouple { link: 1, column: 2, sign: -1.0 }],
        lines: vec![],
        blocks: vec![Block { rows: vec![0, 1, 2], columns: vec![0, 1, 2], prior: vec![] }],
        loads,
        output: Some(Output::Link(0)),
    })
    .unwrap()
}

struct Sweep {
    theta: Vec<f64>,
    coords: Vec<f64>,
    vel: Vec<f64>,
    acc: Vec<f64>,
    w: Vec<f64>,
    a: Vec<f64>,
}

fn sweep(theta: &[f64]) -> Sweep {
    let mut s = Sweep { theta: theta.to_vec(), coords: vec![], vel: vec![], acc: vec![], w: vec![], a: vec![] };
    for &t in theta {
        let (sn, cs) = t.sin_cos();
        s.coords.extend([0.0, 0.0, L * cs, L * sn]);
        s.vel.extend([0.0, 0.0, -L * sn, L * cs]);
        s.acc.extend([0.0, 0.0, -L * cs, -L * sn]);
        s.w.push(1.0);
        s.a.push(0.0);
    }
    s
}

fn run(model: &Model, s: &Sweep, drive: Option<Drive<'_>>) -> Solution {
    let n = s.theta.len();
    let status = vec![Status::Converged.code(); n];
    let det = vec![1.0; n];
    let motion = Motion {
        theta: &s.theta,
        status: &status,
        det: &det,
        coords: &s.coords,
        velocity: &s.vel,
        acceleration: Some(&s.acc),
        angular_velocity: &s.w,
        angular_acceleration: Some(&s.a),
        point_map: &[0, 1],
        link_map: &[0],
        rate: 1.0,
    };
    solve(model, &motion, drive).unwrap()
}

fn close(a: f64, b: f64) {
    assert!((a - b).abs() <= 1e-12 * (1.0 + b.abs()), "{a} != {b}");
}

#[test]
fn forces_pendulum_statics_by_hand() {
    let theta = [0.0, 0.4, 1.2, 2.5, -2.0];
    let s = sweep(&theta);
    let out = run(&pendulum(None), &s, None);
    for (i, t) in theta.iter().enumerate() {
        close(out.unknowns[3 * i + 2], M * G * L / 2.0 * t.cos());
        close(out.virtual_work[i], M * G * L / 2.0 * t.cos());
        close(out.unknowns[3 * i], 0.0);
        close(out.unknowns[3 * i + 1], M * G);
        // the ground carries the weight through the pin, and the torque's reaction
        close(out.ground[3 * i + 1], -M * G);
        close(out.potential[i], M * G * L / 2.0 * t.sin());
        close(out.advantage[i], 1.0);
        assert_eq!(out.status[i], Status::Converged.code());
    }
    assert!(out.check_virtual_work < 1e-14);
}

#[test]
fn forces_pendulum_dynamics_by_hand() {
    let theta = [0.3, 1.0, 2.0];
    let s = sweep(&theta);
    let (omega, alpha) = ([2.0, 3.0, 0.5], [1.5, -0.5, 4.0]);
    let out = run(&pendulum(None), &s, Some(Drive { omega: &omega, alpha: &alpha }));
    let io = I + M * (L / 2.0) * (L / 2.0);
    for (i, t) in theta.iter().enumerate() {
        close(out.unknowns[3 * i + 2], io * alpha[i] + M * G * L / 2.0 * t.cos());
        close(out.kinetic[i], 0.5 * io * omega[i] * omega[i]);
        close(out.input_power[i], out.unknowns[3 * i + 2] * omega[i]);
    }
    assert!(out.check_energy.unwrap() < 1e-14);
}

#[test]
fn forces_dead_point_and_bad_rows_are_statuses() {
    let s = sweep(&[0.1, 0.2]);
    let status = [Status::Converged.code(), Status::NotAssemblable.code()];
    let motion = Motion {
        theta: &s.theta,
        status: &status,
        det: &[1e-7, 1.0],
        coords: &s.coords,
        velocity: &s.vel,
        acceleration: None,
        angular_velocity: &s.w,
        angular_acceleration: None,
        point_map: &[0, 1],
        link_map: &[0],
        rate: 1.0,
    };
    let out = solve(&pendulum(None), &motion, None).unwrap();
    assert_eq!(out.status, vec![Status::Singular.code(), Status::NotAssemblable.code()]);
    assert!(out.unknowns.iter().all(|v| v.is_nan()));
    assert!(solve(&pendulum(None), &motion, Some(Drive { omega: &[1.0, 1.0], alpha: &[0.0, 0.0] })).is_err());
}

#[test]
fn forces_tables_interpolate_as_numpy() {
    // periodic: abscissae modulo 2 pi, closed around the turn
    let tau = std::f64::consts::TAU;
    let t = Table::new("t", &[0.0, 1.0, 4.0], &[1.0, 3.0, -1.0], 1, Some(tau)).unwrap();
    close(t.at(0.5, 0), 2.0);
    close(t.at(2.5, 0), 1.0);
    close(t.at(1.0 + tau, 0), 3.0);
    // from 4 (value -1) to 2 pi (value 1, the first point one period on)
    close(t.at(5.0, 0), -1.0 + 2.0 * (1.0 / (tau - 4.0)));
    let h = Table::new("h", &[0.0, 1.0], &[1.0, 3.0], 1, None).unwrap();
    close(h.at(-5.0, 0), 1.0);
    close(h.at(7.0, 0), 3.0);
    // a torque table on the pendulum adds to the effort with a minus sign
    let tab = Table::new("torque", &[0.0, 1.0], &[2.0, 4.0], 1, None).unwrap();
    let out = run(&pendulum(Some(tab)), &sweep(&[0.5]), None);
    close(out.unknowns[2], M * G * L / 2.0 * 0.5f64.cos() - 3.0);
}

#[test]
fn forces_model_refuses_bad_indices() {
    let mut p = Parts { points: 2, moving: 1, columns: 3, size: 1.0, refs: vec![0, 0], ..Parts::default() };
    p.blocks = vec![Block { rows: vec![0, 1, 2], columns: vec![0, 1, 2], prior: vec![] }];
    assert!(Model::new(p.clone()).is_ok());
    let mut q = p.clone();
    q.refs = vec![0, 5];
    assert!(Model::new(q).is_err());
    let mut q = p.clone();
    q.blocks[0].rows = vec![0, 0, 2];
    assert!(Model::new(q).is_err());
    let mut q = p;
    q.size = 0.0;
    assert!(Model::new(q).is_err());
}

#[test]
fn forces_parts_from_a_scene_hold_a_pendulum_by_hand() {
    use crate::scene::format::{parse, Value};
    use crate::scene::Scene;
    let st = |x: &str| Value::Str(x.into());
    let map = |v: Vec<(&str, Value)>| Value::Map(v.into_iter().map(|(k, v)| (Value::Str(k.into()), v)).collect());
    let xy = |x: f64, y: f64| Value::List(vec![Value::Float(x), Value::Float(y)]);
    let names = |v: &[&str]| Value::List(v.iter().map(|n| Value::Str((*n).into())).collect());
    let data = map(vec![
        ("points", map(vec![("O", xy(0.0, 0.0)), ("X", xy(1.0, 0.0)), ("P", xy(0.8, 0.6)), ("G", xy(0.4, 0.3))])),
        ("links", map(vec![("ground", names(&["O", "X"])), ("arm", names(&["O", "P", "G"]))])),
        ("ground", st("ground")),
        ("input", map(vec![("link", st("arm")), ("pivot", st("O"))])),
        (
            "loads",
            map(vec![
                ("gravity", xy(0.0, -G)),
                (
                    "masses",
                    map(vec![(
                        "arm",
                        map(vec![("mass", Value::Float(M)), ("center", st("G")), ("inertia", Value::Float(I))]),
                    )]),
                ),
                ("forces", Value::List(vec![map(vec![("point", st("P")), ("force", xy(2.0, 0.0))])])),
            ]),
        ),
    ]);
    let parsed = parse(&data).unwrap();
    let loads = parsed.loads.clone().unwrap();
    let scene = Scene::new(parsed.spec.clone()).unwrap();
    let model = Model::new(parts(&scene, &parsed.input, &loads, None, 1.0).unwrap()).unwrap();
    assert_eq!((model.columns(), model.moving()), (3, 1));
    let coords: Vec<f64> = scene.drawn().iter().flat_map(|p| [p[0], p[1]]).collect();
    let zeros = vec![0.0; coords.len()];
    let motion = Motion {
        theta: &[0.6435011087932844],
        status: &[Status::Converged.code()],
        det: &[1.0],
        coords: &coords,
        velocity: &zeros,
        acceleration: None,
        angular_velocity: &[0.0],
        angular_acceleration: None,
        point_map: &[0, 1, 2, 3],
        link_map: &[0],
        rate: 1.0,
    };
    let out = solve(&model, &motion, None).unwrap();
    // the weight at G (arm 0.4) and the push at P (arm 0.6 below the line of action)
    close(out.unknowns[2], M * G * 0.4 + 2.0 * 0.6);
    close(out.unknowns[0], -2.0);
    close(out.unknowns[1], M * G);
    assert!((inertia_factor(Some("mm"), None) - 1e-3).abs() < 1e-18);
}
