//! boundaries.parquet and bifurcations.parquet: the located regime boundaries and
//! bifurcation points of a run (schema in docs/boundaries-schema.md).

use super::TableBuilder;
use crate::analysis::symmetric::CriticalState;
use crate::plan::Plan;
use crate::records::Located;
use anyhow::Result;
use polars::prelude::DataFrame;

fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

/// The state columns shared by both tables, for rows with an optional state.
struct StateColumns {
    thrust: Vec<Option<f64>>,
    crown_moment: Vec<Option<f64>>,
    hinge_angles: Vec<Vec<f64>>,
    hinge_faces: Vec<Vec<String>>,
    sliding_angles: Vec<Vec<f64>>,
    sliding_senses: Vec<Vec<String>>,
}

impl StateColumns {
    fn of<'a>(states: impl Iterator<Item = Option<&'a CriticalState>>) -> Self {
        let mut c = StateColumns {
            thrust: Vec::new(),
            crown_moment: Vec::new(),
            hinge_angles: Vec::new(),
            hinge_faces: Vec::new(),
            sliding_angles: Vec::new(),
            sliding_senses: Vec::new(),
        };
        for s in states {
            c.thrust
                .push(s.and_then(|s| finite(s.thrust_over_half_weight)));
            c.crown_moment.push(s.and_then(|s| finite(s.crown_moment)));
            let m = s.map(|s| &s.mechanism);
            let hinges = m.map_or(&[][..], |m| &m.hinges[..]);
            let sliding = m.map_or(&[][..], |m| &m.sliding_joints[..]);
            c.hinge_angles
                .push(hinges.iter().map(|h| h.angle_deg).collect());
            c.hinge_faces
                .push(hinges.iter().map(|h| h.face.as_str().to_string()).collect());
            c.sliding_angles
                .push(sliding.iter().map(|j| j.angle_deg).collect());
            c.sliding_senses.push(
                sliding
                    .iter()
                    .map(|j| j.sense.as_str().to_string())
                    .collect(),
            );
        }
        c
    }

    fn add(self, t: TableBuilder) -> TableBuilder {
        t.opt_f64("thrust_over_half_weight", self.thrust)
            .opt_f64("crown_moment", self.crown_moment)
            .list_f64("hinge_angles_deg", self.hinge_angles)
            .list_str("hinge_faces", self.hinge_faces)
            .list_f64("sliding_angles_deg", self.sliding_angles)
            .list_str("sliding_senses", self.sliding_senses)
    }
}

/// The form's columns, as results.parquet writes them: shape, eccentricity (null for a
/// circular arch) and joint planes, one row per form.
fn with_form_columns<'a>(
    t: TableBuilder,
    forms: impl Iterator<Item = &'a crate::model::ArchForm>,
) -> TableBuilder {
    let (mut shape, mut e, mut joints) = (Vec::new(), Vec::new(), Vec::new());
    for f in forms {
        let ecc = match f.shape {
            crate::model::Shape::Pointed { eccentricity } => Some(eccentricity),
            crate::model::Shape::Circular => None,
        };
        shape.push(if ecc.is_some() { "pointed" } else { "circular" }.to_string());
        e.push(ecc);
        joints.push(f.joints.as_str().to_string());
    }
    t.str("shape", shape)
        .opt_f64("eccentricity", e)
        .str("joints", joints)
}

fn load_case_name(plan: &Plan, i: usize) -> String {
    plan.manifest
        .load_cases
        .get(i)
        .map_or_else(|| format!("#{i}"), |l| l.name.clone())
}

