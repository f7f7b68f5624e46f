//! results.parquet: one row per case (schema in the README).

use super::TableBuilder;
use crate::engine::CaseResult;
use crate::plan::Plan;
use crate::scene::{HingeRecord, SlidingRecord};
use anyhow::Result;
use polars::prelude::DataFrame;

pub(crate) fn hinge_angles(h: &[HingeRecord]) -> Vec<f64> {
    h.iter().map(|h| h.angle_deg).collect()
}
pub(crate) fn hinge_faces(h: &[HingeRecord]) -> Vec<&'static str> {
    h.iter().map(|h| h.face).collect()
}
pub(crate) fn sliding_angles(s: &[SlidingRecord]) -> Vec<f64> {
    s.iter().map(|s| s.angle_deg).collect()
}
pub(crate) fn sliding_senses(s: &[SlidingRecord]) -> Vec<&'static str> {
    s.iter().map(|s| s.sense).collect()
}

/// The results table: one row per case (schema in the README).
pub fn results_frame(plan: &Plan, rows: &[CaseResult]) -> Result<DataFrame> {
    let col = |f: &dyn Fn(&CaseResult) -> Option<f64>| rows.iter().map(f).collect::<Vec<_>>();
    let scol =
        |f: &dyn Fn(&CaseResult) -> Option<&'static str>| rows.iter().map(f).collect::<Vec<_>>();
    let m = &plan.manifest;
    TableBuilder::new()
        .u64("case_id", rows.iter().map(|r| r.case_id).collect())
        .str(
            "load_case",
            rows.iter()
                .map(|r| m.load_cases[r.load_case].name.as_str())
                .collect(),
        )
        .str(
            "load_kind",
            rows.iter()
                .map(|r| m.load_cases[r.load_case].kind.as_str())
                .collect(),
        )
        .str("find", rows.iter().map(|r| r.solution.find).collect())
        .opt_f64("k", col(&|r| r.solution.k))
        .opt_f64("t_over_r", col(&|r| r.solution.t_over_r))
        .opt_f64(
            "mu",
            col(&|r| {
                if r.solution.mu_infinite {
                    Some(f64::INFINITY)
                } else {
                    r.solution.mu
                }
            }),
        )
        .f64(
            "half_angle_deg",
            rows.iter().map(|r| r.solution.half_angle_deg).collect(),
        )
        .str("weight", rows.iter().map(|r| r.solution.weight).collect())
        .opt_u32(
            "voussoirs",
            rows.iter().map(|r| r.solution.voussoirs).collect(),
        )
        .opt_str("outcome", scol(&|r| r.solution.outcome))
        .opt_str("regime", scol(&|r| r.solution.regime))
        .opt_f64("thrust_r_min", col(&|r| r.solution.thrust_r_min))
        .opt_f64("thrust_r_max", col(&|r| r.solution.thrust_r_max))
        .opt_f64("thrust_s_min", col(&|r| r.solution.thrust_s_min))
        .opt_f64("thrust_s_max", col(&|r| r.solution.thrust_s_max))
        .opt_f64("k_crit", col(&|r| r.solution.k_crit))
        .opt_f64("t_over_r_crit", col(&|r| r.solution.t_over_r_crit))
        .opt_f64("mu_crit", col(&|r| r.solution.mu_crit))
        .opt_str("mechanism", scol(&|r| r.solution.mechanism))
        .opt_f64(
            "thrust_over_half_weight",
            col(&|r| r.solution.thrust_over_half_weight),
        )
        .opt_f64("crown_moment", col(&|r| r.solution.crown_moment))
        .list_f64(
            "hinge_angles_deg",
            rows.iter()
                .map(|r| hinge_angles(&r.solution.hinges))
                .collect(),
        )
        .list_str(
            "hinge_faces",
            rows.iter()
                .map(|r| hinge_faces(&r.solution.hinges))
                .collect(),
        )
        .list_f64(
            "sliding_angles_deg",
            rows.iter()
                .map(|r| sliding_angles(&r.solution.sliding_joints))
                .collect(),
        )
        .list_str(
            "sliding_senses",
            rows.iter()
                .map(|r| sliding_senses(&r.solution.sliding_joints))
                .collect(),
        )
        .opt_f64("work_loads", col(&|r| r.solution.work_loads))
        .opt_f64("work_friction", col(&|r| r.solution.work_friction))
        .opt_f64("work_residual", col(&|r| r.solution.work_residual))
        .opt_u32(
            "mechanism_dof",
            rows.iter().map(|r| r.solution.mechanism_dof).collect(),
        )
        .opt_f64("k_c_rotational", col(&|r| r.solution.k_c_rotational))
        .opt_f64(
            "mu_rotational_mixed",
            col(&|r| r.solution.mu_rotational_mixed),
        )
        .opt_f64("mu_min", col(&|r| r.solution.mu_min))
        .opt_f64("k_mixed_sliding", col(&|r| r.solution.k_mixed_sliding))
        .opt_f64("thrust_min", col(&|r| r.solution.thrust_min))
        .opt_f64("thrust_max", col(&|r| r.solution.thrust_max))
        .list_f64(
            "hinges_min_angles_deg",
            rows.iter()
                .map(|r| hinge_angles(&r.solution.hinges_min))
                .collect(),
        )
        .list_str(
            "hinges_min_faces",
            rows.iter()
                .map(|r| hinge_faces(&r.solution.hinges_min))
                .collect(),
        )
        .list_f64(
            "hinges_max_angles_deg",
            rows.iter()
                .map(|r| hinge_angles(&r.solution.hinges_max))
                .collect(),
        )
        .list_str(
            "hinges_max_faces",
            rows.iter()
                .map(|r| hinge_faces(&r.solution.hinges_max))
                .collect(),
        )
        .str("status", rows.iter().map(|r| r.status.as_str()).collect())
        .opt_str(
            "message",
            rows.iter().map(|r| r.message.as_deref()).collect(),
        )
        .f64(
            "solve_time_us",
            rows.iter().map(|r| r.solution.solve_time_us).collect(),
        )
        .finish()
}
