//! The Arrow schema stored in every Parquet file archstudy writes (its `ARROW:schema` key):
//! plain string and list types that every mainstream reader opens (pandas with pyarrow 18
//! and newer, polars, DuckDB, R arrow), and each column's unit and meaning as field metadata
//! (`unit`, `description`).

use polars::prelude::{ArrowField, ArrowSchema, CompatLevel, DataFrame, PlSmallStr};
use polars_parquet::write::{KeyValue, schema_to_metadata_key};
use std::collections::BTreeMap;

/// Unit (empty for none) and meaning of every documented column, by name; the same name
/// means the same thing in every table of a run.
const COLUMN_DOCS: &[(&str, &str, &str)] = &[
    ("case_id", "", "position of the case in the plan"),
    (
        "point",
        "",
        "index of the grid point among the load case's points (sampling studies)",
    ),
    (
        "sample",
        "",
        "index of the sample (of the base sample of a sensitivity design)",
    ),
    (
        "block",
        "",
        "sensitivity design: A, B, or AB_p (A with the column of parameter p from B)",
    ),
    (
        "stands",
        "",
        "the arch stands (at its λ; for λ_max and the margin, under its own weight)",
    ),
    (
        "lambda_max",
        "",
        "largest load factor of the sample (0: does not stand under its own weight; inf: unbounded)",
    ),
    (
        "margin",
        "",
        "stability margin t/t_c − 1 (t_c the collapse thickness at the sample's other values; −1: no thickness stands)",
    ),
    (
        "quantity",
        "",
        "what an estimate is: probability, exact_probability, mechanism, fragility_cdf, quantile, first_order, total, convergence, grid, …",
    ),
    (
        "parameter",
        "",
        "the mechanism, quantile level, uncertain parameter, sampling method or grid axis an estimate is about",
    ),
    ("value", "", "the estimate"),
    ("lo", "", "lower end of its 95 % interval"),
    ("hi", "", "upper end of its 95 % interval"),
    ("note", "", "how a value was obtained, or why it is missing"),
    ("load_case", "", "load case name"),
    (
        "load_kind",
        "",
        "load case kind: self_weight, horizontal or point",
    ),
    (
        "load",
        "",
        "load case kind: self_weight, horizontal or point",
    ),
    (
        "find",
        "",
        "what the case computes: state, thickness, friction, thrust, thresholds or load_factor",
    ),
    (
        "k",
        "R/r",
        "thickness ratio K = R/r (extrados over intrados radius)",
    ),
    (
        "t_over_r",
        "t/R_c",
        "thickness over centreline radius, 2(K - 1)/(K + 1)",
    ),
    ("mu", "", "friction coefficient μ = tan φ (inf: no sliding)"),
    (
        "half_angle_deg",
        "deg",
        "half-embrace angle α (90: semicircular)",
    ),
    (
        "weight",
        "",
        "weight model: annular (true sector weights) or centreline",
    ),
    ("voussoirs", "", "voussoir count; null for the continuum"),
    ("shape", "", "outline: circular or pointed"),
    (
        "eccentricity",
        "ρ_c",
        "eccentricity e of a pointed arch's centres, over the centreline radius",
    ),
    ("joints", "", "joint planes: radial or vertical"),
    (
        "keystone",
        "",
        "true when the crown lies inside one block: the keystone option (continuum) or an odd voussoir count",
    ),
    (
        "at_deg",
        "deg",
        "position of the point load, from the crown, positive to the right",
    ),
    (
        "at_x",
        "L",
        "position of the point load as x/L: horizontally from the left extrados springing over the extrados span (0.5: the crown)",
    ),
    (
        "load_width",
        "L",
        "width of the extrados a point load is spread over (a patch load centred on its position), over the extrados span; 0 for a concentrated load",
    ),
    ("lambda", "W_total", "given load factor λ of the live load"),
    (
        "outcome",
        "",
        "found, never_stands, always_stands, unbounded, not_converged, failed, unconfirmed, invalid or unsupported",
    ),
    ("regime", "", "stable, rotational, mixed, sliding or none"),
    (
        "regime_low",
        "",
        "regime on the lower-value side of the crossing",
    ),
    (
        "regime_high",
        "",
        "regime on the higher-value side of the crossing",
    ),
    (
        "thrust_r_min",
        "W_half",
        "end of the rotational thrust domain H^r",
    ),
    (
        "thrust_r_max",
        "W_half",
        "end of the rotational thrust domain H^r",
    ),
    (
        "thrust_s_min",
        "W_half",
        "end of the sliding thrust domain H^s",
    ),
    (
        "thrust_s_max",
        "W_half",
        "end of the sliding thrust domain H^s",
    ),
    ("k_crit", "R/r", "collapse thickness K_c"),
    ("t_over_r_crit", "t/R_c", "t/R_c at the collapse thickness"),
    ("mu_crit", "", "critical friction coefficient μ_c"),
    (
        "mechanism",
        "",
        "collapse mechanism: rotational, mixed or sliding",
    ),
    (
        "mechanism_a",
        "",
        "mechanism on the lower-μ (or lower-value) side of the bifurcation",
    ),
    (
        "mechanism_b",
        "",
        "mechanism on the higher-μ (or higher-value) side of the bifurcation",
    ),
    (
        "thrust_over_half_weight",
        "W_half",
        "horizontal crown thrust H of the limit state",
    ),
    (
        "crown_moment",
        "W_half·r",
        "crown moment m of the limit state",
    ),
    (
        "crown_shear",
        "W_half",
        "vertical force at the crown of the limit state",
    ),
    (
        "load_factor",
        "W_total",
        "largest load factor λ of the live load",
    ),
    (
        "load_factor_unbounded",
        "",
        "true when every λ ≥ 0 lets the arch stand",
    ),
    (
        "hinge_angles_deg",
        "deg",
        "hinge joints, from the crown, increasing",
    ),
    (
        "hinges_min_angles_deg",
        "deg",
        "hinge joints, from the crown, increasing",
    ),
    (
        "hinges_max_angles_deg",
        "deg",
        "hinge joints, from the crown, increasing",
    ),
    (
        "hinge_faces",
        "",
        "face of each hinge: intrados or extrados",
    ),
    (
        "hinges_min_faces",
        "",
        "face of each hinge: intrados or extrados",
    ),
    (
        "hinges_max_faces",
        "",
        "face of each hinge: intrados or extrados",
    ),
    (
        "sliding_angles_deg",
        "deg",
        "sliding joints, from the crown",
    ),
    (
        "sliding_senses",
        "",
        "sense of each sliding joint: outward or inward (crown-side part)",
    ),
    (
        "work_loads",
        "W_half·r",
        "work of the loads on the collapse mechanism (eq. 11), largest corner speed 1",
    ),
    (
        "work_friction",
        "W_half·r",
        "friction dissipation -μ Σ R^n |dr^t| of the mechanism (eq. 11)",
    ),
    (
        "work_residual",
        "",
        "|work of loads + friction| over the scale of the block works",
    ),
    (
        "mechanism_dof",
        "",
        "degrees of freedom of the blocks between the active joints",
    ),
    (
        "mechanism_admissible",
        "",
        "true when the collapse mechanism obeys every flow rule (its work equation then checks the state)",
    ),
    (
        "critical_apex_shared",
        "",
        "the find's critical value (μ_c, K_c or λ_max) with an apex load of a pointed arch shared freely between the halves",
    ),
    (
        "gap",
        "",
        "which end of the non-associative gap: no_gap (the static limit is complete), gap (a complete solution comes first along the find's path), no_complete_solution, failed",
    ),
    (
        "collapse_value",
        "",
        "the first complete solution along the find's path (λ up, K down, μ down): the collapse, the conservative end of the gap",
    ),
    (
        "gap_width",
        "",
        "distance along the path from collapse_value to the static limit (0 without gap, inf when λ_max is unbounded)",
    ),
    (
        "gap_searched_to",
        "",
        "the far end of the path searched for a complete solution (λ: its largest value)",
    ),
    (
        "collapse_mechanism",
        "",
        "rotational, mixed or sliding: the mechanism of the first complete solution",
    ),
    (
        "collapse_hinge_angles_deg",
        "deg",
        "hinges of that mechanism, degrees from the crown",
    ),
    (
        "collapse_hinge_faces",
        "",
        "face of each of those hinges that stays closed",
    ),
    (
        "collapse_sliding_angles_deg",
        "deg",
        "sliding joints of that mechanism",
    ),
    (
        "collapse_sliding_senses",
        "",
        "sense of each of those sliding joints (crown-side part)",
    ),
    (
        "collapse_lifted_angles_deg",
        "deg",
        "joints that open at both faces in that mechanism (lift-off: they carry no force)",
    ),
    (
        "collapse_thrust_over_half_weight",
        "W_half",
        "crown thrust of the complete solution's state",
    ),
    (
        "collapse_crown_shear",
        "W_half",
        "crown shear of the complete solution's state",
    ),
    (
        "collapse_crown_moment",
        "W_half·r",
        "crown moment of the complete solution's state",
    ),
    (
        "collapse_work_loads",
        "W_half·r",
        "work of the loads on the complete solution's mechanism (eq. 11), largest corner speed 1",
    ),
    (
        "collapse_work_friction",
        "W_half·r",
        "friction dissipation -μ Σ N |dr^t| of that mechanism",
    ),
    (
        "collapse_work_residual",
        "",
        "|dL(a) + dL(r,n) + dL(r,t)| over its largest term: eq. 11 holds at zero",
    ),
    (
        "collapse_flow_violation",
        "",
        "largest breach of a flow rule by that mechanism (normality, no interpenetration, maximum dissipation), relative to the joint force",
    ),
    (
        "collapse_on_loading",
        "",
        "fixed-λ finds: the first complete λ of the arch at the collapse value when below the scene's λ (it would start to move there as the load rises)",
    ),
    (
        "k_windows_from",
        "R/r",
        "lower end of each interval of K on which the arch stands (the first is k_crit)",
    ),
    (
        "k_windows_to",
        "R/r",
        "upper end of each interval of K on which the arch stands; k_windows_scanned_to where it still stands at the end of the scan",
    ),
    (
        "k_windows_scanned_to",
        "R/r",
        "the largest K the scan for intervals reached",
    ),
    (
        "k_windows_resolution",
        "R/r",
        "step of the scan in K: an interval narrower than this may be missed",
    ),
    ("k_c_rotational", "R/r", "collapse thickness at μ = ∞"),
    (
        "mu_rotational_mixed",
        "",
        "μ of the rotational/mixed bifurcation",
    ),
    ("mu_min", "", "μ_min: below it no thickness stands"),
    (
        "k_mixed_sliding",
        "R/r",
        "K of the mixed/sliding bifurcation",
    ),
    ("thrust_min", "W_half", "minimum admissible crown thrust"),
    ("thrust_max", "W_half", "maximum admissible crown thrust"),
    ("status", "", "ok, or error when the analysis failed"),
    ("message", "", "why the analysis failed"),
    ("solve_time_us", "µs", "the case's own analysis time"),
    ("axis", "", "grid axis of the crossed edge: k or mu"),
    (
        "on_collapse_curve",
        "",
        "true when one side of the crossing is stable",
    ),
];

