//! The engine: every case of a plan analysed in parallel (rayon), in plan order, with its own
//! solve time and a progress bar. A case that fails becomes a row with a status and a
//! message; it never aborts the study.
//!
//! A symmetric self-weight `state` grid uses the separable structure of the problem
//! (docs/mechanics.md §2): H^r depends on K only and H^s/W_half on μ only, so the grid costs one
//! rotational domain per distinct K and one sliding domain per distinct μ, plus a comparison
//! per point. Its rows are compact ([`StateCase`]: the inputs, the regime and both domains'
//! ends), written in place block by block. The solve time of such a case is its share of both
//! domain solves plus its share of its block's comparisons.
//!
//! A symmetric self-weight `state` grid on any other form (pointed arches, vertical joints)
//! is analysed per K line: at fixed K the regime along μ is monotone (H^r does not involve μ,
//! H^s and the stable set grow with it), so each line costs the margins of a bisection for
//! its sliding threshold and its critical friction among the line's own μ values
//! ([`symmetric::line_regimes`]), each the general route's own margin at a grid point.

use crate::analysis::forms::ArchModel;
use crate::analysis::settings::GeneralSettings;
use crate::analysis::symmetric;
use crate::model::{Discretisation, JointOrientation};
use crate::plan::{Case, Plan};
use crate::progress::{Progress, Stage};
use crate::scene::{self, Find, Scene, Solution};
use rayon::prelude::*;
use rustc_hash::FxHashMap;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::time::Instant;

mod separable;
mod states;
use separable::{SeparableDomains, run_separable};
pub use states::{Rows, StateCase};

/// Whether a case produced an answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    /// The analysis ran (its outcome may still be "never stands").
    Ok,
    /// The analysis failed; the message says why.
    Error,
}

impl Status {
    /// `ok` or `error`.
    pub fn as_str(self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::Error => "error",
        }
    }
}

/// How the engine goes through a plan.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GridPath {
    /// Symmetric self-weight `state` grid of a circular arch with radial joints: one
    /// rotational domain per K, one sliding domain per μ, a comparison per case.
    Separable,
    /// Symmetric self-weight `state` grid of any other form: per K line, a bisection for the
    /// sliding threshold and the critical friction among the line's own μ values.
    KLines,
    /// Every case analysed on its own.
    CaseByCase,
}

impl GridPath {
    /// The path the engine takes for a plan.
    pub fn of(plan: &Plan) -> Self {
        // A sampling study's scenes share no K line; only the state of the circular arch
        // under self-weight keeps the separable structure (each K and each μ once).
        if let Some(s) = &plan.manifest.sampling {
            return if s.question == crate::manifest::Question::Probability
                && plan.is_separable_state_grid()
            {
                GridPath::Separable
            } else {
                GridPath::CaseByCase
            };
        }
        if plan.is_separable_state_grid() {
            GridPath::Separable
        } else if is_symmetric_state_grid(plan) {
            GridPath::KLines
        } else {
            GridPath::CaseByCase
        }
    }

    /// `separable`, `k_lines` or `case_by_case` (run.json's `grid_path`).
    pub fn as_str(self) -> &'static str {
        match self {
            GridPath::Separable => "separable",
            GridPath::KLines => "k_lines",
            GridPath::CaseByCase => "case_by_case",
        }
    }
}

/// The result of one case.
#[derive(Debug, Clone)]
pub struct CaseResult {
    /// The case id.
    pub case_id: u64,
    /// Index of the load case in the manifest.
    pub load_case: usize,
    /// The answer (inputs echoed, outputs null on error).
    pub solution: Solution,
    /// Ok or error.
    pub status: Status,
    /// Why it failed, when it did.
    pub message: Option<String>,
}

/// The message a panic carried, when it carried one.
pub(crate) fn panic_message(p: Box<dyn std::any::Any + Send>) -> String {
    if let Some(s) = p.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = p.downcast_ref::<String>() {
        s.clone()
    } else {
        "the analysis panicked".to_string()
    }
}

fn checked(case: &Case, run: impl FnOnce() -> Solution) -> CaseResult {
    match catch_unwind(AssertUnwindSafe(run)) {
        Ok(solution) => CaseResult {
            case_id: case.id,
            load_case: case.load_case,
            solution,
            status: Status::Ok,
            message: None,
        },
        Err(p) => CaseResult {
            case_id: case.id,
            load_case: case.load_case,
            solution: scene::solve_inputs_only(&case.scene),
            status: Status::Error,
            message: Some(panic_message(p)),
        },
    }
}

