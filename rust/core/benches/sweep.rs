//! Criterion benchmarks of the core alone (no Python): the seed sweep (r = 6, 2, 5, 5,
//! 361 crank angles) with each predictor, the closed form over the same angles, one
//! Newton solve, and a small batch. `benches/report.py` compares the seed-sweep time with
//! the same sweep called from Python to measure the Python-side overhead.
//!
//! Rows ending in `_scalar` run with the SIMD kernels off (the bit-exact scalar path).
//!
//! Run: `cargo bench -p planarkin-core --bench sweep` (add `-- --quick` for a short run).

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use planarkin_core::fourbar::{
    closed_form_batch, closed_form_into, default_angles, sweep_batch, sweep_into, validate_links, BatchOut, SweepOut,
};
use planarkin_core::solve::newton::SINGULAR_THRESHOLD;
use planarkin_core::{simd, FourBar, Method, Mode, Never, NewtonOptions, Predictor, SweepOptions};

const N: usize = 361;

fn opts(predictor: Predictor) -> SweepOptions {
    SweepOptions { mode: Mode::Open, newton: NewtonOptions::default(), predictor, method: Method::Newton }
}

/// Output buffers of one sweep, allocated once outside the timed loop.
struct Bufs {
    t3: Vec<f64>,
    t4: Vec<f64>,
    st: Vec<i8>,
    nit: Vec<u32>,
    res: Vec<f64>,
}

impl Bufs {
    fn new(n: usize) -> Self {
        Bufs { t3: vec![0.0; n], t4: vec![0.0; n], st: vec![0; n], nit: vec![0; n], res: vec![0.0; n] }
    }

    fn out(&mut self) -> SweepOut<'_> {
        SweepOut {
            theta3: &mut self.t3,
            theta4: &mut self.t4,
            status: &mut self.st,
            nit: &mut self.nit,
            residual: &mut self.res,
        }
    }

    /// The same buffers as the (M, N) outputs of a batch.
    fn batch(&mut self) -> BatchOut<'_> {
        let SweepOut { theta3, theta4, status, nit, residual } = self.out();
        BatchOut { theta3, theta4, status, nit, residual }
    }
}

fn seed_sweep(c: &mut Criterion) {
    let fb = FourBar::new(6.0, 2.0, 5.0, 5.0).unwrap();
    let t2 = default_angles(N);
    let mut g = c.benchmark_group("seed_sweep_361");
    g.throughput(Throughput::Elements(N as u64));
    for (name, p) in [
        ("quadratic", Predictor::Quadratic),
        ("tangent", Predictor::Tangent),
        ("previous", Predictor::Previous),
        ("closed_form_predicted", Predictor::ClosedForm),
    ] {
        let o = opts(p);
        let mut b = Bufs::new(N);
        g.bench_function(name, |bch| {
            bch.iter(|| sweep_into(black_box(&fb), black_box(&t2), None, &o, b.out(), None, &Never).unwrap())
        });
    }
    // What the binding does on each call: allocate the five outputs, then sweep.
    let o = opts(Predictor::Quadratic);
    g.bench_function("quadratic_alloc", |bch| {
        bch.iter(|| {
            let mut b = Bufs::new(N);
            sweep_into(black_box(&fb), black_box(&t2), None, &o, b.out(), None, &Never).unwrap();
            b
        })
    });
    let (mut t3, mut t4, mut st) = (vec![0.0; N], vec![0.0; N], vec![0i8; N]);
    g.bench_function("closed_form", |bch| {
        bch.iter(|| {
            let (fb, t2) = (black_box(&fb), black_box(&t2));
            closed_form_into(fb, t2, Mode::Open, SINGULAR_THRESHOLD, &mut t3, &mut t4, &mut st, &Never).unwrap()
        })
    });
    // the bit-exact scalar path, for the SIMD speed-up
    let was = simd::set_enabled(false);
    let mut b = Bufs::new(N);
    g.bench_function("quadratic_scalar", |bch| {
        bch.iter(|| sweep_into(black_box(&fb), black_box(&t2), None, &o, b.out(), None, &Never).unwrap())
    });
    g.bench_function("closed_form_scalar", |bch| {
        bch.iter(|| {
            closed_form_into(
                black_box(&fb),
                black_box(&t2),
                Mode::Open,
                SINGULAR_THRESHOLD,
                &mut t3,
                &mut t4,
                &mut st,
                &Never,
            )
            .unwrap()
        })
    });
    simd::set_enabled(was);
    g.finish();
}

fn single_solve(c: &mut Criterion) {
    let fb = FourBar::new(6.0, 2.0, 5.0, 5.0).unwrap();
    let o = NewtonOptions::default();
    let mut g = c.benchmark_group("solve_1");
    g.bench_function("closed_form_start", |b| b.iter(|| fb.solve(black_box(0.3), Mode::Open, None, &o, None)));
    g.finish();
}

/// Deterministic crank-rocker-ish lengths (no RNG crate needed): a linear congruential walk.
fn links(m: usize) -> Vec<f64> {
    let mut s: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut next = || {
        s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..m).flat_map(|_| [5.0 + next(), 1.0 + next(), 4.0 + 2.0 * next(), 4.0 + 2.0 * next()]).collect()
}

fn batch(c: &mut Criterion) {
    let t2 = default_angles(N);
    let m = 1000;
    let fbs = validate_links(&links(m)).unwrap();
    let mut g = c.benchmark_group("batch_1000x361");
    g.throughput(Throughput::Elements((m * N) as u64));
    g.sample_size(20);
    let o = opts(Predictor::Quadratic);
    for threads in [1usize, 2] {
        g.bench_function(format!("sweep_threads_{threads}"), |bch| {
            bch.iter_batched_ref(
                || Bufs::new(m * N),
                |b| sweep_batch(&fbs, &t2, &o, b.batch(), Some(threads), &Never).unwrap(),
                BatchSize::LargeInput,
            )
        });
    }
    let (mut t3, mut t4) = (vec![0.0; m * N], vec![0.0; m * N]);
    for scalar in [false, true] {
        // the bit-exact scalar path, for the SIMD speed-up
        let was = simd::set_enabled(!scalar);
        let tag = if scalar { "_scalar" } else { "" };
        g.bench_function(format!("closed_form_threads_1{tag}"), |bch| {
            bch.iter(|| {
                closed_form_batch(&fbs, &t2, Mode::Open, SINGULAR_THRESHOLD, &mut t3, &mut t4, None, Some(1), &Never)
                    .unwrap()
            })
        });
        if scalar {
            g.bench_function("sweep_threads_1_scalar", |bch| {
                bch.iter_batched_ref(
                    || Bufs::new(m * N),
                    |b| sweep_batch(&fbs, &t2, &o, b.batch(), Some(1), &Never).unwrap(),
                    BatchSize::LargeInput,
                )
            });
        }
        simd::set_enabled(was);
    }
    g.finish();
}

criterion_group!(benches, seed_sweep, single_solve, batch);
criterion_main!(benches);
