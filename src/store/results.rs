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
pub(crate) fn hinge_faces(h: &[HingeRecord]) -> Vec<String> {
    h.iter().map(|h| h.face.to_string()).collect()
}
pub(crate) fn sliding_angles(s: &[SlidingRecord]) -> Vec<f64> {
    s.iter().map(|s| s.angle_deg).collect()
}
pub(crate) fn sliding_senses(s: &[SlidingRecord]) -> Vec<String> {
    s.iter().map(|s| s.sense.to_string()).collect()
}

/// The results table: one row per case (schema in the README).
pub fn results_frame(plan: &Plan, rows: &[CaseResult]) -> Result<DataFrame> {
    let col = |f: &dyn Fn(&CaseResult) -> Option<f64>| rows.iter().map(f).collect::<Vec<_>>();
    let scol = |f: &dyn Fn(&CaseResult) -> Option<String>| rows.iter().map(f).collect::<Vec<_>>();
    let m = &plan.manifest;
    TableBuilder::new()
        .u64("case_id", rows.iter().map(|r| r.case_id).collect())
        .str(
            "load_case",
            rows.iter()
                .map(|r| m.load_cases[r.load_case].name.clone())
                .collect(),
        )
        .str(
            "load_kind",
            rows.iter()
                .map(|r| m.load_cases[r.load_case].kind.as_str().to_string())
                .collect(),
        )
        .str(
            "find",
            rows.iter().map(|r| r.solution.find.to_string()).collect(),
        )
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
        .str(
            "weight",
            rows.iter().map(|r| r.solution.weight.to_string()).collect(),
        )
        .opt_u32(
            "voussoirs",
            rows.iter().map(|r| r.solution.voussoirs).collect(),
        )
        // Form and load case (docs/loads-and-geometries.md).
        .str(
            "shape",
            rows.iter().map(|r| r.solution.shape.to_string()).collect(),
        )
        .opt_f64("eccentricity", col(&|r| r.solution.eccentricity))
        .str(
            "joints",
            rows.iter().map(|r| r.solution.joints.to_string()).collect(),
        )
        .str(
            "load",
            rows.iter().map(|r| r.solution.load.to_string()).collect(),
        )
        .opt_f64("at_deg", col(&|r| r.solution.at_deg))
        .opt_f64("lambda", col(&|r| r.solution.lambda))
        .opt_str("outcome", scol(&|r| r.solution.outcome.map(str::to_string)))
        .opt_str("regime", scol(&|r| r.solution.regime.map(str::to_string)))
        .opt_f64("thrust_r_min", col(&|r| r.solution.thrust_r_min))
        .opt_f64("thrust_r_max", col(&|r| r.solution.thrust_r_max))
        .opt_f64("thrust_s_min", col(&|r| r.solution.thrust_s_min))
        .opt_f64("thrust_s_max", col(&|r| r.solution.thrust_s_max))
        .opt_f64("k_crit", col(&|r| r.solution.k_crit))
        .opt_f64("t_over_r_crit", col(&|r| r.solution.t_over_r_crit))
        .opt_f64("mu_crit", col(&|r| r.solution.mu_crit))
        .opt_str(
            "mechanism",
            scol(&|r| r.solution.mechanism.map(str::to_string)),
        )
        .opt_f64(
            "thrust_over_half_weight",
            col(&|r| r.solution.thrust_over_half_weight),
        )
        .opt_f64("crown_moment", col(&|r| r.solution.crown_moment))
        .opt_f64("crown_shear", col(&|r| r.solution.crown_shear))
        .opt_f64("load_factor", col(&|r| r.solution.load_factor))
        .bool(
            "load_factor_unbounded",
            rows.iter()
                .map(|r| r.solution.load_factor_unbounded)
                .collect(),
        )
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
        .str(
            "status",
            rows.iter().map(|r| r.status.as_str().to_string()).collect(),
        )
        .opt_str("message", rows.iter().map(|r| r.message.clone()).collect())
        .f64(
            "solve_time_us",
            rows.iter().map(|r| r.solution.solve_time_us).collect(),
        )
        .finish()
}