/// Analyses every case of a plan; results are in plan order whatever the thread count.
/// Progress is reported as the [`Stage::Analyse`] stage, counted in cases.
pub fn run(plan: &Plan, progress: &dyn Progress) -> Vec<CaseResult> {
    progress.begin(Stage::Analyse, Some(plan.cases.len() as u64));
    let out = analyse(plan, progress);
    progress.end(Stage::Analyse);
    out
}

/// Analyses every case of a plan, in plan order, advancing the current stage as cases are
/// done (by blocks of cases on the separable path); the caller begins and ends the stage (a
/// shard spans one stage over its chunks).
pub fn analyse(plan: &Plan, progress: &dyn Progress) -> Vec<CaseResult> {
    let mut rows = Rows::default();
    analyse_rows(plan, progress, &mut rows);
    rows.into_results()
}

/// Analyses every case of a plan into `out`, whose rows are replaced: compact rows on the
/// separable `state` path, full rows otherwise. A run analysing chunk after chunk keeps one
/// `out`, so that each chunk's rows are written into memory already in use rather than into
/// fresh pages the kernel must clear.
pub fn analyse_rows(plan: &Plan, progress: &dyn Progress, out: &mut Rows) {
    match GridPath::of(plan) {
        GridPath::Separable => {
            let mut rows = out.take_states();
            run_separable(&plan.cases, plan.manifest.arch.weight, progress, &mut rows);
            *out = Rows::States(rows);
        }
        path => {
            let mut rows = out.take_cases();
            if path == GridPath::KLines {
                run_lines(plan, progress, &mut rows);
            } else {
                // A sample asks whether the arch stands, or for its static limit: the search
                // for the first complete solution beyond it (the gap) is not made.
                let solve = if plan.manifest.sampling.is_some() {
                    scene::solve_static
                } else {
                    scene::solve
                };
                rows.par_extend(plan.cases.par_iter().map(|c| case_row(c, progress, solve)));
            }
            *out = Rows::Cases(rows);
        }
    }
}

/// One case solved on its own (skipped once `progress` asked to stop).
fn case_row(c: &Case, progress: &dyn Progress, solve: fn(&Scene) -> Solution) -> CaseResult {
    if progress.stopped() {
        return skipped(c);
    }
    let r = checked(c, || solve(&c.scene));
    progress.advance(1);
    r
}

/// The row of a case skipped because the caller asked to stop.
fn skipped(c: &Case) -> CaseResult {
    CaseResult {
        case_id: c.id,
        load_case: c.load_case,
        solution: scene::solve_inputs_only(&c.scene),
        status: Status::Error,
        message: Some(crate::progress::Stopped.to_string()),
    }
}

/// Rows per block of [`solve_scenes_in_blocks`]: few enough that a block's rows (about a
/// kilobyte each) are still in cache when the caller turns them into a table, enough that
/// handing a block over costs nothing next to solving it.
pub const SCENE_BLOCK_ROWS: usize = 1 << 14;

/// Analyses scenes that belong to no study (one row each, ids 0, 1, ... in their order, load
/// case 0): self-weight `state` scenes of circular arches with radial joints and one weight
/// model by the separable path, any other batch scene by scene, in parallel on the current
/// rayon pool. [`Stopped`](crate::progress::Stopped) when `progress` asked to stop.
pub fn solve_scenes(
    scenes: &[scene::Scene],
    progress: &dyn Progress,
) -> Result<Vec<CaseResult>, crate::progress::Stopped> {
    let blocks = solve_scenes_in_blocks(scenes, progress, |rows| rows)?;
    Ok(blocks.into_iter().flatten().collect())
}