/// Unit and meaning of a stored column, by name.
pub fn column_doc(name: &str) -> Option<(&'static str, &'static str)> {
    COLUMN_DOCS
        .iter()
        .find(|(n, _, _)| *n == name)
        .map(|&(_, unit, meaning)| (unit, meaning))
}

/// The `ARROW:schema` key of a table: the key of [`stored_arrow_schema`].
pub fn stored_schema(df: &DataFrame) -> KeyValue {
    schema_to_metadata_key(&stored_arrow_schema(df))
}

/// The Arrow schema stored with a table: each column with the plain (non-view) Arrow type of
/// its polars type and, where known, its unit and meaning.
pub fn stored_arrow_schema(df: &DataFrame) -> ArrowSchema {
    let fields = df.schema().iter().map(|(name, dtype)| {
        let field: ArrowField = dtype.to_arrow_field(name.clone(), CompatLevel::oldest());
        match column_doc(name.as_str()) {
            Some((unit, meaning)) => {
                let mut m = BTreeMap::new();
                if !unit.is_empty() {
                    m.insert(
                        PlSmallStr::from_static("unit"),
                        PlSmallStr::from_static(unit),
                    );
                }
                m.insert(
                    PlSmallStr::from_static("description"),
                    PlSmallStr::from_static(meaning),
                );
                field.with_metadata(m)
            }
            None => field,
        }
    });
    fields.collect()
}

