//! Limits that keep a run's time and answers sound: the length of the study name (it names a
//! directory), the thickness ratio K the solver answers reliably, and the voussoir count the
//! general solver answers promptly.

use super::super::error::ManifestError;
use super::super::raw::RawManifest;
use super::super::types::{ArchOptions, AxisName, GridAxis, LoadCase, SceneSpec};
use super::Ctx;
use crate::model::{Discretisation, k_from_t_over_r};

/// Largest manifest file read, in bytes: a study manifest is a few hundred bytes; anything
/// over this (or a device such as /dev/zero) is refused before it is read.
pub const MAX_MANIFEST_BYTES: u64 = 1 << 20;

/// Longest study name, in characters: it names the run directory and its staging sibling,
/// which must fit the 255-byte file-name limit of common file systems.
pub const MAX_NAME_CHARS: usize = 100;

/// Largest thickness ratio K = R/r (t/R_c ≤ 1.9604). Real arches have K below 3; up to
/// K = 10⁴ every mechanism checked satisfied its work equation to 10⁻¹², while at K = 10⁶ the
/// continuum solution no longer does (residual 0.2) and at K = 10³⁰⁰ the thrusts overflow.
/// K ≤ 100 keeps two decades of margin.
pub const MAX_K: f64 = 100.0;

/// Largest voussoir count of the general solver (a live load, a pointed outline or vertical
/// joints): at 10⁵ voussoirs one analysis takes 0.2 to 2.5 s on one core, and the time
/// grows faster than the count (4 s for a load factor at 4·10⁵, no answer in 20 s at 10⁶).
/// Self-weight on a circular arch with radial joints has a closed route and keeps 10⁷.
pub const MAX_GENERAL_VOUSSOIRS: u32 = 100_000;

/// The checks of this module, after the other rules have passed.
pub(super) fn check_limits(
    raw: &RawManifest,
    arch: &ArchOptions,
    grid: &[GridAxis],
    load_cases: &[LoadCase],
    scenes: &[SceneSpec],
    cx: &Ctx,
) -> Result<(), ManifestError> {
    let name = &raw.name;
    let chars = name.value.chars().count();
    if chars > MAX_NAME_CHARS {
        return Err(cx.err(
            Some(name.referenced),
            "name",
            format!(
                "a name of {chars} characters is not allowed: the study name names the run \
                 directory; use at most {MAX_NAME_CHARS} characters"
            ),
        ));
    }
    check_k(grid, scenes, cx)?;
    check_voussoirs(arch, grid, load_cases, cx)
}

/// A number as a person writes it: plain when moderate, in exponent form when very large or
/// very small (1e300, not 301 digits).
pub fn short_number(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-6..1e9).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

fn k_message(k: f64) -> String {
    let k = short_number(k);
    format!(
        "K = {k} is not allowed: K = R/r must be at most {MAX_K} (t/R_c ≤ {:.4}); beyond it \
         the solver's answers are not reliable and no masonry arch is that thick (README, \
         Limits)",
        2.0 * (MAX_K - 1.0) / (MAX_K + 1.0)
    )
}

fn check_k(grid: &[GridAxis], scenes: &[SceneSpec], cx: &Ctx) -> Result<(), ManifestError> {
    for axis in grid {
        let key = match axis.name {
            AxisName::K => "grid.k",
            AxisName::TOverR => "grid.t_over_r",
            _ => continue,
        };
        for &v in &axis.values {
            let k = if axis.name == AxisName::K {
                v
            } else {
                k_from_t_over_r(v)
            };
            if k > MAX_K {
                return Err(cx.err_unplaced(key, k_message(k)));
            }
        }
    }
    if let Some(s) = scenes.iter().find(|s| s.k > MAX_K) {
        return Err(cx.err_unplaced("scenes", k_message(s.k)));
    }
    Ok(())
}

fn check_voussoirs(
    arch: &ArchOptions,
    grid: &[GridAxis],
    load_cases: &[LoadCase],
    cx: &Ctx,
) -> Result<(), ManifestError> {
    let live = load_cases.iter().find(|lc| lc.kind.is_live());
    let general_form = super::load_checks::study_forms(arch, grid)
        .iter()
        .any(|f| !f.is_circular_radial());
    if live.is_none() && !general_form {
        return Ok(());
    }
    let why = match live {
        Some(lc) => format!("load case \"{}\" has a live load", lc.name),
        None => "the arch is pointed or has vertical joints".to_string(),
    };
    let message = |n: f64| {
        format!(
            "{} voussoirs are not allowed here: {why}, which the general solver analyses, \
             and it answers promptly up to {MAX_GENERAL_VOUSSOIRS} voussoirs; use at most \
             {MAX_GENERAL_VOUSSOIRS} (or `continuum`)",
            short_number(n)
        )
    };
    let limit = f64::from(MAX_GENERAL_VOUSSOIRS);
    if let Discretisation::Voussoirs(n) = arch.voussoirs
        && n > MAX_GENERAL_VOUSSOIRS
    {
        return Err(cx.err_unplaced("arch.voussoirs", message(f64::from(n))));
    }
    if let Some(axis) = grid.iter().find(|a| a.name == AxisName::Voussoirs)
        && let Some(&n) = axis.values.iter().find(|v| v.is_finite() && **v > limit)
    {
        return Err(cx.err_unplaced("grid.voussoirs", message(n)));
    }
    Ok(())
}
