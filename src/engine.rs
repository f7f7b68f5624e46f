//! The engine: every case of a plan analysed in parallel (rayon), in plan order, with its own
//! solve time and a progress bar. A case that fails becomes a row with a status and a
//! message; it never aborts the study.
//!
//! A symmetric self-weight `state` grid uses the separable structure of the problem
//! (DESIGN.md §2): H^r depends on K only and H^s/W_half on μ only, so the grid costs one
//! rotational domain per distinct K and one sliding domain per distinct μ, plus a comparison
//! per point. The solve time of such a case is its share of both domain solves plus its
//! comparison.

use crate::analysis::circular::SymmetricCircular;
use crate::analysis::symmetric::{self, RotationalDomain, SlidingDomain};
use crate::model::Discretisation;
use crate::plan::{Case, Plan};
use crate::scene::{self, Find, Solution};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;
use std::collections::HashMap;
use std::io::IsTerminal;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::time::Instant;

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

/// How to show progress.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Progress {
    /// A bar on stderr when stderr is a terminal.
    Auto,
    /// Nothing.
    Hidden,
}

fn progress_bar(len: u64, mode: Progress) -> ProgressBar {
    if mode == Progress::Hidden || !std::io::stderr().is_terminal() {
        return ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::hidden());
    }
    let bar = ProgressBar::new(len);
    if let Ok(style) = ProgressStyle::with_template(
        "{spinner} analysing [{bar:40}] {pos}/{len} cases ({per_sec}, {eta} left)",
    ) {
        bar.set_style(style.progress_chars("=> "));
    }
    bar
}

fn panic_message(p: Box<dyn std::any::Any + Send>) -> String {
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
pub fn run(plan: &Plan, progress: Progress) -> Vec<CaseResult> {
    let bar = progress_bar(plan.cases.len() as u64, progress);
    let out = if plan.is_separable_state_grid() {
        run_separable(plan, &bar)
    } else {
        plan.cases
            .par_iter()
            .map(|c| {
                let r = checked(c, || scene::solve(&c.scene));
                bar.inc(1);
                r
            })
            .collect()
    };
    bar.finish_and_clear();
    out
}

/// Key of the geometry shared by the cases whose domains can be reused.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
struct GeomKey {
    half_angle_bits: u64,
    joints: Discretisation,
    k_bits: u64,
}

fn run_separable(plan: &Plan, bar: &ProgressBar) -> Vec<CaseResult> {
    // Distinct rotational problems (geometry and K) and sliding problems (geometry and μ).
    let mut rot_keys: Vec<GeomKey> = Vec::new();
    let mut rot_index: HashMap<GeomKey, usize> = HashMap::new();
    let mut sld_keys: Vec<(GeomKey, u64)> = Vec::new();
    let mut sld_index: HashMap<(GeomKey, u64), usize> = HashMap::new();
    let mut case_keys = Vec::with_capacity(plan.cases.len());
    for c in &plan.cases {
        let a = &c.scene.arch;
        let rk = GeomKey {
            half_angle_bits: a.half_angle.to_bits(),
            joints: a.joints,
            k_bits: a.k.to_bits(),
        };
        let sk = (GeomKey { k_bits: 0, ..rk }, c.scene.friction.mu().to_bits());
        let ri = *rot_index.entry(rk).or_insert_with(|| {
            rot_keys.push(rk);
            rot_keys.len() - 1
        });
        let si = *sld_index.entry(sk).or_insert_with(|| {
            sld_keys.push(sk);
            sld_keys.len() - 1
        });
        case_keys.push((ri, si));
    }
    let weight = plan.manifest.arch.weight;
    let sample = plan.cases.first().map(|c| c.scene.arch);
    let arch_for = |g: &GeomKey, k: f64| crate::model::Arch {
        k,
        half_angle: f64::from_bits(g.half_angle_bits),
        weight,
        joints: g.joints,
    };
    // Each domain solve is timed; a panic there marks the cases that use it as failed.
    let rot: Vec<Result<(RotationalDomain, f64), String>> = rot_keys
        .par_iter()
        .map(|g| {
            let t = Instant::now();
            catch_unwind(AssertUnwindSafe(|| {
                symmetric::rotational_domain(&SymmetricCircular::new(&arch_for(
                    g,
                    f64::from_bits(g.k_bits),
                )))
            }))
            .map(|d| (d, t.elapsed().as_secs_f64() * 1e6))
            .map_err(panic_message)
        })
        .collect();
    let sld: Vec<Result<(SlidingDomain, f64), String>> = sld_keys
        .par_iter()
        .map(|(g, mu_bits)| {
            let t = Instant::now();
            // H^s does not depend on K; any K > 1 gives the same joints and weights.
            let arch = arch_for(g, sample.map_or(2.0, |a| a.k.max(1.0 + 1e-9)));
            let phi = crate::model::Friction::new(f64::from_bits(*mu_bits))
                .unwrap_or(crate::model::Friction::INFINITE)
                .angle();
            catch_unwind(AssertUnwindSafe(|| {
                symmetric::sliding_domain(&SymmetricCircular::new(&arch), phi)
            }))
            .map(|d| (d, t.elapsed().as_secs_f64() * 1e6))
            .map_err(panic_message)
        })
        .collect();
    // How many cases share each domain, to split its cost.
    let mut rot_uses = vec![0usize; rot.len()];
    let mut sld_uses = vec![0usize; sld.len()];
    for &(r, s) in &case_keys {
        rot_uses[r] += 1;
        sld_uses[s] += 1;
    }
    let results: Vec<CaseResult> = plan
        .cases
        .par_iter()
        .zip(case_keys.par_iter())
        .map(|(c, &(ri, si))| {
            let r = match (&rot[ri], &sld[si]) {
                (Ok((rd, rt)), Ok((sd, st))) => {
                    let start = Instant::now();
                    let mut res = checked(c, || scene::state_from_domains(&c.scene, rd, sd));
                    let own = start.elapsed().as_secs_f64() * 1e6;
                    res.solution.solve_time_us =
                        own + rt / rot_uses[ri] as f64 + st / sld_uses[si] as f64;
                    res
                }
                (Err(m), _) | (_, Err(m)) => CaseResult {
                    case_id: c.id,
                    load_case: c.load_case,
                    solution: scene::solve_inputs_only(&c.scene),
                    status: Status::Error,
                    message: Some(m.clone()),
                },
            };
            bar.inc(1);
            r
        })
        .collect();
    debug_assert!(
        results
            .iter()
            .all(|r| r.solution.find == Find::State.as_str())
    );
    results
}
