//! Charts and sections of the report that depend on what a study varies: a load_factor study
//! over K and μ gets λ as a colour map with its mechanism regions, and a report leaves out a
//! section with nothing in it.

use crate::common::{run_study, scratch};
use archstudy::output::RunLayout;
use archstudy::store;

/// A horizontal body force over K and μ (with μ = ∞): the collapse mechanism changes over
/// the grid, so its bifurcations outline mechanism regions; boundaries.parquet stays empty
/// (regime boundaries belong to state studies).
pub const HORIZONTAL_MAP: &str = "\
name: horizontal
grid:
  k: {from: 1.1, to: 1.6, steps: 11}
  mu: {values: [0.3, 0.35, 0.4, 0.5, 0.6, 0.8, 1.0, inf]}
load_cases:
  - {name: horizontal, kind: horizontal}
find: load_factor
";

/// A small state study over K and μ: boundaries are located.
const STATE_MAP: &str = "\
name: state
grid:
  k: {from: 1.05, to: 1.4, steps: 8}
  mu: {from: 0.2, to: 0.8, steps: 7}
load_cases:
  - {name: gravity, kind: self_weight}
find: state
";

#[test]
fn boundaries_section_only_where_boundaries_were_located() {
    let lf = run_study(&scratch("sections-lf"), "horizontal.yaml", HORIZONTAL_MAP);
    let layout = RunLayout::at(&lf);
    let rows = store::read_boundaries(&layout.boundaries()).expect("boundaries.parquet");
    assert!(rows.is_empty(), "{} boundary rows", rows.len());
    let md = std::fs::read_to_string(layout.report_md()).expect("report.md");
    let html = std::fs::read_to_string(layout.report_html()).expect("report.html");
    assert!(!md.contains("## Boundaries"), "empty section in report.md");
    assert!(
        !html.contains("id=\"boundaries\""),
        "empty section in report.html"
    );
    assert!(
        !html.contains("href=\"#boundaries\""),
        "contents link to no section"
    );

    let st = run_study(&scratch("sections-state"), "state.yaml", STATE_MAP);
    let layout = RunLayout::at(&st);
    let rows = store::read_boundaries(&layout.boundaries()).expect("boundaries.parquet");
    assert!(rows.len() >= 8, "{} boundary rows", rows.len());
    let md = std::fs::read_to_string(layout.report_md()).expect("report.md");
    let section = md
        .split("## Boundaries")
        .nth(1)
        .expect("a Boundaries section where boundaries were located");
    // Every located point is counted once in the section's table of groups.
    let counted: usize = section
        .split("\n\n")
        .nth(2)
        .expect("the groups table")
        .lines()
        .skip(2)
        .filter_map(|l| l.split('|').nth(5)?.trim().parse::<usize>().ok())
        .sum();
    assert_eq!(counted, rows.len(), "{section}");
}
