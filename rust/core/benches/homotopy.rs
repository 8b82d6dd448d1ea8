//! The all-solutions homotopy on random double butterflies, through the public scene API:
//! the time of one solve, and (with `stats`) how often tracking loses a root over 1000
//! random geometries of each inversion. A harness that prints, not a test: CI does not
//! run it.
//!
//!     cargo bench -p planarkin-core --bench homotopy              # timing, ~10 s
//!     cargo bench -p planarkin-core --bench homotopy -- stats     # statistics, minutes
//!
//! The double butterfly's links (seed 003's numbering): 1 bar A K; 2 ternary A B C;
//! 3 ternary B D E; 4 bar E H; 5 ternary H I K; 6 bar D G; 7 ternary F G I; 8 bar C F.
//! Each geometry draws the ten joints at random in [-1, 1]^2, each scaled by
//! 10^U(-spread, spread) (links of disparate lengths are harder), and is a valid
//! scene as drawn (lengths come from the drawing).

use std::collections::BTreeMap;
use std::time::Instant;

use planarkin_core::scene::{Scene, SceneSpec};
use planarkin_core::solve::homotopy::HomotopyOptions;
use planarkin_core::Never;

const JOINTS: &str = "ABCDEFGHIK";
const LINKS: [(&str, &str); 8] = [
    ("l1", "AK"),
    ("l2", "ABC"),
    ("l3", "BDE"),
    ("l4", "EH"),
    ("l5", "HIK"),
    ("l6", "DG"),
    ("l7", "FGI"),
    ("l8", "CF"),
];

/// An inversion: (name, ground link, input link, input pivot, finite complex assemblies
/// expected; Waldron and Sreenivasan 1996 give 18 with the input at a butterfly hinge,
/// 16 at a ternary-bar joint).
type Inversion = (&'static str, &'static str, &'static str, &'static str, usize);

const INVERSIONS: [Inversion; 3] = [
    ("bar ground, input at A (ternary-bar joint)", "l1", "l2", "A", 16),
    ("ternary ground, input at hinge I", "l5", "l7", "I", 18),
    ("ternary ground, input at H (ternary-bar joint)", "l5", "l4", "H", 16),
];

/// splitmix64: reproducible geometries with no dependency.
struct Rng(u64);

impl Rng {
    fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn scene(rng: &mut Rng, spread: f64, inv: &Inversion) -> Option<Scene> {
    let points = JOINTS
        .chars()
        .map(|c| {
            let f = 10f64.powf(spread * (2.0 * rng.uniform() - 1.0));
            (c.to_string(), [(2.0 * rng.uniform() - 1.0) * f, (2.0 * rng.uniform() - 1.0) * f])
        })
        .collect();
    let links = LINKS.iter().map(|(n, js)| (n.to_string(), js.chars().map(String::from).collect())).collect();
    let spec = SceneSpec {
        points,
        links,
        ground: inv.1.into(),
        input: (inv.2.into(), inv.3.into()),
        output: None,
        ..Default::default()
    };
    // a random drawing can be degenerate (the rank check refuses it): skipped, counted
    Scene::new(spec).ok()
}

fn timing() {
    let mut rng = Rng(300);
    for inv in &INVERSIONS {
        let sc = scene(&mut rng, 0.0, inv).expect("a regular drawing");
        for runs in [1, 2] {
            let o = HomotopyOptions::new(HomotopyOptions::default().seed, runs).unwrap();
            let mut t: Vec<f64> = (0..40)
                .map(|_| {
                    let t0 = Instant::now();
                    std::hint::black_box(sc.assemblies(sc.input_angle(), &o, &Never).unwrap());
                    t0.elapsed().as_secs_f64() * 1e3
                })
                .collect();
            t.sort_by(f64::total_cmp);
            println!("{}, runs {runs}: min {:.2} ms, median {:.2} ms over 40 solves", inv.0, t[0], t[20]);
        }
    }
}

fn stats(inv: &Inversion, spread: f64, seed: u64) {
    let count = 1000;
    let mut rng = Rng(seed);
    let (mut counts, mut failed, mut short, mut pose_missing, mut skipped) = (BTreeMap::new(), 0, 0, 0, 0);
    let mut times = Vec::new();
    for _ in 0..count {
        let Some(sc) = scene(&mut rng, spread, inv) else {
            skipped += 1;
            continue;
        };
        let t = Instant::now();
        let a = sc.assemblies(sc.input_angle(), &HomotopyOptions::default(), &Never).unwrap();
        times.push(t.elapsed().as_secs_f64());
        let found: usize = a.complex_counts.iter().flatten().sum();
        *counts.entry(found).or_insert(0) += 1;
        failed += a.failed_paths;
        short += inv.4.saturating_sub(found);
        let drawn = sc.drawn();
        let tol = 1e-9 * sc.scale();
        let is_drawn =
            |p: &[[f64; 2]]| p.iter().zip(drawn).all(|(q, d)| (q[0] - d[0]).abs().max((q[1] - d[1]).abs()) < tol);
        if !a.list.iter().any(|x| is_drawn(&x.points)) {
            pose_missing += 1;
        }
    }
    times.sort_by(f64::total_cmp);
    let n = times.len().max(1);
    println!("{}, spread {spread}: {} geometries ({skipped} degenerate drawings skipped)", inv.0, times.len());
    println!("  complex root counts {counts:?} (expected {}); roots lost {short}; failed paths {failed}", inv.4);
    println!("  drawn pose not among the real assemblies: {pose_missing}");
    println!(
        "  time per solve: median {:.1} ms, max {:.1} ms",
        times.get(n / 2).copied().unwrap_or(f64::NAN) * 1e3,
        times.last().copied().unwrap_or(f64::NAN) * 1e3
    );
}

fn main() {
    if std::env::args().any(|a| a == "stats") {
        stats(&INVERSIONS[1], 0.0, 4343);
        stats(&INVERSIONS[0], 1.0, 4444);
        stats(&INVERSIONS[0], 0.0, 4242);
        stats(&INVERSIONS[2], 0.0, 4545);
    } else {
        timing();
    }
}
