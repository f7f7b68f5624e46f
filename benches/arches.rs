//! One state solve per arch kind and load kind (`cargo bench --bench arches`): a group per
//! arch (circular with radial joints, circular with vertical joints, pointed e = 0.2, 64
//! voussoirs), in each the self-weight, horizontal (λ = 0.1) and point (λ = 0.1 at 30°) scenes
//! at (K, μ) = (1.3, 0.5). `scene` is the route `archstudy` takes for the scene (under
//! self-weight the closed forms of the circular arch with radial joints, the right half in
//! the symmetric unknowns on the other forms); `general` is the general three-unknown route
//! over the whole arch on the same scene (its regime from the feasibility of the rotational
//! rows, the sliding rows and all rows), so the ratio of the two medians in one run is the
//! speed-up of the route taken over the general LP.
//!
//! `critical` times the critical-value searches of the symmetric forms under self-weight
//! (K_c at μ = 0.4 and μ_c at K = 1.3), on the right half in the symmetric unknowns (`half`)
//! and over the whole arch in three unknowns (`whole`), for their ratio.
//!
//! `load_factor` times the largest load factor λ_max of the semicircle (K = 1.3): the
//! continuum under a horizontal load (μ = 0.6) and under a point load at 30° (μ = ∞), and
//! 64 voussoirs under the horizontal load, whose programme (4·65 + 1 rows in F_x, F_y, M₀,
//! λ) is also solved by the dedicated LP alone and by clarabel (setup and solve), for their
//! ratio.

use archstudy::analysis::forms::ArchModel;
use archstudy::analysis::general::{self, LinearRows, OBJECTIVE, RowSet, Settings};
use archstudy::analysis::lp;
use archstudy::analysis::statics::ArchGeometry;
use archstudy::model::{
    Arch, ArchForm, Discretisation, Friction, JointOrientation, Load, Shape, WeightModel,
};
use archstudy::scene::{self, Find, Scene};
use divan::{Bencher, black_box};

fn main() {
    divan::main();
}

const LOADS: [&str; 3] = ["self_weight", "horizontal", "point"];

fn load(name: &str) -> Load {
    match name {
        "horizontal" => Load::Horizontal,
        "point" => Load::point(30.0),
        _ => Load::SelfWeight,
    }
}

fn scene_of(form: ArchForm, joints: Discretisation, load_name: &str) -> Scene {
    let arch = Arch::new(1.3, 90.0, WeightModel::Annular, joints).expect("a valid arch");
    let load = load(load_name);
    Scene {
        arch,
        friction: Friction::new(0.5).expect("μ ≥ 0"),
        find: Find::State,
        form,
        load,
        lambda: if load == Load::SelfWeight { 0.0 } else { 0.1 },
    }
}

fn bench_scene(bencher: Bencher, s: &Scene) {
    bencher.bench(|| scene::solve(black_box(s)).regime());
}

fn bench_general(bencher: Bencher, s: &Scene) {
    let model = ArchModel::new(s.arch, s.form, s.load).expect("a valid form");
    let settings = Settings {
        lambda: s.lambda,
        symmetric_half: false,
        ..Settings::default()
    };
    bencher.bench(|| general::regime(black_box(&model), s.friction.angle(), &settings).regime);
}

const CIRCULAR: ArchForm = ArchForm {
    shape: Shape::Circular,
    joints: JointOrientation::Radial,
    keystone: false,
};
const VERTICAL: ArchForm = ArchForm {
    shape: Shape::Circular,
    joints: JointOrientation::Vertical,
    keystone: false,
};
const POINTED: ArchForm = ArchForm {
    shape: Shape::Pointed { eccentricity: 0.2 },
    joints: JointOrientation::Radial,
    keystone: false,
};

mod circular {
    use super::*;

    #[divan::bench(args = LOADS)]
    fn scene(b: Bencher, l: &str) {
        bench_scene(b, &scene_of(CIRCULAR, Discretisation::Continuum, l));
    }

    #[divan::bench(args = LOADS)]
    fn general(b: Bencher, l: &str) {
        bench_general(b, &scene_of(CIRCULAR, Discretisation::Continuum, l));
    }
}

mod vertical_joints {
    use super::*;

    #[divan::bench(args = LOADS)]
    fn scene(b: Bencher, l: &str) {
        bench_scene(b, &scene_of(VERTICAL, Discretisation::Continuum, l));
    }

    #[divan::bench(args = LOADS)]
    fn general(b: Bencher, l: &str) {
        bench_general(b, &scene_of(VERTICAL, Discretisation::Continuum, l));
    }
}

mod pointed {
    use super::*;

    #[divan::bench(args = LOADS)]
    fn scene(b: Bencher, l: &str) {
        bench_scene(b, &scene_of(POINTED, Discretisation::Continuum, l));
    }

    #[divan::bench(args = LOADS)]
    fn general(b: Bencher, l: &str) {
        bench_general(b, &scene_of(POINTED, Discretisation::Continuum, l));
    }
}

