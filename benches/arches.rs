//! One state solve per arch kind and load kind (`cargo bench --bench arches`): a group per
//! arch (circular with radial joints, circular with vertical joints, pointed e = 0.2, 64
//! voussoirs), in each the self-weight, horizontal (λ = 0.1) and point (λ = 0.1 at 30°) scenes
//! at (K, μ) = (1.3, 0.5). `scene` is the route `archstudy` takes for the scene; `general` is
//! the general three-unknown route on the same scene (its regime from the feasibility of the
//! rotational rows, the sliding rows and all rows), so the ratio of the two medians in one
//! run is the speed-up of the route taken over the general LP.

use archstudy::analysis::forms::ArchModel;
use archstudy::analysis::general::{self, Settings};
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
        "point" => Load::Point { at_deg: 30.0 },
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
        ..Settings::default()
    };
    bencher.bench(|| general::regime(black_box(&model), s.friction.angle(), &settings).regime);
}

const CIRCULAR: ArchForm = ArchForm {
    shape: Shape::Circular,
    joints: JointOrientation::Radial,
};
const VERTICAL: ArchForm = ArchForm {
    shape: Shape::Circular,
    joints: JointOrientation::Vertical,
};
const POINTED: ArchForm = ArchForm {
    shape: Shape::Pointed { eccentricity: 0.2 },
    joints: JointOrientation::Radial,
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
