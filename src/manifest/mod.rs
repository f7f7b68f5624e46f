//! Study manifests: YAML as typed (serde-saphyr, unknown keys rejected) turned into a
//! validated [`Manifest`]. Every error names the file, line and column, the key, the value
//! given and what is allowed.
//!
//! `raw` holds the types as written, `types` the validated ones, `error` the error and
//! `validate` every rule, one named step per group of rules.

mod error;
mod parse_errors;
mod raw;
mod scene_options;
mod types;
mod uncertain;
mod validate;

pub use error::ManifestError;
pub use parse_errors::MAX_NODES;
pub use raw::{Number, RawVoussoirs};
pub use scene_options::{SceneOptionError, SceneOptions};
pub use types::{
    ArchOptions, Author, AxisName, DEFAULT_BOUNDARY_TOLERANCE, FigureWidth, GridAxis,
    JOINTS_RADIAL, JOINTS_VERTICAL, LoadCase, LoadKind, Manifest, SceneSpec, axis_value_of_joints,
    joints_of_axis_value,
};
pub use uncertain::{
    Correlation, DEFAULT_BOOTSTRAP, DEFAULT_SAMPLES, DistributionAxis, ParamName, Question,
    Sampling, UncertainParam,
};
pub use validate::{
    MAX_AXIS_STEPS, MAX_BOOTSTRAP, MAX_GENERAL_VOUSSOIRS, MAX_K, MAX_MANIFEST_BYTES,
    MAX_NAME_CHARS, MAX_SAMPLES, short_number,
};

use raw::RawManifest;
use std::path::Path;

/// Reads and validates a manifest file.
pub fn load(path: &Path) -> Result<Manifest, ManifestError> {
    let text = std::fs::read_to_string(path).map_err(|e| ManifestError {
        path: path.to_path_buf(),
        position: None,
        key: None,
        message: format!("cannot read the manifest: {e}"),
    })?;
    parse(&text, path)
}

