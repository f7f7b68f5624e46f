//! The `arch:` block: shape and eccentricity, joints, half-angle, weight model and voussoirs.

use super::{Ctx, fmt_num};
use crate::manifest::error::ManifestError;
use crate::manifest::raw::{RawArch, RawVoussoirs};
use crate::manifest::types::ArchOptions;
use crate::model::{Discretisation, JointOrientation, WeightModel};
use serde_saphyr::Location;

/// The arch options, each checked in the order its key is reported.
/// `e_axis`: the grid has an `eccentricity` axis, which gives a pointed arch its eccentricity
/// case by case (a nominal one is then not needed, and overridden when given).
pub(super) fn validate_arch(
    a: &RawArch,
    e_axis: bool,
    cx: &Ctx,
) -> Result<ArchOptions, ManifestError> {
    let shape = shape(a, cx)?;
    if e_axis && shape != "pointed" {
        return Err(cx.err(
            a.shape.as_ref().map(|s| s.referenced),
            "arch.shape",
            "an `eccentricity` axis spans pointed arches: set `shape: pointed` (e = 0 is the \
             semicircle's outline)",
        ));
    }
    let eccentricity = if e_axis && a.eccentricity.is_none() {
        None
    } else {
        eccentricity(a, shape, cx)?
    };
    let joints = joints(a, cx)?;
    let half_angle_deg = match &a.half_angle_deg {
        None => 90.0,
        Some(h) => check_half_angle(h.value, h.referenced, "arch.half_angle_deg", cx)?,
    };
    let weight = weight(a, cx)?;
    let voussoirs = voussoirs(a, cx)?;
    Ok(ArchOptions {
        shape,
        eccentricity,
        half_angle_deg,
        joints: joints.as_str(),
        keystone: a.keystone.as_ref().is_some_and(|k| k.value),
        weight,
        voussoirs,
    })
}

/// `circular` (the default) or `pointed`.
fn shape(a: &RawArch, cx: &Ctx) -> Result<&'static str, ManifestError> {
    match a.shape.as_ref().map(|s| s.value.as_str()) {
        None | Some("circular") => Ok("circular"),
        Some("pointed") => Ok("pointed"),
        Some(other) => Err(cx.err(
            a.shape.as_ref().map(|s| s.referenced),
            "arch.shape",
            format!("value {other:?} is not allowed: use circular or pointed"),
        )),
    }
}

/// A pointed arch needs an eccentricity in [0, 0.9999]; no other shape has one.
fn eccentricity(a: &RawArch, shape: &str, cx: &Ctx) -> Result<Option<f64>, ManifestError> {
    match (&a.eccentricity, shape) {
        (None, "pointed") => Err(cx.err(
            a.shape.as_ref().map(|s| s.referenced),
            "arch.eccentricity",
            "a pointed arch needs `eccentricity: e` with 0 ≤ e ≤ 0.9999 (0.5 is the equilateral arch)",
        )),
        (None, _) => Ok(None),
        (Some(e), "pointed") => {
            if !crate::analysis::forms::eccentricity_allowed(e.value) {
                return Err(cx.err(
                    Some(e.referenced),
                    "arch.eccentricity",
                    format!(
                        "value {} is not allowed: it must lie in {} (beyond, the critical \
                         thickness t/R_c ≈ 0.175 (1 − e) is below what the margins resolve)",
                        fmt_num(e.value),
                        crate::analysis::forms::ECCENTRICITY_RANGE
                    ),
                ));
            }
            Ok(Some(e.value))
        }
        (Some(e), _) => Err(cx.err(
            Some(e.referenced),
            "arch.eccentricity",
            format!(
                "value {} is not allowed: only a pointed arch has an eccentricity (add `shape: pointed`)",
                fmt_num(e.value)
            ),
        )),
    }
}

/// `radial` (the default) or `vertical` joints.
fn joints(a: &RawArch, cx: &Ctx) -> Result<JointOrientation, ManifestError> {
    match &a.joints {
        None => Ok(JointOrientation::Radial),
        Some(j) => JointOrientation::parse(&j.value).ok_or_else(|| {
            cx.err(
                Some(j.referenced),
                "arch.joints",
                format!("value {:?} is not allowed: use radial or vertical", j.value),
            )
        }),
    }
}

/// `annular` (the default) or `centreline` weight.
fn weight(a: &RawArch, cx: &Ctx) -> Result<WeightModel, ManifestError> {
    match &a.weight {
        None => Ok(WeightModel::Annular),
        Some(w) => WeightModel::parse(&w.value).ok_or_else(|| {
            cx.err(
                Some(w.referenced),
                "arch.weight",
                format!(
                    "value {:?} is not allowed: use annular or centreline",
                    w.value
                ),
            )
        }),
    }
}

/// `continuum` (the default) or a voussoir count.
fn voussoirs(a: &RawArch, cx: &Ctx) -> Result<Discretisation, ManifestError> {
    Ok(match &a.voussoirs {
        None => Discretisation::Continuum,
        Some(v) => match v.value {
            RawVoussoirs::Continuum => Discretisation::Continuum,
            RawVoussoirs::Count(n) => Discretisation::Voussoirs(check_voussoirs(
                n as f64,
                v.referenced,
                "arch.voussoirs",
                cx,
            )?),
        },
    })
}

fn check_half_angle(v: f64, at: Location, key: &str, cx: &Ctx) -> Result<f64, ManifestError> {
    if v > 0.0 && v < 180.0 {
        Ok(v)
    } else {
        Err(cx.err(
            Some(at),
            key,
            format!(
                "value {} is not allowed: the half-angle must lie in (0, 180) degrees",
                fmt_num(v)
            ),
        ))
    }
}

fn check_voussoirs(v: f64, at: Location, key: &str, cx: &Ctx) -> Result<u32, ManifestError> {
    if v.fract() == 0.0 && (1.0..=1e7).contains(&v) {
        Ok(v as u32)
    } else {
        Err(cx.err(
            Some(at),
            key,
            format!(
                "value {} is not allowed: the voussoir count must be an integer in [1, 10000000]",
                fmt_num(v)
            ),
        ))
    }
}