/// [`solve_scenes`] in blocks of [`SCENE_BLOCK_ROWS`] consecutive scenes, each block's rows
/// handed to `each` as soon as they are solved and dropped after it (a million rows would
/// take a gigabyte): `each`'s outputs in scene order. Blocks and the scenes within a block
/// run in parallel; the domains of a separable batch are solved once for all blocks.
pub fn solve_scenes_in_blocks<T: Send>(
    scenes: &[scene::Scene],
    progress: &dyn Progress,
    each: impl Fn(Vec<CaseResult>) -> T + Sync,
) -> Result<Vec<T>, crate::progress::Stopped> {
    let case = |i: usize, s: &Scene| Case {
        id: i as u64,
        load_case: 0,
        scene: *s,
    };
    let weight = scenes.first().map(|s| s.arch.weight);
    let separable = scenes
        .iter()
        .all(|s| s.find == Find::State && s.uses_closed_forms() && Some(s.arch.weight) == weight);
    progress.begin(Stage::Analyse, Some(scenes.len() as u64));
    let domains = match weight {
        Some(w) if separable => Some(SeparableDomains::solve(scenes.iter(), w)),
        _ => None,
    };
    let out = scenes
        .par_chunks(SCENE_BLOCK_ROWS)
        .enumerate()
        .map(|(b, block)| {
            let first = b * SCENE_BLOCK_ROWS;
            let rows = match &domains {
                Some(d) => {
                    let cases: Vec<Case> = (block.iter().enumerate())
                        .map(|(j, s)| case(first + j, s))
                        .collect();
                    let mut rows = Vec::new();
                    d.write_states(&cases, first, progress, &mut rows);
                    rows.into_par_iter().map(StateCase::into_result).collect()
                }
                None => (block.par_iter().enumerate())
                    .map(|(j, s)| case_row(&case(first + j, s), progress, scene::solve))
                    .collect(),
            };
            each(rows)
        })
        .collect();
    progress.end(Stage::Analyse);
    if progress.stopped() {
        return Err(crate::progress::Stopped);
    }
    Ok(out)
}

/// True when every case is a symmetric self-weight `state` query on a form other than the
/// circular arch with radial joints: the grid goes per K line ([`symmetric::line_regimes`]).
pub fn is_symmetric_state_grid(plan: &Plan) -> bool {
    !plan.is_separable_state_grid()
        && plan
            .manifest
            .load_cases
            .iter()
            .all(|l| l.find == Find::State && !l.kind.is_live())
}

/// The cases of one K line (one arch, every μ), in plan order.
fn k_lines(plan: &Plan) -> Vec<Vec<usize>> {
    type LineKey = (
        u64,
        Discretisation,
        u64,
        (bool, u64, JointOrientation, bool),
    );
    let mut index: FxHashMap<LineKey, usize> = FxHashMap::default();
    let mut lines: Vec<Vec<usize>> = Vec::new();
    for (n, c) in plan.cases.iter().enumerate() {
        let a = &c.scene.arch;
        let key = (
            a.half_angle.to_bits(),
            a.joints,
            a.k.to_bits(),
            c.scene.form.key(),
        );
        let l = *index.entry(key).or_insert_with(|| {
            lines.push(Vec::new());
            lines.len() - 1
        });
        lines[l].push(n);
    }
    lines
}

/// Consecutive K lines analysed in turn by one task, each starting its threshold search from
/// the previous line's thresholds (a cost, not a result: any grouping gives the same answers).
const LINES_PER_TASK: usize = 16;

/// The results of one K line: its regimes from the line's thresholds, or every case through
/// the general route when a margin fails or the form does not exist at this K. The line's
/// solve time is shared equally by its cases. `near` holds the thresholds of the previous
/// line of the task and receives this line's.
fn line_results(
    plan: &Plan,
    line: &[usize],
    near: &mut Option<symmetric::LineRegimes>,
) -> Vec<CaseResult> {
    let cases: Vec<&Case> = line.iter().map(|&n| &plan.cases[n]).collect();
    let one_by_one = || -> Vec<CaseResult> {
        cases
            .iter()
            .map(|c| checked(c, || scene::solve(&c.scene)))
            .collect()
    };
    let Some(first) = cases.first() else {
        return Vec::new();
    };
    let start = Instant::now();
    let sc = &first.scene;
    let Ok(model) = ArchModel::new(sc.arch, sc.form, sc.load) else {
        return one_by_one();
    };
    let mut phis: Vec<f64> = cases.iter().map(|c| c.scene.friction.angle()).collect();
    phis.sort_by(f64::total_cmp);
    phis.dedup();
    let settings = GeneralSettings {
        lambda: sc.lambda,
        ..GeneralSettings::default()
    };
    let found = catch_unwind(AssertUnwindSafe(|| {
        symmetric::line_regimes(&model, &phis, &settings, near.as_ref())
    }));
    let Ok(Some(regimes)) = found else {
        return one_by_one();
    };
    *near = Some(regimes);
    let share = start.elapsed().as_secs_f64() * 1e6 / cases.len() as f64;
    cases
        .iter()
        .map(|c| {
            let phi = c.scene.friction.angle();
            let i = phis.partition_point(|p| p.total_cmp(&phi).is_lt());
            let mut solution = Solution::empty(&c.scene);
            solution.regime = Some(regimes.regime(i));
            solution.solve_time_us = share;
            CaseResult {
                case_id: c.id,
                load_case: c.load_case,
                solution,
                status: Status::Ok,
                message: None,
            }
        })
        .collect()
}

