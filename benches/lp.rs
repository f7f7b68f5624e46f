//! Timing of the dedicated LP against clarabel on the discrete margin programmes of the
//! semicircular arch (K = 1.2, μ = 0.35, all rows): N = 64, 512, 4096 voussoirs, i.e.
//! 4(N + 1) + 1 rows in four unknowns (F_x, F_y, M₀, τ), and the continuum margin by the
//! exchange method. The load-factor programmes are timed in `benches/arches.rs`.

use archstudy::analysis::circular::CircularArch;
use archstudy::analysis::general::{self, LinearRows, OBJECTIVE, RowSet, Settings};
use archstudy::analysis::lp;
use archstudy::analysis::statics::ArchGeometry;
use archstudy::model::{Arch, Discretisation, WeightModel};
use divan::counter::ItemsCount;
use divan::{Bencher, black_box};

fn main() {
    divan::main();
}

fn geometry(joints: Discretisation) -> CircularArch {
    let arch = Arch::new(1.2, 90.0, WeightModel::Annular, joints).expect("a valid arch");
    CircularArch::new(arch)
}

/// The margin programme of an N-voussoir arch.
fn programme(n: u32) -> LinearRows {
    let g = geometry(Discretisation::Voussoirs(n));
    let thetas = g.discrete_joints().unwrap_or_default();
    LinearRows::margin(&g, &thetas, 0.35f64.atan(), RowSet::All, 0.0, 1.0)
}

/// The dedicated LP on the margin programme.
#[divan::bench(args = [64, 512, 4096])]
fn dedicated_lp(bencher: Bencher, n: u32) {
    let rows = programme(n);
    let settings = lp::Settings::for_rows(rows.a.len());
    // Rows per second in the output: constant when the cost is linear in N.
    bencher.counter(ItemsCount::new(rows.a.len())).bench(|| {
        lp::maximise(
            black_box(&OBJECTIVE),
            black_box(&rows.a),
            &rows.b,
            &settings,
        )
    });
}

/// clarabel (setup and solve) on the same programmes, for the ratio.
#[divan::bench(args = [64, 512, 4096])]
fn clarabel(bencher: Bencher, n: u32) {
    use clarabel::algebra::CscMatrix;
    use clarabel::solver::{DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT};
    let rows = programme(n);
    let p = CscMatrix::<f64>::zeros((4, 4));
    let q = OBJECTIVE.map(|c| -c);
    let a = CscMatrix::from(rows.a.iter());
    let cones = [NonnegativeConeT(rows.b.len())];
    bencher.counter(ItemsCount::new(rows.a.len())).bench(|| {
        let settings = DefaultSettingsBuilder::default()
            .verbose(false)
            .build()
            .expect("valid settings");
        let mut solver = DefaultSolver::new(&p, &q, &a, black_box(&rows.b), &cones, settings)
            .expect("a well-formed problem");
        solver.solve();
        solver.solution.x[3]
    });
}

/// The whole general route for the continuum: one margin by the exchange method.
#[divan::bench]
fn continuum_margin() -> f64 {
    let g = geometry(Discretisation::Continuum);
    general::margin(&g, 0.35f64.atan(), RowSet::All, &Settings::default()).margin
}
