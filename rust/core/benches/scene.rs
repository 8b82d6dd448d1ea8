//! Criterion benchmarks of scene sweeps in the core alone (no Python): the centred
//! slider-crank (r = 40, l = 160, the built-in `slider-crank`) over 361 crank angles, its
//! piston pin only and every point, with and without velocities. `benches/bench_slider.py`
//! times the same sweep from Python: the difference is the Python layers' cost.
//!
//! Run: `cargo bench -p planarkin-core --bench scene` (add `-- --quick` for a short run).

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use planarkin_core::scene::{Plan, Scene, SceneSpec, SceneSweepBuffers, SceneSweepOptions, SlotSpec};
use planarkin_core::{Never, NewtonOptions};

const N: usize = 361;

fn slider_crank() -> Scene {
    let s = |x: &str| x.to_string();
    let spec = SceneSpec {
        points: vec![
            (s("O2"), [0.0, 0.0]),
            (s("X"), [1.0, 0.0]),
            (s("A"), [34.64101615137755, 19.999999999999996]),
            (s("B"), [193.386094815253, 0.0]),
        ],
        links: vec![
            (s("ground"), vec![s("O2"), s("X")]),
            (s("crank"), vec![s("O2"), s("A")]),
            (s("rod"), vec![s("A"), s("B")]),
        ],
        ground: s("ground"),
        input: (s("crank"), s("O2")),
        output: None,
        slots: vec![(s("piston"), SlotSpec { point: s("B"), guide: s("ground"), line: (s("O2"), s("X")) })],
        prismatic: vec![],
        linear_input: None,
    };
    Scene::new(spec).expect("the built-in slider-crank is valid")
}

/// Output buffers of one sweep, allocated once outside the timed loop.
struct Bufs(SceneSweepBuffers);

impl Bufs {
    fn new(plan: &Plan, n: usize, kin: bool) -> Self {
        Bufs(SceneSweepBuffers::new(plan, n, kin).expect("the buffers fit"))
    }

    fn run(&mut self, plan: &Plan, theta: &[f64], opts: &SceneSweepOptions) {
        plan.sweep(black_box(theta), opts, self.0.out(), &Never).expect("the sweep runs");
    }
}

/// A row: its name, the requested outputs (None: all), omega and max_step.
type Case = (&'static str, Option<Vec<String>>, Option<f64>, f64);

fn slider(c: &mut Criterion) {
    let sc = slider_crank();
    let theta: Vec<f64> = (0..N).map(|k| sc.input_angle() + (k as f64).to_radians()).collect();
    let mut g = c.benchmark_group("slider_crank_361");
    g.throughput(Throughput::Elements(N as u64));
    let max_step = 3f64.to_radians();
    let cases: [Case; 4] = [
        ("piston", Some(vec!["B".into()]), None, max_step),
        ("all", None, None, max_step),
        ("all_omega", None, Some(1.0), max_step),
        // steps larger than max_step: the continuation path, whatever the plan
        ("piston_continuation", Some(vec!["B".into()]), None, 0.5f64.to_radians()),
    ];
    for (name, outputs, omega, ms) in cases {
        let plan = sc.plan(outputs.as_deref()).expect("the plan compiles");
        let opts = SceneSweepOptions::new(NewtonOptions::default(), ms, omega).expect("valid options");
        let mut b = Bufs::new(&plan, N, omega.is_some());
        g.bench_function(name, |bch| bch.iter(|| b.run(&plan, &theta, &opts)));
    }
    // a full turn from 30 deg past the drawn angle: the same column path (issue 36)
    let plan = sc.plan(Some(&["B".to_string()])).expect("the plan compiles");
    let opts = SceneSweepOptions::new(NewtonOptions::default(), max_step, None).expect("valid options");
    let shifted: Vec<f64> = theta.iter().map(|t| t + 30f64.to_radians()).collect();
    let mut b = Bufs::new(&plan, N, false);
    g.bench_function("piston_from_30", |bch| bch.iter(|| b.run(&plan, &shifted, &opts)));
    g.finish();
}

criterion_group!(benches, slider);
criterion_main!(benches);