/// The boundary table: one row per located crossing (always the full schema, even empty).
pub fn boundaries_frame(plan: &Plan, located: &Located) -> Result<DataFrame> {
    let b = &located.boundaries;
    let t = TableBuilder::new()
        .str(
            "load_case",
            b.iter()
                .map(|p| load_case_name(plan, p.load_case))
                .collect(),
        )
        .f64("mu", b.iter().map(|p| p.mu).collect())
        .f64("k", b.iter().map(|p| p.k).collect())
        .f64("t_over_r", b.iter().map(|p| p.t_over_r()).collect())
        .str(
            "regime_low",
            b.iter()
                .map(|p| p.regime_low.as_str().to_string())
                .collect(),
        )
        .str(
            "regime_high",
            b.iter()
                .map(|p| p.regime_high.as_str().to_string())
                .collect(),
        )
        .str(
            "axis",
            b.iter().map(|p| p.axis.as_str().to_string()).collect(),
        )
        .bool(
            "on_collapse_curve",
            b.iter().map(|p| p.on_collapse_curve).collect(),
        )
        .opt_str(
            "mechanism",
            b.iter()
                .map(|p| p.mechanism.map(|m| m.as_str().to_string()))
                .collect(),
        );
    let t = StateColumns::of(b.iter().map(|p| p.state.as_ref()))
        .add(t)
        .f64(
            "half_angle_deg",
            b.iter().map(|p| p.half_angle_deg).collect(),
        )
        .opt_u32("voussoirs", b.iter().map(|p| p.voussoirs).collect());
    with_form_columns(t, b.iter().map(|p| &p.form))
        .opt_f64("at_deg", b.iter().map(|p| p.at_deg).collect())
        .opt_f64("at_x", b.iter().map(|p| p.at_x).collect())
        .finish()
}

