//! Timing of the dedicated LP against clarabel on the discrete margin programmes of the
//! semicircular arch (K = 1.2, μ = 0.35, all rows): N = 64, 512, 4096 voussoirs, i.e.
//! 4(N + 1) + 1 rows in four unknowns (F_x, F_y, M₀, τ); and on the load-factor programme
//! of a horizontal load (K = 1.3, μ = 0.6, N = 64: 4(N + 1) + 1 rows in F_x, F_y, M₀, λ), with
//! the whole load-factor analysis of the continuum and of 64 voussoirs.

use archstudy::analysis::circular::CircularArch;
use archstudy::analysis::forms::ArchModel;
use archstudy::analysis::general::{self, LinearRows, OBJECTIVE, RowSet, Settings};
use archstudy::analysis::lp;
use archstudy::analysis::statics::ArchGeometry;
use archstudy::model::{Arch, ArchForm, Discretisation, Load, WeightModel};
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

/// The semicircular arch (K = 1.3) under self-weight and a live load.
fn loaded(joints: Discretisation, load: Load) -> ArchModel {
    let arch = Arch::new(1.3, 90.0, WeightModel::Annular, joints).expect("a valid arch");
    ArchModel::new(arch, ArchForm::default(), load).expect("a valid form")
}

/// The load-factor programme of 64 voussoirs under a horizontal load, μ = 0.6.
fn load_factor_programme() -> LinearRows {
    let g = loaded(Discretisation::Voussoirs(64), Load::Horizontal);
    let thetas = g.discrete_joints().unwrap_or_default();
    LinearRows::load_factor(&g, &thetas, 0.6f64.atan(), RowSet::All)
}

/// The dedicated LP on the 64-voussoir load-factor programme.
#[divan::bench]
fn load_factor_lp_64(bencher: Bencher) {
    let rows = load_factor_programme();
    let settings = lp::Settings::for_rows(rows.a.len());
    bencher.bench(|| {
        lp::maximise(
            black_box(&OBJECTIVE),
            black_box(&rows.a),
            &rows.b,
            &settings,
        )
    });
}

/// clarabel (setup and solve) on the same load-factor programme, for the ratio.
#[divan::bench]
fn load_factor_clarabel_64(bencher: Bencher) {
    use clarabel::algebra::CscMatrix;
    use clarabel::solver::{DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT};
    let rows = load_factor_programme();
    let p = CscMatrix::<f64>::zeros((4, 4));
    let q = OBJECTIVE.map(|c| -c);
    let a = CscMatrix::from(rows.a.iter());
    let cones = [NonnegativeConeT(rows.b.len())];
    bencher.bench(|| {
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

/// The whole load-factor analysis of 64 voussoirs: rows, LP and the mechanism's rows.
#[divan::bench]
fn load_factor_64() -> f64 {
    let g = loaded(Discretisation::Voussoirs(64), Load::Horizontal);
    general::load_factor(&g, 0.6f64.atan(), &Settings::default()).lambda
}

/// The whole load-factor analysis of the continuum (exchange method), horizontal load.
#[divan::bench]
fn load_factor_continuum_horizontal() -> f64 {
    let g = loaded(Discretisation::Continuum, Load::Horizontal);
    general::load_factor(&g, 0.6f64.atan(), &Settings::default()).lambda
}

/// The whole load-factor analysis of the continuum, point load at 30° (μ = ∞).
#[divan::bench]
fn load_factor_continuum_point() -> f64 {
    let g = loaded(Discretisation::Continuum, Load::Point { at_deg: 30.0 });
    general::load_factor(&g, std::f64::consts::FRAC_PI_2, &Settings::default()).lambda
}