#[cfg(test)]
mod tests {
    use super::super::{TableBuilder, read_parquet, str_column, write_parquet};
    use polars::prelude::ArrowDataType;
    use polars_parquet::read::read_metadata;

    #[test]
    fn stored_types_are_plain_and_columns_carry_their_units() {
        let mut df = TableBuilder::new()
            .f64("k", vec![1.2, 1.3])
            .str("regime", vec!["stable", "mixed"])
            .list_str("hinge_faces", vec![vec!["intrados"], vec![]])
            .finish()
            .unwrap();
        let schema = super::stored_arrow_schema(&df);
        let field = |n: &str| schema.get(n).unwrap().clone();
        assert_eq!(field("regime").dtype, ArrowDataType::LargeUtf8);
        match &field("hinge_faces").dtype {
            ArrowDataType::LargeList(inner) => assert_eq!(inner.dtype, ArrowDataType::LargeUtf8),
            other => panic!("hinge_faces stored as {other:?}"),
        }
        let k = field("k");
        let meta = k.metadata.as_deref().unwrap();
        assert_eq!(meta.get("unit").map(|s| s.as_str()), Some("R/r"));
        assert!(meta.contains_key("description"));

        // The file carries exactly that schema, and polars reads its own files back.
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.parquet");
        write_parquet(&mut df, &path).unwrap();
        let meta = read_metadata(&mut std::fs::File::open(&path).unwrap()).unwrap();
        let stored: Vec<_> = meta
            .key_value_metadata()
            .iter()
            .flatten()
            .filter(|kv| kv.key == "ARROW:schema")
            .collect();
        assert_eq!(stored, vec![&super::stored_schema(&df)]);
        let back = read_parquet(&path).unwrap();
        assert_eq!(
            str_column(&back, "regime").unwrap(),
            vec![Some("stable".to_string()), Some("mixed".to_string())]
        );
    }

    #[test]
    fn every_documented_column_has_a_meaning() {
        for name in [
            "k",
            "mu",
            "regime",
            "hinge_faces",
            "solve_time_us",
            "mechanism_b",
        ] {
            let (_, meaning) = super::column_doc(name).unwrap();
            assert!(!meaning.is_empty(), "{name}");
        }
        assert!(super::column_doc("no_such_column").is_none());
    }
}