/// A symmetric self-weight `state` grid on any form, per K line in parallel; results
/// appended to `out` in plan order.
fn run_lines(plan: &Plan, progress: &dyn Progress, out: &mut Vec<CaseResult>) {
    let lines = k_lines(plan);
    let per_line: Vec<(Vec<usize>, Vec<CaseResult>)> = lines
        .par_chunks(LINES_PER_TASK)
        .flat_map_iter(|task| {
            let mut near = None;
            task.iter()
                .map(|line| {
                    let r = line_results(plan, line, &mut near);
                    progress.advance(line.len() as u64);
                    (line.clone(), r)
                })
                .collect::<Vec<_>>()
        })
        .collect();
    let mut slots: Vec<Option<CaseResult>> = vec![None; plan.cases.len()];
    for (line, results) in per_line {
        for (n, r) in line.into_iter().zip(results) {
            slots[n] = Some(r);
        }
    }
    out.extend(
        slots
            .into_iter()
            .zip(&plan.cases)
            .map(|(r, c)| r.unwrap_or_else(|| checked(c, || scene::solve(&c.scene)))),
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::manifest::SceneOptions;
    use crate::progress::{Silent, StopNow, Stopped};

    fn state(k: f64, mu: f64) -> scene::Scene {
        SceneOptions {
            k: Some(k),
            mu,
            ..SceneOptions::default()
        }
        .scene()
        .unwrap()
    }

    /// Progress that asks to stop from the start.
    #[test]
    fn a_batch_of_state_scenes_answers_as_each_scene_alone() {
        let scenes = [state(1.1, 0.3), state(1.2, 0.5), state(1.35, f64::INFINITY)];
        let rows = solve_scenes(&scenes, &Silent).unwrap();
        for (i, (r, s)) in rows.iter().zip(&scenes).enumerate() {
            let one = scene::solve(s);
            assert_eq!(r.case_id, i as u64);
            assert_eq!(r.status, Status::Ok);
            assert_eq!(r.solution.regime, one.regime, "scene {i}");
            assert_eq!(r.solution.thrust_r_min, one.thrust_r_min, "scene {i}");
            assert_eq!(r.solution.thrust_s_max, one.thrust_s_max, "scene {i}");
        }
    }

    #[test]
    fn blocks_of_a_batch_come_in_scene_order_and_match_the_whole_batch() {
        let n = 2 * SCENE_BLOCK_ROWS + 3;
        let scenes: Vec<Scene> = (0..n)
            .map(|i| {
                state(
                    1.05 + 0.4 * (i % 97) as f64 / 96.0,
                    0.2 + (i % 89) as f64 / 100.0,
                )
            })
            .collect();
        let blocks = solve_scenes_in_blocks(&scenes, &Silent, |rows| {
            let ids: Vec<u64> = rows.iter().map(|r| r.case_id).collect();
            let regimes: Vec<_> = rows.iter().map(|r| r.solution.regime).collect();
            (ids, regimes)
        })
        .unwrap();
        assert_eq!(
            blocks.iter().map(|b| b.0.len()).collect::<Vec<_>>(),
            [SCENE_BLOCK_ROWS, SCENE_BLOCK_ROWS, 3]
        );
        let ids: Vec<u64> = blocks.iter().flat_map(|b| b.0.clone()).collect();
        assert_eq!(ids, (0..n as u64).collect::<Vec<_>>());
        for i in (0..n).step_by(1009) {
            let one = scene::solve(&scenes[i]);
            let b = &blocks[i / SCENE_BLOCK_ROWS];
            assert_eq!(b.1[i % SCENE_BLOCK_ROWS], one.regime, "scene {i}");
        }
    }

    #[test]
    fn a_batch_asked_to_stop_returns_stopped() {
        let scenes = [state(1.2, 0.5), state(1.3, 0.6)];
        assert_eq!(solve_scenes(&scenes, &StopNow).unwrap_err(), Stopped);
    }
}
