//! Whole-grid costs (`cargo bench --bench grid`): the seed `state` grid through the engine
//! (analysis only) and through the store, at several sizes to show the scaling in the number
//! of grid points.

use archstudy::engine::{self, Progress};
use archstudy::{manifest, plan, store};
use divan::{Bencher, black_box};
use std::path::Path;

fn main() {
    divan::main();
}

/// The seed study's ranges with `side` × `side` points.
fn seed_plan(side: usize) -> plan::Plan {
    let text = format!(
        "name: bench\ngrid:\n  k: {{from: 1.05, to: 1.5, steps: {side}}}\n  mu: {{from: 0.2, to: 0.8, steps: {side}}}\n"
    );
    let m = manifest::parse(&text, Path::new("bench.yaml")).expect("a valid manifest");
    plan::build(m).expect("a plan of allowed size")
}

/// Engine time of a side × side state grid (separable path, all cores).
#[divan::bench(args = [101, 201, 401, 1001], sample_count = 10)]
fn state_grid_engine(bencher: Bencher, side: usize) {
    let plan = seed_plan(side);
    bencher.bench(|| engine::run(black_box(&plan), Progress::Hidden).len());
}

/// Building the results table of a side × side state grid (no file I/O).
#[divan::bench(args = [101, 401, 1001], sample_count = 5)]
fn state_grid_results_frame(bencher: Bencher, side: usize) {
    let plan = seed_plan(side);
    let rows = engine::run(&plan, Progress::Hidden);
    bencher.bench(|| store::results_frame(black_box(&plan), &rows).map(|df| df.height()));
}
