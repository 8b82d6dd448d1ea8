//! The format's messages, word for word as Python's `planarkin.Scene` has given them.

use super::*;

fn s(x: &str) -> Value {
    Value::Str(x.into())
}

fn list(v: Vec<Value>) -> Value {
    Value::List(v)
}

fn map(v: Vec<(&str, Value)>) -> Value {
    Value::Map(v.into_iter().map(|(k, v)| (s(k), v)).collect())
}

fn xy(x: f64, y: f64) -> Value {
    list(vec![Value::Float(x), Value::Float(y)])
}

/// A four-bar's data, with `edit` applied to its entries.
fn fourbar(edit: impl FnOnce(&mut Vec<(&'static str, Value)>)) -> Value {
    let names = |v: &[&str]| list(v.iter().map(|n| s(n)).collect());
    let mut d = vec![
        ("points", map(vec![("O2", xy(0.0, 0.0)), ("A", xy(1.0, 0.5)), ("B", xy(3.0, 2.0)), ("O4", xy(3.0, 0.0))])),
        (
            "links",
            map(vec![
                ("ground", names(&["O2", "O4"])),
                ("crank", names(&["O2", "A"])),
                ("coupler", names(&["A", "B"])),
                ("rocker", names(&["O4", "B"])),
            ]),
        ),
        ("ground", s("ground")),
        ("input", map(vec![("link", s("crank")), ("pivot", s("O2"))])),
    ];
    edit(&mut d);
    Value::Map(d.into_iter().map(|(k, v)| (s(k), v)).collect())
}

fn set(d: &mut Vec<(&'static str, Value)>, key: &'static str, v: Value) {
    match d.iter_mut().find(|(k, _)| *k == key) {
        Some(e) => e.1 = v,
        None => d.push((key, v)),
    }
}

fn message(data: &Value) -> String {
    parse(data).expect_err("refused").to_string()
}

#[test]
fn floats_read_as_python_writes_them() {
    for (x, py) in [
        (1e-5, "1e-05"),
        (1e16, "1e+16"),
        (0.1, "0.1"),
        (-0.0, "-0.0"),
        (1.0, "1.0"),
        (f64::INFINITY, "inf"),
        (f64::NEG_INFINITY, "-inf"),
        (f64::NAN, "nan"),
        (123456789.0, "123456789.0"),
        (1.5e300, "1.5e+300"),
    ] {
        assert_eq!(Value::Float(x).repr(), py);
    }
}

#[test]
fn values_read_as_python_writes_them() {
    let v = list(vec![
        Value::Null,
        Value::Bool(true),
        Value::Int(-3),
        s("it's"),
        s("a\\b'\""),
        Value::Tuple(vec![Value::Int(1)]),
        Value::Tuple(vec![]),
        map(vec![("link", s("crank"))]),
        Value::Map(vec![]),
    ]);
    assert_eq!(v.repr(), r#"[None, True, -3, "it's", 'a\\b\'"', (1,), (), {'link': 'crank'}, {}]"#);
    let d = Described { repr: "array([1., 2., 3.])".into(), type_name: "ndarray".into() };
    assert_eq!(Value::foreign(d, Like::Nothing).repr(), "array([1., 2., 3.])");
}

#[test]
fn a_valid_scene_reads_into_its_spec() {
    let p = parse(&fourbar(|d| {
        set(d, "name", s("fb"));
        set(d, "outputs", list(vec![s("B")]));
        set(d, "output", Value::Null);
    }))
    .expect("valid");
    assert_eq!(p.spec.points.len(), 4);
    assert_eq!(p.spec.input, ("crank".into(), "O2".into()));
    assert_eq!(p.name.as_deref(), Some("fb"));
    assert_eq!(p.outputs, Some(vec!["B".to_string()]));
    assert!(p.output.is_none() && p.lengths.is_none());
}

#[test]
fn every_entry_is_named_with_what_it_got() {
    let cases: Vec<(Value, &str)> = vec![
        (list(vec![]), "scene: must be a mapping, got list"),
        (
            fourbar(|d| set(d, "colour", s("red"))),
            "scene: unknown keys ['colour']; known keys: name, description, units, points, links, ground, input, \
             output, outputs, slots, prismatic, lengths, loads, limits",
        ),
        (fourbar(|d| d.retain(|(k, _)| *k != "ground")), "ground: is required"),
        (fourbar(|d| set(d, "points", list(vec![]))), "points: must be a table name -> [x, y]"),
        (fourbar(|d| set(d, "links", s("x"))), "links: must be a table name -> [point names]"),
        (
            fourbar(|d| set(d, "points", map(vec![("A", list(vec![Value::Float(1.0)]))]))),
            "points.A: must be a pair [x, y], got [1.0]",
        ),
        (
            fourbar(|d| set(d, "points", map(vec![("A", list(vec![s("x"), Value::Float(1.0)]))]))),
            "points.A[0] must be a real number, got 'x'",
        ),
        (
            fourbar(|d| {
                let big = Value::BigInt { digits: "9".repeat(400), bits: 1329 };
                set(d, "points", map(vec![("A", list(vec![big, Value::Int(0)]))]))
            }),
            "points.A[0] must be a real number within the float range, got an integer of 1329 bits",
        ),
        (
            fourbar(|d| set(d, "links", map(vec![("crank", list(vec![s("O2"), Value::Int(1)]))]))),
            "links.crank: must be a list of point names, got ['O2', 1]",
        ),
        (fourbar(|d| set(d, "ground", Value::Int(1))), "ground: must be a link name"),
        (
            fourbar(|d| set(d, "input", map(vec![("link", s("crank"))]))),
            "input: must be a table with keys 'link' and 'pivot' (an angle), or with one key 'slot' or \
             'prismatic' (a displacement), got {'link': 'crank'}",
        ),
        (
            fourbar(|d| set(d, "input", map(vec![("link", Value::Int(2)), ("pivot", s("O2"))]))),
            "input.link: must be a link name, got 2",
        ),
        (fourbar(|d| set(d, "input", map(vec![("slot", Value::Null)]))), "input.slot: must be a slot name, got None"),
        (fourbar(|d| set(d, "output", map(vec![("prismatic", s("p"))]))), "output.prismatic: 'p' is not a prismatic"),
        (fourbar(|d| set(d, "slots", list(vec![]))), "slots: must be a table name -> {point, guide, line}"),
        (
            fourbar(|d| {
                let slot = map(vec![("point", s("B")), ("guide", s("ground")), ("line", list(vec![s("O2")]))]);
                set(d, "slots", map(vec![("s", slot)]))
            }),
            "slots.s.line: must be a pair of point names, got ['O2']",
        ),
        (
            fourbar(|d| set(d, "prismatic", map(vec![("p", map(vec![("link", s("x"))]))]))),
            "prismatic.p: must be a table with keys 'link', 'guide' and 'line', got {'link': 'x'}",
        ),
        (
            fourbar(|d| set(d, "outputs", Value::Tuple(vec![s("B"), Value::Float(1.0)]))),
            "outputs: must be a list of point or link names, got ('B', 1.0)",
        ),
        (fourbar(|d| set(d, "units", Value::Float(1e-5))), "units: must be a string, got 1e-05"),
        (fourbar(|d| set(d, "lengths", map(vec![]))), "lengths: must be a list of [name, name, length], got {}"),
        (
            fourbar(|d| set(d, "lengths", list(vec![list(vec![s("A"), s("B")])]))),
            "lengths[0]: must be [name, name, length], got ['A', 'B']",
        ),
        (
            fourbar(|d| set(d, "lengths", list(vec![list(vec![s("A"), s("B"), Value::Bool(false)])]))),
            "lengths[0]: the length must be a real number, got False",
        ),
    ];
    for (data, want) in cases {
        assert_eq!(message(&data), want);
    }
}

#[test]
fn nesting_deeper_than_a_scene_names_the_entry() {
    let mut deep = Value::Float(1.0);
    for _ in 0..MAX_DEPTH + 3 {
        deep = list(vec![deep]);
    }
    let data = fourbar(|d| set(d, "description", deep));
    assert_eq!(message(&data), "scene: description[0][0][0][0][0][0][0][0][0][0][0][0][0][0][0] nests deeper than 16 levels (a scene has at most 4)");
    // exactly at the bound is fine for the walk (the entry's own check refuses it)
    let mut ok = Value::Float(1.0);
    for _ in 0..MAX_DEPTH - 2 {
        ok = list(vec![ok]);
    }
    let data = fourbar(|d| set(d, "description", ok));
    assert!(message(&data).starts_with("description: must be a string, got [[["));
}

#[test]
fn foreign_values_stand_for_what_they_are_like() {
    let np = |r: &str, like| Value::foreign(Described { repr: r.into(), type_name: "x".into() }, like);
    let data = fourbar(|d| {
        let a = np("array([1., 2.])", Like::Array(vec![np("np.float64(1.0)", Like::Real(1.0)), Value::Float(0.5)]));
        set(d, "points", map(vec![("O2", xy(0.0, 0.0)), ("A", a)]))
    });
    let p = parse(&data).expect("an array of two reals is a pair");
    assert_eq!(p.spec.points[1].1, [1.0, 0.5]);
    let data = fourbar(|d| set(d, "links", map(vec![("crank", np("array(['O2', 'A'])", Like::Array(vec![])))])));
    assert_eq!(message(&data), "links.crank: must be a list of point names, got array(['O2', 'A'])");
}

#[test]
fn defaults_are_numpys() {
    let v = linspace(-1.0, 2.0, 361);
    assert_eq!(v.len(), 361);
    assert_eq!((v[0], v[360]), (-1.0, 2.0));
    assert_eq!(v[7], 7.0 * (3.0 / 360.0) - 1.0);
    let t = default_inputs(0.25, None);
    assert_eq!(t[360], 0.25 + 360.0 * (std::f64::consts::TAU / 360.0));
    assert_eq!(size(&[[0.0, 0.0], [3.0, -1.0], [1.0, 1.5]]), 3.0);
    assert_eq!(MAX_STEP, 3f64.to_radians());
    assert_eq!(max_step(true, 2.0), 2.0 * MAX_STEP);
}

/// The four-bar with `loads` set to `loads`.
fn loaded(loads: Value) -> Value {
    fourbar(|d| set(d, "loads", loads))
}

fn f(x: f64) -> Value {
    Value::Float(x)
}

#[test]
fn units_read_as_a_string_or_a_table() {
    let p = parse(&fourbar(|d| set(d, "units", s("mm")))).unwrap();
    assert_eq!((p.units.as_deref(), p.unit_table), (Some("mm"), None));
    let t = map(vec![("length", s("mm")), ("force", s("N")), ("mass", s("kg"))]);
    let p = parse(&fourbar(|d| set(d, "units", t))).unwrap();
    assert_eq!(p.units.as_deref(), Some("mm"));
    let u = p.unit_table.unwrap();
    assert_eq!((u.force.as_deref(), u.mass.as_deref()), (Some("N"), Some("kg")));
    assert_eq!(u.to_value().repr(), "{'length': 'mm', 'force': 'N', 'mass': 'kg'}");
    for (units, want) in [
        (map(vec![("time", s("s"))]), "units: unknown key 'time'; known keys: length, force, mass"),
        (map(vec![("force", f(1.0))]), "units.force: must be a string, got 1.0"),
    ] {
        assert_eq!(message(&fourbar(|d| set(d, "units", units))), want);
    }
}

#[test]
fn loads_read_normalised() {
    let loads = map(vec![
        ("forces", list(vec![map(vec![("point", s("B")), ("force", xy(0.0, -50.0))])])),
        ("torques", list(vec![map(vec![("link", s("rocker")), ("torque", Value::Int(-2))])])),
        (
            "springs",
            list(vec![map(vec![("between", list(vec![s("A"), s("O4")])), ("k", f(400.0)), ("free_length", f(4.5))])]),
        ),
        ("gravity", xy(0.0, -9.81)),
        ("masses", map(vec![("coupler", map(vec![("mass", f(1.2)), ("center", xy(2.0, 1.0))]))])),
    ]);
    let p = parse(&loaded(loads)).unwrap();
    let l = p.loads.unwrap();
    assert_eq!(l.forces[0], (Target::Point("B".into()), Profile { input: None, values: vec![0.0, -50.0], width: 2 }));
    assert_eq!(l.torques[0].1.values, vec![-2.0]);
    assert_eq!((l.springs[0].rate, l.springs[0].free_length, l.springs[0].preload), (400.0, Some(4.5), 0.0));
    assert_eq!(l.gravity, Some([0.0, -9.81]));
    assert_eq!(l.masses[0].1, Mass { mass: 1.2, center: Center::At([2.0, 1.0]), inertia: 0.0 });
    assert_eq!(
        l.to_value().repr(),
        "{'forces': [{'point': 'B', 'force': [0.0, -50.0]}], 'torques': [{'link': 'rocker', 'torque': -2.0}], \
         'springs': [{'between': ['A', 'O4'], 'k': 400.0, 'free_length': 4.5, 'preload': 0.0}], 'dampers': [], \
         'gravity': [0.0, -9.81], 'masses': {'coupler': {'mass': 1.2, 'center': [2.0, 1.0], 'inertia': 0.0}}}"
    );
    // a table over the input
    let table = map(vec![(
        "torques",
        list(vec![map(vec![
            ("link", s("crank")),
            ("torque", list(vec![f(1.0), f(2.0)])),
            ("input", list(vec![f(0.0), f(1.0)])),
        ])]),
    )]);
    let l = parse(&loaded(table)).unwrap().loads.unwrap();
    assert_eq!(l.torques[0].1, Profile { input: Some(vec![0.0, 1.0]), values: vec![1.0, 2.0], width: 1 });
}

#[test]
fn every_load_entry_is_named_with_what_it_got() {
    let force = |k: &str, n: &str, v: Value| map(vec![("forces", list(vec![map(vec![(k, s(n)), ("force", v)])]))]);
    let mass = |m: Value| map(vec![("masses", map(vec![("coupler", m)]))]);
    let cases: Vec<(Value, &str)> = vec![
        (s("x"), "loads: must be a table with keys (optional 'forces', 'torques', 'springs', 'dampers', 'gravity', 'masses'), got 'x'"),
        (map(vec![("wind", f(1.0))]), "loads: unknown key 'wind'; keys: (optional 'forces', 'torques', 'springs', 'dampers', 'gravity', 'masses')"),
        (force("point", "Z", xy(0.0, 1.0)), "loads.forces[0].point: 'Z' is not a point of the scene"),
        (force("point", "B", f(1.0)), "loads.forces[0].force: must be a pair [x, y], got 1.0"),
        (force("slot", "piston", f(1.0)), "loads.forces[0].slot: must name a slot or prismatic pair of the scene, got 'piston'"),
        (
            map(vec![("forces", list(vec![map(vec![("link", s("crank"))])]))]),
            "loads.forces[0]: must have a key 'point', 'slot' or 'prismatic', got {'link': 'crank'}",
        ),
        (
            map(vec![("torques", list(vec![map(vec![("link", s("arm")), ("torque", f(1.0))])]))]),
            "loads.torques[0].link: 'arm' is not a link of the scene",
        ),
        (
            map(vec![(
                "torques",
                list(vec![map(vec![
                    ("link", s("crank")),
                    ("torque", list(vec![f(1.0)])),
                    ("input", list(vec![f(0.0), f(1.0)])),
                ])]),
            )]),
            "loads.torques[0].torque: must be a list of 2 values (one per input value), got [1.0]",
        ),
        (
            map(vec![(
                "torques",
                list(vec![map(vec![
                    ("link", s("crank")),
                    ("torque", list(vec![f(1.0), f(2.0)])),
                    ("input", list(vec![f(1.0), f(0.0)])),
                ])]),
            )]),
            "loads.torques[0].input: must be strictly increasing",
        ),
        (
            map(vec![("springs", list(vec![map(vec![("between", list(vec![s("A"), s("O4")])), ("k", f(-1.0)), ("free_length", f(1.0))])]))]),
            "loads.springs[0].k: must be >= 0, got -1.0",
        ),
        (
            map(vec![("springs", list(vec![map(vec![("between", list(vec![s("A"), s("A")])), ("k", f(1.0)), ("free_length", f(1.0))])]))]),
            "loads.springs[0].between: must name two different points, got ['A', 'A']",
        ),
        (
            map(vec![("dampers", list(vec![map(vec![("between", list(vec![s("A")])), ("c", f(1.0))])]))]),
            "loads.dampers[0].between: must be a pair of point names, got ['A']",
        ),
        (map(vec![("gravity", xy(0.0, f64::NAN))]), "loads.gravity[1]: must be finite, got nan"),
        (mass(map(vec![("mass", f(-1.0)), ("center", s("A"))])), "loads.masses.coupler.mass: must be >= 0, got -1.0"),
        (mass(map(vec![("mass", f(1.0)), ("center", s("O4"))])), "loads.masses.coupler.center: 'O4' is not a point of link 'coupler'"),
        (mass(map(vec![("mass", f(1.0))])), "loads.masses.coupler: must have key 'center', got {'mass': 1.0}"),
        (
            map(vec![("masses", map(vec![("arm", map(vec![("mass", f(1.0)), ("center", s("A"))]))]))]),
            "loads.masses.arm: 'arm' is not a link of the scene",
        ),
    ];
    for (loads, want) in cases {
        assert_eq!(message(&loaded(loads)), want);
    }
}