/// Parses and validates manifest text; `path` is used in messages.
pub fn parse(text: &str, path: &Path) -> Result<Manifest, ManifestError> {
    let mut options = serde_saphyr::Options::default();
    // NaN and ±inf reach the validation below, which names the key and the value.
    options.non_finite_float_policy = serde_saphyr::NonFiniteFloatPolicy::PassThrough;
    let raw: RawManifest = serde_saphyr::from_str_with_options(text, options).map_err(|e| {
        let position = e
            .location()
            .filter(|l| l.line() > 0)
            .map(|l| (l.line(), l.column()));
        // The crate's rendering may start with its own position and add a snippet: keep the
        // first line without the position.
        let msg = e.to_string();
        let mut first = msg
            .lines()
            .next()
            .unwrap_or("invalid YAML")
            .trim()
            .to_string();
        if let Some(rest) = first.strip_prefix("error: ") {
            first = rest.to_string();
        }
        if first.starts_with("line ")
            && let Some(i) = first.find(": ")
        {
            first = first[i + 2..].to_string();
        }
        // A missing key is reported where its mapping ends, after the mapping's last key:
        // the key at fault is the missing one.
        let missing = (first.strip_prefix("missing field `"))
            .and_then(|rest| rest.split('`').next())
            .map(str::to_string);
        ManifestError {
            path: path.to_path_buf(),
            position,
            key: missing
                .clone()
                .or_else(|| position.and_then(|(l, c)| parse_errors::key_at(text, l, c))),
            message: match missing {
                Some(k) => format!(
                    "`{k}` is required here and missing (the position is where its mapping ends)"
                ),
                None => parse_errors::friendly(&first),
            },
        }
    })?;
    validate::manifest(raw, path)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Find;

    fn p(s: &str) -> Result<Manifest, ManifestError> {
        parse(s, Path::new("study.yaml"))
    }

    #[test]
    fn a_missing_key_is_named_itself_not_the_key_before_it() {
        let e = p("grid:\n  k: {values: [1.2]}\n  mu: {values: [0.4]}\nfind: state\n").unwrap_err();
        assert_eq!(e.key.as_deref(), Some("name"), "{e}");
        assert!(e.to_string().contains("`name` is required"), "{e}");
        let e =
            p("name: a\ngrid:\n  k: {values: [1.2]}\nload_cases:\n  - {name: g}\n").unwrap_err();
        assert_eq!(e.key.as_deref(), Some("kind"), "{e}");
    }

    const TWO_FINDS: &str = "name: a
grid:
  voussoirs: {values: [8, continuum]}
  t_over_r: {values: [0.15]}
  mu: {values: [0.4]}
load_cases:
  - {name: gravity, kind: self_weight}
  - {name: wind, kind: horizontal, find: load_factor}
find: thresholds
";

    #[test]
    fn a_load_case_may_name_its_own_find() {
        let m = p(TWO_FINDS).unwrap();
        assert_eq!(m.find, Find::Thresholds);
        assert_eq!(m.load_cases[0].find, Find::Thresholds);
        assert_eq!(m.load_cases[1].find, Find::LoadFactor);
        // The thresholds find K and μ: their load case spans the voussoir axis only.
        let spans =
            |lc: &LoadCase| -> Vec<bool> { m.grid.iter().map(|a| lc.spans(a.name)).collect() };
        assert_eq!(spans(&m.load_cases[0]), [true, false, false]);
        assert_eq!(spans(&m.load_cases[1]), [true, true, true]);
        // The resolved manifest (run.json) names every load case's find.
        let json = serde_json::to_value(&m).unwrap();
        assert_eq!(json["load_cases"][0]["find"], "thresholds");
        assert_eq!(json["load_cases"][1]["find"], "load_factor");
    }

    #[test]
    fn per_load_case_finds_are_checked_against_the_axes_and_loads() {
        // An axis that no load case spans.
        let e = p("name: a
grid:
  voussoirs: {values: [8]}
  mu: {values: [0.4]}
load_cases:
  - {name: gravity, kind: self_weight}
  - {name: more, kind: self_weight, find: friction}
find: thresholds
")
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("study.yaml:4:")
                && e.contains("grid.mu")
                && e.contains("no load case uses this axis")
                && e.contains("thresholds, friction"),
            "{e}"
        );
        // A load case whose find needs an axis the grid lacks is named.
        let e = p(&TWO_FINDS.replace("  mu: {values: [0.4]}\n", ""))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("load case \"wind\" (find load_factor) needs a mu axis"),
            "{e}"
        );
        // Each load case's find is checked against its load.
        let e = p(&TWO_FINDS.replace(
            "kind: horizontal, find: load_factor",
            "kind: horizontal, find: thrust",
        ))
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("load_cases.kind") && e.contains("defined for self_weight only"),
            "{e}"
        );
        // An unknown find is located at the load case.
        let e = p(&TWO_FINDS.replace("find: load_factor", "find: lambda"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("study.yaml:8:")
                && e.contains("load_cases.find")
                && e.contains("\"lambda\""),
            "{e}"
        );
    }

    #[test]
    fn minimal_manifest_has_defaults() {
        let m = p(
            "name: a\ngrid:\n  k: {from: 1.05, to: 1.5, steps: 10}\n  mu: {values: [0.3, inf]}\n",
        )
        .unwrap();
        assert_eq!(m.find, Find::State);
        assert_eq!(m.arch.half_angle_deg, 90.0);
        assert_eq!(m.grid.len(), 2);
        assert_eq!(m.grid[0].values.len(), 10);
        assert_eq!(m.grid[0].values[9], 1.5);
        assert!(m.grid[1].values[1].is_infinite());
        assert_eq!(m.load_cases.len(), 1);
    }

    #[test]
    fn errors_name_line_column_key_and_value() {
        let e = p("name: a\ngrid:\n  k: {from: 1.05, to: 1.5, steps: 0}\n  mu: {values: [0.3]}\n")
            .unwrap_err();
        let s = e.to_string();
        assert!(s.starts_with("study.yaml:3:"), "{s}");
        assert!(s.contains("grid.k.steps") && s.contains("value 0"), "{s}");
        let e = p("name: a\ngrid:\n  k: {from: 0.9, to: 1.5, steps: 3}\n  mu: {values: [0.3]}\n")
            .unwrap_err();
        assert!(
            e.to_string().contains("value 0.9") && e.to_string().contains("greater than 1"),
            "{e}"
        );
        let e = p("name: a\ngrid:\n  k: {values: [1.2]}\n  mu: {values: [-0.1]}\n").unwrap_err();
        assert!(e.to_string().contains("value -0.1"), "{e}");
        let e = p("name: a\ngrid:\n  k: {values: [1.2]}\n  mu: {values: [.nan]}\n").unwrap_err();
        assert!(e.to_string().contains("NaN"), "{e}");
        let e = p("name: a\nfoo: 1\n").unwrap_err();
        assert!(e.to_string().contains("foo"), "{e}");
        assert_eq!(e.position.map(|p| p.0), Some(2));
    }
}
