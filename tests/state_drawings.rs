//! The drawings of states, checked on their own geometry: the angle labels of hinges and
//! sliding joints stand clear of the masonry and of the hatched supports.

use crate::common::{StudyRun, study_run};
use archstudy::manifest::FigureWidth;
use archstudy::output::RunLayout;
use archstudy::plot::state::{StateDrawing, box_meets_polygon, boxes_meet};
use archstudy::plot::{Figure, Format, PlotContext, paper};
use archstudy::report::charts::{self, Chart};
use archstudy::report::data;
use std::path::Path;

/// A study of the repository's `studies/` directory, run into a scratch directory.
fn run_example(name: &str) -> StudyRun {
    let file = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("studies")
        .join(format!("{name}.yaml"));
    let text = std::fs::read_to_string(&file).expect("the example study");
    study_run(&format!("labels-{name}"), "study.yaml", &text)
}

/// The state drawings of a run, as the report draws them.
fn drawings(run: &Path) -> Vec<(String, StateDrawing)> {
    let data = data::load(&RunLayout::at(run)).expect("the run reads back");
    charts::build(&data)
        .into_iter()
        .filter_map(|f| match f.chart {
            Chart::State(d) => Some((f.stem, d)),
            _ => None,
        })
        .collect()
}

/// Every angle label of every state drawing of `study`, laid out for the PNG and for the
/// single-column paper figure, misses the outline of the arch and the box of either
/// support's hatching; returns how many labels name a springing (|angle| = 90°).
fn assert_labels_clear(study: &str) -> usize {
    let run = run_example(study);
    let mut at_springing = 0;
    let all = drawings(&run);
    assert!(!all.is_empty(), "{study}: no state drawn");
    for (stem, d) in &all {
        // The print layouts the run draws (PNG and PDF are converted from them), with the
        // plotting area left by titles, subtitles and legend.
        let contexts = [FigureWidth::Double, FigureWidth::Single].map(|w| {
            let layout = paper::paper_layout(d.size(), (1, 1), w);
            let ctx = PlotContext::new(Format::Paper(w), layout.size);
            let (pw, ph) = ctx.pixels();
            (ctx, (pw - 60, ph - 330))
        });
        for (ctx, area) in contexts {
            for l in d.angle_labels(&ctx, area) {
                for s in &d.supports {
                    assert!(
                        !boxes_meet(l.data_box, s.hatching_box()),
                        "{study} {stem}: {} at {:?} on the hatching {:?}",
                        l.text,
                        l.data_box,
                        s.hatching_box()
                    );
                }
                assert!(
                    !box_meets_polygon(l.data_box, &d.outline),
                    "{study} {stem}: {} at {:?} on the masonry",
                    l.text,
                    l.data_box
                );
                if l.text == "90.0°" || l.text == "-90.0°" {
                    at_springing += 1;
                    // Beside the arch, not under the ground line.
                    assert!(
                        l.data_box[3] > 0.0,
                        "{study} {stem}: {l:?} under the ground"
                    );
                }
            }
        }
    }
    at_springing
}

#[test]
fn springing_labels_clear_the_supports_and_the_masonry() {
    // The studies whose states have hinges or sliding joints at a springing: the label sat
    // on the hatching there.
    let mut springing = 0;
    for study in ["influence-line", "vertical-joints", "seed", "pointed"] {
        springing += assert_labels_clear(study);
    }
    assert!(springing >= 4, "{springing} springing labels checked");
}

/// The mechanisms of an arch with vertical joints are drawn on its own arch: each stands on
/// its radial springings (the horizontal beds from (±1, 0) to (±K, 0) of the semicircle, not
/// the vertical sections through the intrados springings), and its parts together cover the
/// arch, the wedges between those sections and the springings included: their areas add up
/// to π(K² − 1)/2 (the extrados and intrados drawn by chords of at most 1°, so to 1e-4).
#[test]
fn vertical_joint_mechanisms_stand_on_their_radial_springings_and_cover_the_arch() {
    use archstudy::analysis::kinematics::MechanismDrawing;
    let run = run_example("vertical-joints-horizontal");
    let data = data::load(&RunLayout::at(&run)).expect("the run reads back");
    assert!(!data.mechanisms.is_empty(), "no mechanisms stored");
    let area = |poly: &[[f64; 2]]| -> f64 {
        let n = poly.len();
        0.5 * (0..n)
            .map(|i| {
                let (p, q) = (poly[i], poly[(i + 1) % n]);
                p[0] * q[1] - q[0] * p[1]
            })
            .sum::<f64>()
            .abs()
    };
    for m in &data.mechanisms {
        let d: MechanismDrawing = serde_json::from_str(&m.drawing_json).expect("a drawing");
        for (s, side) in d.supports.iter().zip([-1.0, 1.0]) {
            for (p, x) in [(s.intrados, side), (s.extrados, side * m.k)] {
                assert!(
                    (p[0] - x).abs() < 1e-12 && p[1].abs() < 1e-12,
                    "{p:?} at K {}",
                    m.k
                );
            }
        }
        let covered: f64 = d.outlines.iter().map(|o| area(&o.original)).sum();
        let exact = 0.5 * std::f64::consts::PI * (m.k * m.k - 1.0);
        assert!(
            (covered - exact).abs() < 1e-4 * exact,
            "{}: parts cover {covered}, the arch {exact}",
            m.state_id
        );
    }
    // Their figures are drawn.
    let stems: Vec<String> = charts::build(&data).into_iter().map(|f| f.stem).collect();
    assert!(
        stems.iter().any(|s| s.starts_with("mechanisms-")),
        "{stems:?}"
    );
}
