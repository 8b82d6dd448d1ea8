//! The column path against the continuation on the slider built-ins (their drawings
//! copied from `python/planarkin/scene/builtin`): the same statuses, and positions,
//! angles, conditioning, velocities and accelerations to 1e-12 of the drawing's size.

use super::blocks::dyad_block;
use super::frame::{Columns, B, OK};
use super::*;
use crate::interrupt::{Never, Poll};
use crate::scene::ops::Dyad;
use crate::scene::sweep::options::SceneSweepOptions;
use crate::scene::vec2::Xy;
use crate::scene::{LinearKind, PrismaticSpec, Scene, SceneSpec, SceneSweepBuffers, SlotSpec};
use crate::solve::newton::NewtonOptions;
use crate::Status;

type Joint<'a> = (&'a str, &'a str, &'a str, (&'a str, &'a str));

struct Spec<'a> {
    points: &'a [(&'a str, Xy)],
    links: &'a [(&'a str, &'a [&'a str])],
    input: (&'a str, &'a str),
    slots: &'a [Joint<'a>],
    prismatic: &'a [Joint<'a>],
    linear: Option<(LinearKind, &'a str)>,
}

fn scene(s: &Spec<'_>) -> Scene {
    let o = |x: &str| x.to_string();
    let joint = |&(n, a, g, (l0, l1)): &Joint<'_>| (o(n), (o(a), o(g), (o(l0), o(l1))));
    let spec = SceneSpec {
        points: s.points.iter().map(|&(n, p)| (o(n), p)).collect(),
        links: s.links.iter().map(|&(n, ps)| (o(n), ps.iter().map(|p| o(p)).collect())).collect(),
        ground: o("ground"),
        input: (o(s.input.0), o(s.input.1)),
        output: None,
        slots: s.slots.iter().map(joint).map(|(n, j)| (n, SlotSpec::from(j))).collect(),
        prismatic: s.prismatic.iter().map(joint).map(|(n, j)| (n, PrismaticSpec::from(j))).collect(),
        linear_input: s.linear.map(|(k, n)| (k, o(n))),
    };
    Scene::new(spec).expect("a built-in is valid")
}

