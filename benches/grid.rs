//! Whole-grid costs (`cargo bench --bench grid`): the seed `state` grid through the engine
//! (analysis only) and through the store, at several sizes to show the scaling in the number
//! of grid points; and whole runs (`archstudy run`: engine, Parquet, boundaries, figure data,
//! figures and reports) of the seed study and of a 1001 × 1001 map over the same ranges. The
//! same engine on a pointed arch and on vertical joints (per K line) at 101² and 201².

use archstudy::engine;
use archstudy::runner::{self, RunOptions};
use archstudy::{manifest, plan, store};
use divan::counter::ItemsCount;
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

/// Engine time of a side × side state grid (separable path, all cores), into compact rows
/// written over one buffer, as a run's chunks are.
#[divan::bench(args = [101, 201, 401, 1001], sample_count = 10)]
fn state_grid_engine(bencher: Bencher, side: usize) {
    let plan = seed_plan(side);
    let mut rows = engine::Rows::default();
    // Points per second in the output: constant when the cost is linear in the points.
    bencher
        .counter(ItemsCount::new(plan.cases.len()))
        .bench_local(|| {
            engine::analyse_rows(black_box(&plan), &archstudy::progress::Silent, &mut rows);
            matches!(rows, engine::Rows::States(_))
        });
}

/// The seed ranges on another form (`arch` is the manifest's `arch:` block), side × side.
fn form_plan(arch: &str, side: usize) -> plan::Plan {
    let text = format!(
        "name: bench\narch:\n{arch}\ngrid:\n  k: {{from: 1.05, to: 1.5, steps: {side}}}\n  mu: {{from: 0.2, to: 0.8, steps: {side}}}\n"
    );
    let m = manifest::parse(&text, Path::new("bench.yaml")).expect("a valid manifest");
    plan::build(m).expect("a plan of allowed size")
}

/// Engine time of a side × side state grid of a pointed arch (e = 0.2): per K line, a few
/// margins of the general route each; compare with `state_grid_engine` at the same size.
#[divan::bench(args = [101, 201], sample_count = 10)]
fn pointed_state_grid_engine(bencher: Bencher, side: usize) {
    let plan = form_plan("  shape: pointed\n  eccentricity: 0.2", side);
    bencher
        .counter(ItemsCount::new(plan.cases.len()))
        .bench(|| engine::run(black_box(&plan), &archstudy::progress::Silent).len());
}

/// Engine time of a side × side state grid of a semicircle with vertical joints.
#[divan::bench(args = [101, 201], sample_count = 10)]
fn vertical_joints_state_grid_engine(bencher: Bencher, side: usize) {
    let plan = form_plan("  joints: vertical", side);
    bencher
        .counter(ItemsCount::new(plan.cases.len()))
        .bench(|| engine::run(black_box(&plan), &archstudy::progress::Silent).len());
}

/// Building the results table of a side × side state grid from its compact rows (no file
/// I/O), as a run does.
#[divan::bench(args = [101, 401, 1001], sample_count = 5)]
fn state_grid_results_frame(bencher: Bencher, side: usize) {
    let plan = seed_plan(side);
    let mut rows = engine::Rows::default();
    engine::analyse_rows(&plan, &archstudy::progress::Silent, &mut rows);
    let engine::Rows::States(states) = rows else {
        panic!("the seed grid takes the separable path");
    };
    bencher
        .counter(ItemsCount::new(states.len()))
        .bench(|| store::state_results_frame(black_box(&plan), &states).map(|df| df.height()));
}

/// One whole run of a manifest into a scratch directory (replaced by every run).
fn run(bencher: Bencher, study: &Path) {
    let out = std::env::temp_dir().join(format!("archstudy-bench-{}", std::process::id()));
    let opts = RunOptions {
        command_line: vec!["bench".into()],
        ..RunOptions::new(study, &out)
    };
    bencher.bench(|| runner::run_study(black_box(&opts)).map(|s| s.info.cases.total));
    let _ = std::fs::remove_dir_all(&out);
}

/// `archstudy run studies/seed.yaml` (451 × 601 points) end to end.
#[divan::bench(sample_count = 5)]
fn seed_study_end_to_end(bencher: Bencher) {
    run(
        bencher,
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("studies/seed.yaml"),
    );
}

/// A 1001 × 1001 state map over the seed ranges, end to end.
#[divan::bench(sample_count = 5)]
fn state_map_1001_end_to_end(bencher: Bencher) {
    let dir = std::env::temp_dir().join(format!("archstudy-bench-m-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a scratch directory");
    let study = dir.join("map1001.yaml");
    std::fs::write(
        &study,
        "name: map1001\ngrid:\n  k: {from: 1.05, to: 1.5, steps: 1001}\n  mu: {from: 0.2, to: 0.8, steps: 1001}\n",
    )
    .expect("a scratch manifest");
    run(bencher, &study);
    let _ = std::fs::remove_dir_all(&dir);
}
