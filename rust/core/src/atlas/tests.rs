use super::*;
use crate::interrupt::Never;
use crate::scene::Xy;

fn similar(pts: &[Xy], a: Xy, b: Xy) -> Vec<Xy> {
    pts.iter().map(|p| [a[0] * p[0] - a[1] * p[1] + b[0], a[0] * p[1] + a[1] * p[0] + b[1]]).collect()
}

/// The descriptor up to the one ambiguity its normalisation leaves (the even harmonics'
/// sign): the distance to the nearer of the two.
fn distance(x: &[f32; DESCRIPTOR], y: &[f32; DESCRIPTOR]) -> f64 {
    let d = |flip: bool| -> f64 {
        (0..DESCRIPTOR)
            .map(|i| {
                let k = i / 4 + 1;
                let s = if flip && k % 2 == 0 { -1.0 } else { 1.0 };
                (x[i] as f64 - s * y[i] as f64).powi(2)
            })
            .sum::<f64>()
            .sqrt()
    };
    d(false).min(d(true))
}

#[test]
fn four_bar_pose_closes_its_loop() {
    let (p, s) = ([0.4, 1.2, 1.1, 0.3, 0.5], [1.0]);
    for k in 0..36 {
        let t = k as f64 * 0.17;
        let q = pose(Topology::FourBar, &p, &s, t).expect("a crank-rocker assembles everywhere");
        let [o2, o4, a, b, pt] = [q.points[0], q.points[1], q.points[2], q.points[3], q.points[4]];
        let len = |u: Xy, v: Xy| (u[0] - v[0]).hypot(u[1] - v[1]);
        assert!((len(o2, a) - 0.4).abs() < 1e-14 && (len(a, b) - 1.2).abs() < 1e-13);
        assert!((len(o4, b) - 1.1).abs() < 1e-13);
        // the open mode (+1) has B to the left of A -> O4
        assert!((o4[0] - a[0]) * (b[1] - a[1]) - (o4[1] - a[1]) * (b[0] - a[0]) > 0.0);
        // P = A + 0.3 (B - A) + 0.5 perp(B - A)
        let d = [b[0] - a[0], b[1] - a[1]];
        assert!((pt[0] - (a[0] + 0.3 * d[0] - 0.5 * d[1])).abs() < 1e-14);
        // transmission sine from the law of cosines on A, B, O4
        let cos_mu = (1.2f64.powi(2) + 1.1f64.powi(2) - len(a, o4).powi(2)) / (2.0 * 1.2 * 1.1);
        assert!((q.conditioning - (1.0 - cos_mu * cos_mu).sqrt()).abs() < 1e-12);
    }
}

#[test]
fn crank_rocker_is_closed_and_triple_rocker_is_an_arc_ending_at_its_dead_points() {
    let c = coupler_curve(Topology::FourBar, &[0.4, 1.2, 1.1, 0.3, 0.5], &[1.0], SAMPLES).unwrap();
    assert!(c.closed && c.conditioning > 0.1);
    // non-Grashof (1, 1.2, 0.8, 0.9): the crank reaches |A - O4| = r3 + r4 = 1.7 at most
    let c = coupler_curve(Topology::FourBar, &[1.2, 0.8, 0.9, 0.5, 0.0], &[1.0], SAMPLES).unwrap();
    assert!(!c.closed);
    let (lo, hi) = (c.theta[0], *c.theta.last().unwrap());
    let limit = ((1.0 + 1.44 - 1.7f64.powi(2)) / (2.0 * 1.2)).acos();
    for t in [lo, hi] {
        let w = crate::wrap_angle(t).abs();
        assert!((w - limit).abs() < 1e-9, "{w} vs {limit}");
    }
}

#[test]
fn descriptor_ignores_translation_rotation_scale_start_and_direction() {
    let c = coupler_curve(Topology::FourBar, &[0.35, 1.3, 1.2, 0.6, -0.4], &[-1.0], 200).unwrap();
    let mut d0 = [0.0f32; DESCRIPTOR];
    assert!(describe(&c.points, true, &mut d0));
    let mut moved = similar(&c.points, [2.0 * 0.6f64.cos(), 2.0 * 0.6f64.sin()], [5.0, -3.0]);
    moved.rotate_left(37);
    let mut d1 = [0.0f32; DESCRIPTOR];
    assert!(describe(&moved, true, &mut d1));
    assert!(distance(&d0, &d1) < 2e-3, "{}", distance(&d0, &d1));
    moved.reverse();
    assert!(describe(&moved, true, &mut d1));
    assert!(distance(&d0, &d1) < 2e-3, "{}", distance(&d0, &d1));
    // a different linkage is far
    let c2 = coupler_curve(Topology::FourBar, &[0.3, 1.0, 1.0, 0.0, 1.0], &[1.0], 200).unwrap();
    assert!(describe(&c2.points, true, &mut d1));
    assert!(distance(&d0, &d1) > 0.05);
}

