//! The sketch against the closed form, exact drawings and scalings, and the messages.

use super::*;
use crate::scene::tests::fourbar;
use crate::{ClosedForm, FourBar, Mode, Never};

fn lengths(v: &[(&str, &str, f64)]) -> Vec<LengthSpec> {
    v.iter().map(|(a, b, d)| (a.to_string(), b.to_string(), *d)).collect()
}

fn sketch(spec: SceneSpec, l: &[LengthSpec]) -> Result<Sketched, Error> {
    assemble_sketch(spec, l, &Never)
}

fn fourbar_lengths() -> Vec<LengthSpec> {
    lengths(&[("O2", "A", 2.0), ("A", "B", 5.0), ("O4", "B", 5.0)])
}

/// The entry and message of a scene error.
fn scene_err(r: Result<Sketched, Error>) -> (String, String) {
    match r {
        Err(Error::Scene { entry, message }) => (entry, message),
        other => panic!("expected a scene error, got {other:?}"),
    }
}

#[test]
fn a_fourbar_sketch_assembles_to_the_closed_form_in_its_sketched_mode() {
    let fb = FourBar::new(6.0, 2.0, 5.0, 5.0).unwrap();
    for (sign, mode) in [(1.0, Mode::Open), (-1.0, Mode::Crossed)] {
        for deg in [0.0_f64, 35.0, 100.0, 200.0, 300.0] {
            let t = deg.to_radians();
            let ClosedForm::Solved { theta3, .. } = fb.closed_form(t, mode) else { panic!("{deg}") };
            let a = [2.0 * t.cos(), 2.0 * t.sin()];
            let b = [a[0] + 5.0 * theta3.cos(), a[1] + 5.0 * theta3.sin()];
            let mut spec = fourbar(sign);
            // A sketched 15% long on its exact direction, B off by (0.3, -0.25)
            spec.points[2].1 = [2.3 * t.cos(), 2.3 * t.sin()];
            spec.points[3].1 = [b[0] + 0.3, b[1] - 0.25];
            let s = sketch(spec, &fourbar_lengths()).unwrap();
            for (p, q) in [(2, a), (3, b)] {
                let e = (s.points[p][0] - q[0]).hypot(s.points[p][1] - q[1]);
                assert!(e < 1e-12 * 6.0, "{deg} {p} {e:e}");
            }
            assert_eq!(&s.points[..2], &[[0.0, 0.0], [6.0, 0.0]]);
            assert_eq!(&s.moved[..2], &[0.0, 0.0]);
            assert!((s.moved[2] - 0.3).abs() < 1e-12, "{}", s.moved[2]);
            assert!((s.moved[3] - 0.3f64.hypot(0.25)).abs() < 1e-12, "{}", s.moved[3]);
        }
    }
}

#[test]
fn an_exact_drawing_is_kept_bit_for_bit() {
    for sign in [1.0, -1.0] {
        let spec = fourbar(sign);
        let drawn: Vec<Xy> = spec.points.iter().map(|p| p.1).collect();
        let s = sketch(spec, &lengths(&[("O2", "A", 2.0), ("A", "B", 5.0), ("O4", "B", 5.0)])).unwrap();
        assert_eq!(s.points, drawn);
        assert!(s.moved.iter().all(|&m| m == 0.0));
    }
}

#[test]
fn a_power_of_two_scaling_scales_the_result_exactly() {
    let mut spec = fourbar(1.0);
    spec.points[3].1 = [4.4, 4.1];
    let base = sketch(spec.clone(), &fourbar_lengths()).unwrap();
    for f in [2f64.powi(-60), 2f64.powi(70)] {
        let mut s = spec.clone();
        for p in &mut s.points {
            p.1 = [p.1[0] * f, p.1[1] * f];
        }
        let l: Vec<LengthSpec> = fourbar_lengths().into_iter().map(|(a, b, d)| (a, b, d * f)).collect();
        let out = sketch(s, &l).unwrap();
        for (p, q) in out.points.iter().zip(&base.points) {
            assert_eq!(*p, [q[0] * f, q[1] * f]);
        }
    }
}

#[test]
fn lengths_that_cannot_close_name_a_link_of_the_loop() {
    let (entry, message) =
        scene_err(sketch(fourbar(1.0), &lengths(&[("O2", "A", 2.0), ("A", "B", 1.5), ("O4", "B", 1.5)])));
    assert!(entry == "links.coupler" || entry == "links.rocker", "{entry}");
    assert!(message.starts_with("no assembly near the sketch"), "{message}");
}

#[test]
fn a_link_without_its_length_is_named() {
    let (entry, message) = scene_err(sketch(fourbar(1.0), &lengths(&[("O2", "A", 2.0), ("A", "B", 5.0)])));
    assert_eq!(entry, "links.rocker");
    assert!(message.starts_with("has no lengths"), "{message}");
}

#[test]
fn bad_entries_are_named() {
    type Case = (&'static [(&'static str, &'static str, f64)], &'static str);
    let cases: [Case; 7] = [
        (&[("A", "Q", 1.0)], "unknown point \"Q\""),
        (&[("A", "A", 1.0)], "names \"A\" twice"),
        (&[("O2", "B", 1.0)], "are on no common link"),
        (&[("A", "B", 0.0)], "must be > 0"),
        (&[("A", "B", f64::NAN)], "must be finite"),
        (&[("B", "A", 4.0)], "but lengths[1] gave 5"),
        (&[("O2", "O4", 5.0)], "ground points, which stay as drawn"),
    ];
    for (extra, want) in cases {
        let mut l = fourbar_lengths();
        l.extend(lengths(extra));
        let (entry, message) = scene_err(sketch(fourbar(1.0), &l));
        assert_eq!(entry, "lengths[3]", "{message}");
        assert!(message.contains(want), "{message}");
    }
}

#[test]
fn a_dead_point_sketch_is_refused() {
    let mut spec = fourbar(1.0);
    spec.points[3].1 = [4.0, 0.0]; // A, B and O4 in line
    let (entry, message) = scene_err(sketch(spec, &fourbar_lengths()));
    assert!(entry == "links.coupler" || entry == "links.rocker", "{entry}");
    assert!(message.contains("drawn at a dead point") && message.contains("\"B\""), "{message}");
}
