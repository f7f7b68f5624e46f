//! Validation of a manifest as written into a [`Manifest`]: one step per group of rules,
//! in the order the errors are reported (name, arch, find, load cases, grid, cross-checks of
//! the loads, scenes, boundary tolerance). Every error names the key and the value at fault.

mod arch;
mod citation;
mod distributions;
mod grid;
mod limits;
mod load_checks;
mod loads;
mod uncertain;

pub use grid::MAX_AXIS_STEPS;
pub use limits::{MAX_GENERAL_VOUSSOIRS, MAX_K, MAX_MANIFEST_BYTES, MAX_NAME_CHARS, short_number};
pub use uncertain::{MAX_BOOTSTRAP, MAX_SAMPLES};

use super::error::ManifestError;
use super::raw::{RawBoundaries, RawFigures, RawManifest, RawScene};
use super::types::{DEFAULT_BOUNDARY_TOLERANCE, FigureWidth, Manifest, SceneSpec};
use crate::scene::Find;
use serde_saphyr::{Location, Spanned};
use std::path::Path;

/// Where the messages of a validation point: the manifest file.
pub(super) struct Ctx<'a> {
    path: &'a Path,
}

impl Ctx<'_> {
    fn err(&self, at: Option<Location>, key: &str, message: impl Into<String>) -> ManifestError {
        ManifestError {
            path: self.path.to_path_buf(),
            position: at.filter(|l| l.line() > 0).map(|l| (l.line(), l.column())),
            key: Some(key.to_string()),
            message: message.into(),
        }
    }

    /// An error at a key without a position in the file.
    fn err_unplaced(&self, key: &str, message: impl Into<String>) -> ManifestError {
        ManifestError {
            path: self.path.to_path_buf(),
            position: None,
            key: Some(key.into()),
            message: message.into(),
        }
    }
}

fn fmt_num(x: f64) -> String {
    if x.is_infinite() {
        if x > 0.0 { "inf".into() } else { "-inf".into() }
    } else {
        format!("{x}")
    }
}

fn is_valid_name(s: &str) -> bool {
    !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
}

/// Validates a manifest as written; `path` is used in messages.
pub(super) fn manifest(raw: RawManifest, path: &Path) -> Result<Manifest, ManifestError> {
    let cx = &Ctx { path };
    check_name(&raw.name, cx)?;
    let e_axis = raw.grid.as_ref().is_some_and(|g| g.eccentricity.is_some());
    let arch = arch::validate_arch(&raw.arch, e_axis, cx)?;
    let question = raw
        .find
        .as_ref()
        .and_then(|f| crate::manifest::Question::parse(&f.value));
    let find = match (&raw.find, question) {
        (None, _) | (Some(_), Some(_)) => Find::State,
        (Some(f), None) => parse_find(f, "find", cx)?,
    };
    let mut load_cases = loads::validate_load_cases(raw.load_cases.as_deref(), find, cx)?;
    let sampled = match question {
        Some(q) => Some(uncertain::validate(&raw, q, &arch, &mut load_cases, cx)?),
        None => {
            if let Some(u) = &raw.uncertain {
                return Err(cx.err(
                    Some(u.referenced),
                    "uncertain",
                    "uncertain parameters are sampled by a `find: probability`, `fragility` or \
                     `sensitivity` study: set the study's find to one of them",
                ));
            }
            if let Some(s) = &raw.samples {
                return Err(cx.err(
                    Some(s.referenced),
                    "samples",
                    "`samples` sets how the uncertain parameters of a probability, fragility or \
                     sensitivity study are sampled: this study has none",
                ));
            }
            None
        }
    };
    // The other checks see each uncertain parameter as an axis of its extreme values.
    let shadow = sampled.as_ref().map_or(&[][..], |v| &v.shadow[..]);
    let grid = grid::validate_grid(raw.grid.as_ref(), &load_cases, shadow, cx)?;
    let mut checked = grid.clone();
    checked.extend((shadow.iter()).filter(|a| !a.name.is_position()).cloned());
    let checked_lcs = match &sampled {
        Some(v) => uncertain::as_checked(&v.sampling, &load_cases),
        None => load_cases.clone(),
    };
    load_checks::check_loads(&raw, &arch, &checked, &checked_lcs, cx)
        .map_err(|e| as_uncertain(e, shadow, &grid))?;
    let scenes = validate_scenes(raw.scenes.as_deref().unwrap_or(&[]), cx)?;
    let boundary_tolerance = boundary_tolerance(raw.boundaries.as_ref(), cx)?;
    let figure_width = figure_width(raw.figures.as_ref(), cx)?;
    limits::check_limits(&raw, &arch, &checked, &load_cases, &scenes, cx)
        .map_err(|e| as_uncertain(e, shadow, &grid))?;
    if let Some(v) = &sampled {
        // Checked as the state or load-factor studies they resemble; each sample is then
        // analysed with the find its question asks for.
        for lc in &mut load_cases {
            lc.find = v.sampling.question.scene_find(lc.kind);
            lc.sampled = true;
        }
    }
    Ok(Manifest {
        name: raw.name.value,
        title: raw.title,
        description: raw.description,
        authors: citation::validate_authors(raw.authors.as_deref().unwrap_or(&[]), cx)?,
        license: citation::validate_license(raw.license.as_ref(), cx)?,
        arch,
        grid,
        load_cases,
        find,
        scenes,
        boundary_tolerance,
        figure_width,
        sampling: sampled.map(|v| v.sampling),
    })
}