const NO: &[Joint<'static>] = &[];

fn builtins() -> Vec<(&'static str, Scene)> {
    let slider_crank = |b: Xy, a: Xy, x: Xy| {
        scene(&Spec {
            points: &[("O2", [0.0, 0.0]), ("X", x), ("A", a), ("B", b)],
            links: &[("ground", &["O2", "X"]), ("crank", &["O2", "A"]), ("rod", &["A", "B"])],
            input: ("crank", "O2"),
            slots: &[("piston", "B", "ground", ("O2", "X"))],
            prismatic: NO,
            linear: None,
        })
    };
    let whitworth = scene(&Spec {
        points: &[
            ("O2", [0.0, 0.0]),
            ("O4", [0.0, 30.0]),
            ("X", [-1.0, 30.0]),
            ("A", [51.96152422706632, 29.999999999999996]),
            ("C", [-50.0, 30.000000000000004]),
            ("D", [-200.0, 30.0]),
        ],
        links: &[
            ("ground", &["O2", "O4", "X"]),
            ("crank", &["O2", "A"]),
            ("lever", &["O4", "C"]),
            ("rod", &["C", "D"]),
        ],
        input: ("crank", "O2"),
        slots: &[("block", "A", "lever", ("O4", "C")), ("ram", "D", "ground", ("O4", "X"))],
        prismatic: NO,
        linear: None,
    });
    let yoke = scene(&Spec {
        points: &[
            ("O2", [0.0, 0.0]),
            ("G", [1.0, 0.0]),
            ("A", [45.31538935183249, 21.130913087034973]),
            ("Y1", [45.31538935183249, -60.0]),
            ("Y2", [45.31538935183249, 60.0]),
            ("R", [165.3153893518325, 0.0]),
        ],
        links: &[("ground", &["O2", "G"]), ("crank", &["O2", "A"]), ("yoke", &["Y1", "Y2", "R"])],
        input: ("crank", "O2"),
        slots: &[("pin", "A", "yoke", ("Y1", "Y2"))],
        prismatic: &[("guide", "yoke", "ground", ("O2", "G"))],
        linear: None,
    });
    let inverted = scene(&Spec {
        points: &[
            ("O2", [0.0, 0.0]),
            ("O4", [100.0, 0.0]),
            ("A", [30.64177772475912, 25.71150438746157]),
            ("C", [-40.64693667150496, 52.1386536546704]),
        ],
        links: &[("ground", &["O2", "O4"]), ("crank", &["O2", "A"]), ("cylinder", &["O4", "C"])],
        input: ("crank", "O2"),
        slots: &[("block", "A", "cylinder", ("O4", "C"))],
        prismatic: NO,
        linear: None,
    });
    let trammel = scene(&Spec {
        points: &[
            ("O", [0.0, 0.0]),
            ("X", [1.0, 0.0]),
            ("Y", [0.0, 1.0]),
            ("A", [60.0, 0.0]),
            ("B", [0.0, 80.0]),
            ("P", [36.0, 32.0]),
        ],
        links: &[("ground", &["O", "X", "Y"]), ("bar", &["A", "B", "P"])],
        input: ("", ""),
        slots: &[("a", "A", "ground", ("O", "X")), ("b", "B", "ground", ("O", "Y"))],
        prismatic: NO,
        linear: Some((LinearKind::Slot, "a")),
    });
    let boom = scene(&Spec {
        points: &[
            ("O", [0.0, 0.0]),
            ("C1", [600.0, -400.0]),
            ("E", [692.820323027551, 399.99999999999994]),
            ("T", [1732.0508075688774, 999.9999999999999]),
            ("C2", [634.5756721218627, -101.9991226567924]),
            ("R", [646.7194268650675, 2.665496875723136]),
        ],
        links: &[("ground", &["O", "C1"]), ("boom", &["O", "E", "T"]), ("barrel", &["C1", "C2"]), ("rod", &["R", "E"])],
        input: ("", ""),
        slots: NO,
        prismatic: &[("cylinder", "rod", "barrel", ("C1", "C2"))],
        linear: Some((LinearKind::Prismatic, "cylinder")),
    });
    vec![
        ("slider-crank", slider_crank([193.386094815253, 0.0], [34.64101615137755, 19.999999999999996], [1.0, 0.0])),
        ("whitworth", whitworth),
        ("scotch-yoke", yoke),
        ("inverted-slider-crank", inverted),
        ("elliptic-trammel", trammel),
        ("hydraulic-boom", boom),
    ]
}

#[test]
fn sliders_on_columns_match_the_continuation() {
    for ((name, sc), omega) in builtins().into_iter().flat_map(|b| [(b.clone(), None), (b, Some(2.5))]) {
        let plan = sc.plan(None).expect("the plan compiles");
        assert!(plan.columns_ok(), "{name}");
        let size = sc.scale();
        // 1-degree steps through a turn; a linear input from its drawn pose 0.4 sizes on
        let theta: Vec<f64> = if plan.linear {
            (0..100).map(|k| k as f64 * 0.004 * size).collect()
        } else {
            (0..361).map(|k| sc.input_angle() + (k as f64).to_radians()).collect()
        };
        let h = (theta[1] - theta[0]).abs();
        let n = theta.len();
        let opts = |max_step: f64| SceneSweepOptions::new(NewtonOptions::default(), max_step, omega).unwrap();
        let mut cols = SceneSweepBuffers::new(&plan, n, omega.is_some()).unwrap();
        sweep(&plan, &theta, &opts(2.0 * h), &mut cols.out(), &Poll::new(&Never)).unwrap();
        // the certificate holds here: the plain sweep takes the columns as they are
        assert!(cols.status.iter().all(|&s| s == OK), "{name}: {:?}", cols.status);
        assert!(cols.step_det.iter().all(|d| d.abs() >= 0.05), "{name}");
        let mut plain = SceneSweepBuffers::new(&plan, n, omega.is_some()).unwrap();
        plan.sweep(&theta, &opts(2.0 * h), plain.out(), &Never).unwrap();
        let bits = |b: &SceneSweepBuffers| {
            b.reals().iter().map(|v| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>()).collect::<Vec<_>>()
        };
        assert!(bits(&plain) == bits(&cols), "{name}: the plain sweep is not the column one");
        // steps longer than max_step: the continuation
        let mut cont = SceneSweepBuffers::new(&plan, n, omega.is_some()).unwrap();
        plan.sweep(&theta, &opts(0.5 * h), cont.out(), &Never).unwrap();
        let ints =
            |b: &SceneSweepBuffers| (b.status.clone(), b.step_status.clone(), b.point_status.clone(), b.nit.clone());
        assert!(ints(&cont) == ints(&cols), "{name}: statuses differ");
        for (k, (a, b)) in cols.reals().into_iter().zip(cont.reals()).enumerate() {
            // positions, angles, dets and rates: 1e-12 of their largest size
            let big = a.iter().map(|x| x.abs()).filter(|x| x.is_finite()).fold(1.0, f64::max);
            for (x, y) in a.iter().zip(b) {
                let same = (x.is_nan() && y.is_nan()) || (x - y).abs() <= 1e-12 * big;
                assert!(same, "{name} (omega {omega:?}): output {k}: {x} vs {y}");
            }
        }
    }
}

/// The dyad over a block is `Dyad::solve` value for value, bit for bit (both run
/// `closed_form`; what this checks is the block's statuses, conditioning and masking
/// against the scalar solve's cases, which its own tests hold to circle
/// intersections): random known points, and the cases at the edges (coincident points
/// with equal and unequal links, out of reach, exactly in line, a non-finite input, a
/// failed input).
#[test]
fn the_dyad_block_is_dyad_solve_bit_for_bit() {
    let mut seed = 0x2545_f491_4f6c_dd1d_u64;
    let mut next = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 * 12.0 - 6.0
    };
    let links = [0, 0];
    for d in [
        Dyad { p: 2, k1: 0, k2: 1, r1: 5.0, r2: 5.0, side: 1.0, links },
        Dyad { p: 0, k1: 2, k2: 1, r1: 2.5, r2: 4.0, side: -1.0, links },
    ] {
        let (mut reals, mut st) = (vec![0.0; 6 * B], vec![OK; 3 * B]);
        let mut c = Columns::carve(&mut reals, &mut st, 3 * B, 0);
        let (o1, o2) = (d.k1 * B, d.k2 * B);
        for j in 0..B {
            (c.x[o1 + j], c.y[o1 + j], c.x[o2 + j], c.y[o2 + j]) = (next(), next(), next(), next());
        }
        // coincident; in line at full reach; out of reach; non-finite; a failed input
        (c.x[o2], c.y[o2]) = (c.x[o1], c.y[o1]);
        (c.x[o2 + 1], c.y[o2 + 1]) = (c.x[o1 + 1] + d.r1 + d.r2, c.y[o1 + 1]);
        (c.x[o2 + 2], c.y[o2 + 2]) = (c.x[o1 + 2] + 2.0 * (d.r1 + d.r2), c.y[o1 + 2]);
        c.x[o1 + 3] = f64::NAN;
        c.st[o2 + 4] = Status::Limit.code();
        let (mut det, mut sst) = (vec![0.0; B], vec![OK; B]);
        dyad_block(&d, &mut c, B, 1e-6, false, &mut det, &mut sst);
        let mut seen = std::collections::BTreeSet::new();
        for j in 0..B {
            let (a, b) = ([c.x[o1 + j], c.y[o1 + j]], [c.x[o2 + j], c.y[o2 + j]]);
            let bad = [c.st[o1 + j], c.st[o2 + j]].into_iter().find(|&s| s != OK);
            let (st, dt, p) = match (bad, d.solve(a, b)) {
                (Some(s), _) => (s, f64::NAN, None),
                (None, crate::scene::ops::DyadOut::Solved(p, dt)) if dt.abs() >= 1e-6 => (OK, dt, Some(p)),
                (None, crate::scene::ops::DyadOut::Solved(_, dt)) => {
                    (if dt.is_nan() { Status::NonFinite.code() } else { Status::Singular.code() }, dt, None)
                }
                (None, crate::scene::ops::DyadOut::NotAssemblable) => (Status::NotAssemblable.code(), f64::NAN, None),
                (None, crate::scene::ops::DyadOut::Indeterminate) => (Status::Singular.code(), 0.0, None),
            };
            seen.insert(st);
            assert_eq!((sst[j], c.st[d.p * B + j]), (st, st), "value {j}");
            assert_eq!(det[j].to_bits(), dt.to_bits(), "value {j}: {} vs {dt}", det[j]);
            if let Some(p) = p {
                let q = [c.x[d.p * B + j], c.y[d.p * B + j]];
                assert_eq!(q.map(f64::to_bits), p.map(f64::to_bits), "value {j}");
            }
        }
        // every case met: solved, singular (in line or coincident), not assemblable,
        // and the failed input's status carried
        assert!(seen.len() >= 4, "{seen:?}");
    }
}