#[test]
fn shards_are_the_same_however_they_are_cut() {
    let whole = build_shard(Topology::FourBar, 7, 0, 60, &Never).unwrap();
    let a = build_shard(Topology::FourBar, 7, 0, 25, &Never).unwrap();
    let b = build_shard(Topology::FourBar, 7, 25, 35, &Never).unwrap();
    assert_eq!(whole.params, [a.params, b.params].concat());
    assert_eq!(whole.descriptor, [a.descriptor, b.descriptor].concat());
    let other = build_shard(Topology::FourBar, 8, 0, 60, &Never).unwrap();
    assert_ne!(whole.params, other.params);
    for t in Topology::ALL {
        // the scene solver's Stephenson III is slow in a debug build: a few will do
        let n = if t == Topology::Stephenson3 { 3 } else { 40 };
        let s = build_shard(t, 1, 0, n, &Never).unwrap();
        assert_eq!(s.params.len(), n * t.params());
        assert!(s.descriptor.iter().all(|v| v.is_finite()));
    }
}

#[test]
fn matching_finds_the_similarity_the_start_and_the_inputs() {
    let c = coupler_curve(Topology::FourBar, &[0.35, 1.3, 1.2, 0.6, -0.4], &[1.0], SAMPLES).unwrap();
    let (a, b) = ([1.5 * 2.0f64.cos(), 1.5 * 2.0f64.sin()], [3.0, 1.0]);
    // a closed target: the curve at 40 fresh input angles from 1.0 rad on
    let th: Vec<f64> = (0..40).map(|k| 1.0 + k as f64 * std::f64::consts::TAU / 40.0).collect();
    let pts: Vec<Xy> = th
        .iter()
        .map(|&t| pose(Topology::FourBar, &[0.35, 1.3, 1.2, 0.6, -0.4], &[1.0], t).unwrap().tracer())
        .collect();
    let target = similar(&pts, a, b);
    let m = match_curve(&c, &target, true, &FRACTIONS, Search::FINE).unwrap();
    // the target is a 40-gon of the curve: its chords leave a residual of about 2e-4
    assert!(m.cost < 1e-3, "{}", m.cost);
    assert!((m.a[0] - a[0]).abs() < 1e-2 && (m.a[1] - a[1]).abs() < 1e-2, "{:?}", m.a);
    assert!(!m.reversed);
    for (t, u) in m.theta.iter().zip(&th) {
        let d = crate::wrap_angle(t - u);
        assert!(d.abs() < 0.05, "{t} vs {u}");
    }
    // an open part of it, backwards
    let part: Vec<Xy> = target[5..18].iter().rev().copied().collect();
    let m = match_curve(&c, &part, false, &FRACTIONS, Search::FINE).unwrap();
    assert!(m.cost < 1e-2, "{}", m.cost);
    for (t, u) in m.theta.iter().zip(th[5..18].iter().rev()) {
        assert!(crate::wrap_angle(t - u).abs() < 0.1, "{t} vs {u}");
    }
}

#[test]
fn a_curve_with_no_extent_has_no_descriptor() {
    let mut d = [0.0f32; DESCRIPTOR];
    assert!(!describe(&[[3.0, 4.0]; 20], true, &mut d));
    assert!(!describe(&[[1e6, -2e6]; 20], false, &mut d));
    // a tiny curve far from the origin still has one
    let tiny: Vec<_> = (0..20).map(|k| [1e3 + 1e-6 * (k as f64).cos(), 1e-6 * (k as f64).sin()]).collect();
    assert!(describe(&tiny, true, &mut d));
}

#[test]
fn stephenson3_poses_keep_every_link_rigid() {
    // the built-in Stephenson III (python/planarkin/scene/builtin/stephenson3.json) scaled
    // by 1/5, its crank tip j6, j1, j2, j4, j5 and the tracer P = j4 + (0.1, 0.2)
    let drawn: [[f64; 2]; 6] = [
        [5.564345617061239, 0.4371950482264578],
        [0.35387676334036855, 2.213893501387662],
        [2.259021654080528, 1.4462003297361068],
        [3.020627139940088, 4.335523731482693],
        [4.746459539263316, 4.457062944011273],
        [3.520627139940088, 5.335523731482693],
    ];
    let p: Vec<f64> = drawn.iter().flat_map(|q| [q[0] / 5.0, q[1] / 5.0]).collect();
    let c = coupler_curve(Topology::Stephenson3, &p, &[], 32).expect("its crank turns fully");
    assert!(c.closed && c.points.len() == 32);
    let at0 = pose(Topology::Stephenson3, &p, &[], c.theta[0]).unwrap();
    let len = |q: &Pose, i: usize, j: usize| {
        let (a, b) = (q.points[i], q.points[j]);
        (a[0] - b[0]).hypot(a[1] - b[1])
    };
    // every pair on one link: ground, crank, T1, T2 (with P), B1, B2
    let pairs = [(0, 1), (1, 2), (3, 4), (3, 0), (4, 0), (5, 6), (5, 2), (6, 2), (7, 5), (7, 6), (3, 5), (4, 6)];
    for k in [0, 5, 13, 22, 31] {
        let q = pose(Topology::Stephenson3, &p, &[], c.theta[k]).unwrap();
        for &(i, j) in &pairs {
            assert!((len(&q, i, j) - len(&at0, i, j)).abs() < 1e-9, "{k}: {i}-{j}");
        }
        assert!((q.tracer()[0] - c.points[k][0]).abs() < 1e-12);
        // the crank is at the asked angle
        let d = [q.points[2][0] - 1.0, q.points[2][1]];
        assert!(crate::wrap_angle(d[1].atan2(d[0]) - c.theta[k]).abs() < 1e-12);
    }
}