/// The bifurcation table: one row per bifurcation point (always the full schema).
pub fn bifurcations_frame(plan: &Plan, located: &Located) -> Result<DataFrame> {
    let b = &located.bifurcations;
    let t = TableBuilder::new()
        .str(
            "load_case",
            b.iter()
                .map(|p| load_case_name(plan, p.load_case))
                .collect(),
        )
        .f64("mu", b.iter().map(|p| p.mu).collect())
        .f64("k", b.iter().map(|p| p.k).collect())
        .f64("t_over_r", b.iter().map(|p| p.t_over_r()).collect())
        .str(
            "mechanism_a",
            b.iter()
                .map(|p| p.mechanism_a.as_str().to_string())
                .collect(),
        )
        .str(
            "mechanism_b",
            b.iter()
                .map(|p| p.mechanism_b.as_str().to_string())
                .collect(),
        );
    let t = StateColumns::of(b.iter().map(|p| Some(&p.state)))
        .add(t)
        .f64(
            "half_angle_deg",
            b.iter().map(|p| p.half_angle_deg).collect(),
        )
        .opt_u32("voussoirs", b.iter().map(|p| p.voussoirs).collect());
    with_form_columns(t, b.iter().map(|p| &p.form))
        .opt_f64("at_deg", b.iter().map(|p| p.at_deg).collect())
        .opt_f64("at_x", b.iter().map(|p| p.at_x).collect())
        .opt_str(
            "axis",
            b.iter()
                .map(|p| p.axis.map(|a| a.as_str().to_string()))
                .collect(),
        )
        .opt_f64("load_factor", b.iter().map(|p| p.load_factor).collect())
        .finish()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::{Regime, symmetric};
    use crate::model::{Arch, Friction};
    use crate::records::{Bifurcation, BoundaryPoint, EdgeAxis};
    use polars::prelude::DataType;
    use std::path::Path;

    const BOUNDARY_COLUMNS: [&str; 22] = [
        "load_case",
        "mu",
        "k",
        "t_over_r",
        "regime_low",
        "regime_high",
        "axis",
        "on_collapse_curve",
        "mechanism",
        "thrust_over_half_weight",
        "crown_moment",
        "hinge_angles_deg",
        "hinge_faces",
        "sliding_angles_deg",
        "sliding_senses",
        "half_angle_deg",
        "voussoirs",
        "shape",
        "eccentricity",
        "joints",
        "at_deg",
        "at_x",
    ];
    const BIFURCATION_COLUMNS: [&str; 21] = [
        "load_case",
        "mu",
        "k",
        "t_over_r",
        "mechanism_a",
        "mechanism_b",
        "thrust_over_half_weight",
        "crown_moment",
        "hinge_angles_deg",
        "hinge_faces",
        "sliding_angles_deg",
        "sliding_senses",
        "half_angle_deg",
        "voussoirs",
        "shape",
        "eccentricity",
        "joints",
        "at_deg",
        "at_x",
        "axis",
        "load_factor",
    ];

    fn plan() -> Plan {
        let m = crate::manifest::parse(
            "name: t\nload_cases: [{name: gravity, kind: self_weight}]\ngrid:\n  k: {values: [1.2]}\n  mu: {values: [0.4]}\n",
            Path::new("t.yaml"),
        )
        .unwrap();
        crate::plan::build(m).unwrap()
    }

    fn names(df: &DataFrame) -> Vec<String> {
        df.get_column_names()
            .iter()
            .map(|s| s.to_string())
            .collect()
    }

    fn dtype(df: &DataFrame, c: &str) -> DataType {
        df.column(c).unwrap().dtype().clone()
    }

    #[test]
    fn empty_tables_have_the_full_schema() {
        let l = Located::default();
        let b = boundaries_frame(&plan(), &l).unwrap();
        assert_eq!(names(&b), BOUNDARY_COLUMNS);
        assert_eq!(b.height(), 0);
        assert_eq!(dtype(&b, "mechanism"), DataType::String);
        assert_eq!(dtype(&b, "on_collapse_curve"), DataType::Boolean);
        assert_eq!(
            dtype(&b, "hinge_angles_deg"),
            DataType::List(Box::new(DataType::Float64))
        );
        assert_eq!(
            dtype(&b, "sliding_senses"),
            DataType::List(Box::new(DataType::String))
        );
        let f = bifurcations_frame(&plan(), &l).unwrap();
        assert_eq!(names(&f), BIFURCATION_COLUMNS);
        assert_eq!(f.height(), 0);
    }

    #[test]
    fn rows_carry_the_state_and_nulls_where_there_is_none() {
        let arch = Arch::semicircular(1.3).unwrap();
        let kc = symmetric::thickness(&arch, Friction::INFINITE)
            .found()
            .cloned()
            .unwrap();
        let point = |state: Option<_>| BoundaryPoint {
            load_case: 0,
            half_angle_deg: 90.0,
            voussoirs: None,
            form: crate::model::ArchForm::default(),
            at_deg: None,
            at_x: None,
            k: kc.k,
            mu: 0.5,
            axis: EdgeAxis::K,
            regime_low: Regime::Rotational,
            regime_high: Regime::Stable,
            on_collapse_curve: true,
            mechanism: Some(kc.mechanism.kind),
            state,
        };
        let l = Located {
            boundaries: vec![point(Some(kc.clone())), point(None)],
            bifurcations: vec![Bifurcation {
                load_case: 0,
                half_angle_deg: 90.0,
                voussoirs: Some(16),
                form: crate::model::ArchForm::default(),
                at_deg: None,
                at_x: None,
                axis: None,
                load_factor: None,
                k: kc.k,
                mu: 0.39,
                mechanism_a: crate::analysis::MechanismKind::Mixed,
                mechanism_b: crate::analysis::MechanismKind::Rotational,
                state: kc.clone(),
            }],
            refinement_analyses: 3,
        };
        let b = boundaries_frame(&plan(), &l).unwrap();
        assert_eq!(b.height(), 2);
        let thrust = super::super::f64_column(&b, "thrust_over_half_weight").unwrap();
        assert_eq!(thrust, vec![Some(kc.thrust_over_half_weight), None]);
        let faces = super::super::list_str_column(&b, "hinge_faces").unwrap();
        assert_eq!(faces[0].len(), 5);
        assert!(faces[1].is_empty());
        let axis = super::super::str_column(&b, "axis").unwrap();
        assert_eq!(axis[0].as_deref(), Some("k"));
        let lc = super::super::str_column(&b, "load_case").unwrap();
        assert_eq!(lc[0].as_deref(), Some("gravity"));
        let f = bifurcations_frame(&plan(), &l).unwrap();
        let t = super::super::f64_column(&f, "t_over_r").unwrap();
        assert!((t[0].unwrap() - 0.107478038107).abs() < 1e-9);
        let v = super::super::f64_column(&f, "voussoirs").unwrap();
        assert_eq!(v, vec![Some(16.0)]);
    }
}