/// An error the checks of the loads or the limits found on an axis that stands for an
/// uncertain parameter, keyed by that parameter (`uncertain.k`, not `grid.k`).
fn as_uncertain(
    mut e: ManifestError,
    shadow: &[super::types::GridAxis],
    grid: &[super::types::GridAxis],
) -> ManifestError {
    if let Some(key) = &e.key
        && let Some(name) = key.strip_prefix("grid.")
        && shadow.iter().any(|a| a.name.as_str() == name)
        && !grid.iter().any(|a| a.name.as_str() == name)
    {
        e.key = Some(format!("uncertain.{name}"));
    }
    e
}

/// The column width of the paper figures: `single` or `double` (the default).
fn figure_width(raw: Option<&RawFigures>, cx: &Ctx) -> Result<FigureWidth, ManifestError> {
    match raw.and_then(|f| f.width.as_ref()) {
        None => Ok(FigureWidth::default()),
        Some(w) => FigureWidth::parse(&w.value).ok_or_else(|| {
            cx.err(
                Some(w.referenced),
                "figures.width",
                format!(
                    "value {:?} is not allowed: use {}",
                    w.value,
                    FigureWidth::NAMES
                ),
            )
        }),
    }
}

/// The study name names the run directory: letters, digits, `_` and `-` only.
fn check_name(name: &Spanned<String>, cx: &Ctx) -> Result<(), ManifestError> {
    if is_valid_name(&name.value) {
        return Ok(());
    }
    Err(cx.err(
        Some(name.referenced),
        "name",
        format!(
            "value {:?} is not allowed: use letters, digits, `_` and `-` only",
            name.value
        ),
    ))
}

fn parse_find(f: &Spanned<String>, key: &str, cx: &Ctx) -> Result<Find, ManifestError> {
    Find::parse(&f.value).ok_or_else(|| {
        cx.err(
            Some(f.referenced),
            key,
            format!(
                "value {:?} is not allowed: use state, thickness, friction, thrust, thresholds or load_factor (or, with uncertain parameters, probability, fragility or sensitivity)",
                f.value
            ),
        )
    })
}

/// The scenes to draw: exactly one of K or t/R_c, and μ ≥ 0 or inf.
fn validate_scenes(raw: &[Spanned<RawScene>], cx: &Ctx) -> Result<Vec<SceneSpec>, ManifestError> {
    let mut scenes = Vec::new();
    for s in raw {
        let k = scene_k(s, cx)?;
        let mu = s.value.mu.value.0;
        if !(mu >= 0.0) {
            return Err(cx.err(
                Some(s.value.mu.referenced),
                "scenes.mu",
                format!("value {} is not allowed: μ must be ≥ 0 or inf", fmt_num(mu)),
            ));
        }
        scenes.push(SceneSpec { k, mu });
    }
    Ok(scenes)
}

/// The K of a scene, given as K or as t/R_c.
fn scene_k(s: &Spanned<RawScene>, cx: &Ctx) -> Result<f64, ManifestError> {
    match (&s.value.k, &s.value.t_over_r) {
        (Some(k), None) => {
            if !(k.value > 1.0 && k.value.is_finite()) {
                return Err(cx.err(
                    Some(k.referenced),
                    "scenes.k",
                    format!("value {} is not allowed: K must be > 1", k.value),
                ));
            }
            Ok(k.value)
        }
        (None, Some(t)) => {
            if !(t.value > 0.0 && t.value < 2.0) {
                return Err(cx.err(
                    Some(t.referenced),
                    "scenes.t_over_r",
                    format!("value {} is not allowed: t/R_c must lie in (0, 2)", t.value),
                ));
            }
            Ok(crate::model::k_from_t_over_r(t.value))
        }
        _ => Err(cx.err(
            Some(s.referenced),
            "scenes",
            "each scene needs exactly one of k or t_over_r, and mu",
        )),
    }
}

/// The tolerance for locating boundaries: in (0, 0.01], at least 1e-13.
fn boundary_tolerance(raw: Option<&RawBoundaries>, cx: &Ctx) -> Result<f64, ManifestError> {
    match raw.and_then(|b| b.tolerance.as_ref()) {
        None => Ok(DEFAULT_BOUNDARY_TOLERANCE),
        Some(t) => {
            if !(t.value > 0.0 && t.value <= 1e-2) {
                return Err(cx.err(
                    Some(t.referenced),
                    "boundaries.tolerance",
                    format!("value {} is not allowed: it must lie in (0, 0.01]", t.value),
                ));
            }
            Ok(t.value.max(1e-13))
        }
    }
}