mod voussoirs {
    use super::*;

    #[divan::bench(args = LOADS)]
    fn scene(b: Bencher, l: &str) {
        bench_scene(b, &scene_of(CIRCULAR, Discretisation::Voussoirs(64), l));
    }

    #[divan::bench(args = LOADS)]
    fn general(b: Bencher, l: &str) {
        bench_general(b, &scene_of(CIRCULAR, Discretisation::Voussoirs(64), l));
    }
}

mod critical {
    use super::*;

    const FORMS: [&str; 3] = ["pointed", "vertical_joints", "pointed_9_voussoirs"];

    fn form(name: &str) -> (ArchForm, Discretisation) {
        match name {
            "vertical_joints" => (VERTICAL, Discretisation::Continuum),
            "pointed_9_voussoirs" => (POINTED, Discretisation::Voussoirs(9)),
            _ => (POINTED, Discretisation::Continuum),
        }
    }

    fn settings(half: bool) -> Settings {
        Settings {
            symmetric_half: half,
            ..Settings::default()
        }
    }

    fn model(name: &str, k: f64) -> Option<ArchModel> {
        let (form, joints) = form(name);
        let arch = Arch::new(k, 90.0, WeightModel::Annular, joints).ok()?;
        ArchModel::new(arch, form, Load::SelfWeight).ok()
    }

    fn thickness(bencher: Bencher, name: &str, half: bool) {
        let s = settings(half);
        let mu = Friction::new(0.4).expect("μ ≥ 0");
        bencher.bench(|| {
            general::thickness_with(|k| model(name, k), 3.0, None, black_box(mu), &s)
                .found()
                .and_then(|c| c.k)
        });
    }

    fn friction(bencher: Bencher, name: &str, half: bool) {
        let s = settings(half);
        let m = model(name, 1.3).expect("a valid arch");
        bencher.bench(|| general::friction(black_box(&m), &s).found().map(|c| c.mu));
    }

    #[divan::bench(args = FORMS)]
    fn thickness_half(b: Bencher, name: &str) {
        thickness(b, name, true);
    }

    #[divan::bench(args = FORMS)]
    fn thickness_whole(b: Bencher, name: &str) {
        thickness(b, name, false);
    }

    #[divan::bench(args = FORMS)]
    fn friction_half(b: Bencher, name: &str) {
        friction(b, name, true);
    }

    #[divan::bench(args = FORMS)]
    fn friction_whole(b: Bencher, name: &str) {
        friction(b, name, false);
    }
}

mod load_factor {
    use super::*;

    /// The semicircle (K = 1.3) under self-weight and a live load.
    fn loaded(joints: Discretisation, load: Load) -> ArchModel {
        let arch = Arch::new(1.3, 90.0, WeightModel::Annular, joints).expect("a valid arch");
        ArchModel::new(arch, CIRCULAR, load).expect("a valid form")
    }

    /// μ = 0.6 as a friction angle.
    fn phi() -> f64 {
        0.6f64.atan()
    }

    /// The load-factor programme of 64 voussoirs under a horizontal load, μ = 0.6.
    fn programme_64() -> LinearRows {
        let g = loaded(Discretisation::Voussoirs(64), Load::Horizontal);
        let thetas = g.discrete_joints().unwrap_or_default();
        LinearRows::load_factor(&g, &thetas, phi(), RowSet::All)
    }

    /// The whole analysis of the continuum (exchange method), horizontal load, μ = 0.6.
    #[divan::bench]
    fn continuum_horizontal(bencher: Bencher) {
        let g = loaded(Discretisation::Continuum, Load::Horizontal);
        bencher.bench(|| general::load_factor(black_box(&g), phi(), &Settings::default()).lambda);
    }

    /// The whole analysis of the continuum, point load at 30°, μ = ∞.
    #[divan::bench]
    fn continuum_point_30(bencher: Bencher) {
        let g = loaded(Discretisation::Continuum, Load::point(30.0));
        let phi = std::f64::consts::FRAC_PI_2;
        bencher.bench(|| general::load_factor(black_box(&g), phi, &Settings::default()).lambda);
    }

    /// The whole analysis of 64 voussoirs: rows, programme and the mechanism's rows.
    #[divan::bench]
    fn voussoirs_64(bencher: Bencher) {
        let g = loaded(Discretisation::Voussoirs(64), Load::Horizontal);
        bencher.bench(|| general::load_factor(black_box(&g), phi(), &Settings::default()).lambda);
    }

    /// The dedicated LP on the 64-voussoir programme.
    #[divan::bench]
    fn lp_64_dedicated(bencher: Bencher) {
        let rows = programme_64();
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

    /// clarabel (setup and solve) on the same programme.
    #[divan::bench]
    fn lp_64_clarabel(bencher: Bencher) {
        use clarabel::algebra::CscMatrix;
        use clarabel::solver::{DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT};
        let rows = programme_64();
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
}
