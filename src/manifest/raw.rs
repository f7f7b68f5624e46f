//! The manifest as written: serde types that mirror the YAML (unknown keys rejected), with
//! the location of every value kept for the messages of the validation.

use serde::de::{self, Deserializer, Visitor};
use serde::{Deserialize, Serialize};
use serde_saphyr::Spanned;
use std::fmt;

/// A number that may be written `inf` (for μ).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Number(pub f64);

impl<'de> Deserialize<'de> for Number {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl Visitor<'_> for V {
            type Value = Number;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a number or `inf`")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Number, E> {
                Ok(Number(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Number, E> {
                Ok(Number(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Number, E> {
                Ok(Number(v as f64))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Number, E> {
                match v.trim() {
                    // `continuum` is the voussoir count N → ∞.
                    "inf" | "+inf" | ".inf" | "infinity" | "Inf" | "INF" | "continuum" => {
                        Ok(Number(f64::INFINITY))
                    }
                    other => other.parse::<f64>().map(Number).map_err(|_| {
                        E::invalid_value(de::Unexpected::Str(v), &"a number or `inf`")
                    }),
                }
            }
        }
        d.deserialize_any(V)
    }
}

/// Voussoirs as written: `continuum` or an integer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RawVoussoirs {
    /// `continuum`.
    Continuum,
    /// An integer (validated later).
    Count(i64),
}

impl<'de> Deserialize<'de> for RawVoussoirs {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl Visitor<'_> for V {
            type Value = RawVoussoirs;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("`continuum` or an integer ≥ 1")
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<RawVoussoirs, E> {
                Ok(RawVoussoirs::Count(v))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<RawVoussoirs, E> {
                Ok(RawVoussoirs::Count(i64::try_from(v).unwrap_or(i64::MAX)))
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<RawVoussoirs, E> {
                if v.fract() == 0.0 && v.abs() < 1e15 {
                    Ok(RawVoussoirs::Count(v as i64))
                } else {
                    Err(E::invalid_value(de::Unexpected::Float(v), &self))
                }
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<RawVoussoirs, E> {
                match v {
                    "continuum" => Ok(RawVoussoirs::Continuum),
                    _ => Err(E::invalid_value(de::Unexpected::Str(v), &self)),
                }
            }
        }
        d.deserialize_any(V)
    }
}

/// The `arch:` block as written.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawArch {
    pub(super) shape: Option<Spanned<String>>,
    pub(super) eccentricity: Option<Spanned<f64>>,
    pub(super) half_angle_deg: Option<Spanned<f64>>,
    pub(super) joints: Option<Spanned<String>>,
    pub(super) keystone: Option<Spanned<bool>>,
    pub(super) weight: Option<Spanned<String>>,
    pub(super) voussoirs: Option<Spanned<RawVoussoirs>>,
}

/// One grid axis as written: `{from, to, steps}` (with `also: [...]` values added to the
/// range) or `{values: [...]}`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawAxis {
    pub(super) from: Option<Spanned<Number>>,
    pub(super) to: Option<Spanned<Number>>,
    pub(super) steps: Option<Spanned<i64>>,
    pub(super) values: Option<Vec<Spanned<Number>>>,
    /// Values added to a range, e.g. `also: [inf]` beside `{from: 0.2, to: 0.8, steps: 13}`.
    pub(super) also: Option<Vec<Spanned<Number>>>,
}

/// An axis of names, `{values: [radial, vertical]}`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawNamesAxis {
    pub(super) values: Vec<Spanned<String>>,
}

/// The `grid:` block as written.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawGrid {
    pub(super) k: Option<Spanned<RawAxis>>,
    pub(super) t_over_r: Option<Spanned<RawAxis>>,
    pub(super) mu: Option<Spanned<RawAxis>>,
    pub(super) half_angle_deg: Option<Spanned<RawAxis>>,
    pub(super) eccentricity: Option<Spanned<RawAxis>>,
    pub(super) joints: Option<Spanned<RawNamesAxis>>,
    pub(super) voussoirs: Option<Spanned<RawAxis>>,
    pub(super) at_deg: Option<Spanned<RawAxis>>,
    pub(super) at_x: Option<Spanned<RawAxis>>,
}

/// One load case as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawLoadCase {
    pub(super) name: Spanned<String>,
    pub(super) kind: Spanned<String>,
    pub(super) at_deg: Option<Spanned<f64>>,
    pub(super) at_x: Option<Spanned<f64>>,
    pub(super) width: Option<Spanned<f64>>,
    pub(super) lambda: Option<Spanned<f64>>,
    pub(super) find: Option<Spanned<String>>,
}

/// A scene listed for drawing.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawScene {
    pub(super) k: Option<Spanned<f64>>,
    pub(super) t_over_r: Option<Spanned<f64>>,
    pub(super) mu: Spanned<Number>,
}

/// Boundary location settings as written.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawBoundaries {
    pub(super) tolerance: Option<Spanned<f64>>,
}

/// Figure options as written.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawFigures {
    pub(super) width: Option<Spanned<String>>,
}

/// An author of a study as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawAuthor {
    pub(super) name: String,
    pub(super) orcid: Option<String>,
    pub(super) affiliation: Option<String>,
}

/// The manifest as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawManifest {
    pub(super) name: Spanned<String>,
    pub(super) title: Option<String>,
    pub(super) description: Option<String>,
    pub(super) authors: Option<Vec<Spanned<RawAuthor>>>,
    pub(super) license: Option<Spanned<String>>,
    #[serde(default)]
    pub(super) arch: RawArch,
    pub(super) grid: Option<RawGrid>,
    pub(super) load_cases: Option<Vec<Spanned<RawLoadCase>>>,
    pub(super) find: Option<Spanned<String>>,
    pub(super) scenes: Option<Vec<Spanned<RawScene>>>,
    pub(super) boundaries: Option<RawBoundaries>,
    pub(super) figures: Option<RawFigures>,
    pub(super) uncertain: Option<Spanned<RawUncertain>>,
    pub(super) samples: Option<Spanned<RawSamples>>,
}

/// A parameter of a distribution as written: a number, or an axis of values (each grid point
/// then has its own distribution).
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub(super) enum RawParam {
    /// One value.
    Value(Number),
    /// `{values: [...]}` or `{from, to, steps}`.
    Axis(Box<RawAxis>),
}

/// One uncertain parameter as written: a distribution by name and its parameters.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawDistribution {
    pub(super) distribution: Spanned<String>,
    pub(super) mean: Option<Spanned<RawParam>>,
    pub(super) sd: Option<Spanned<RawParam>>,
    pub(super) median: Option<Spanned<RawParam>>,
    pub(super) cov: Option<Spanned<RawParam>>,
    pub(super) from: Option<Spanned<RawParam>>,
    pub(super) to: Option<Spanned<RawParam>>,
    pub(super) alpha: Option<Spanned<RawParam>>,
    pub(super) beta: Option<Spanned<RawParam>>,
    pub(super) values: Option<Vec<Spanned<Number>>>,
    pub(super) weights: Option<Vec<Spanned<f64>>>,
}

/// A correlation between two uncertain parameters as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawCorrelation {
    pub(super) between: Spanned<Vec<String>>,
    pub(super) value: Spanned<f64>,
}

/// The `uncertain:` block as written: a distribution for each uncertain parameter.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawUncertain {
    pub(super) k: Option<Spanned<RawDistribution>>,
    pub(super) t_over_r: Option<Spanned<RawDistribution>>,
    pub(super) mu: Option<Spanned<RawDistribution>>,
    pub(super) half_angle_deg: Option<Spanned<RawDistribution>>,
    pub(super) eccentricity: Option<Spanned<RawDistribution>>,
    pub(super) voussoirs: Option<Spanned<RawDistribution>>,
    pub(super) at_deg: Option<Spanned<RawDistribution>>,
    pub(super) at_x: Option<Spanned<RawDistribution>>,
    pub(super) lambda: Option<Spanned<RawDistribution>>,
    pub(super) correlation: Option<Spanned<RawCorrelation>>,
}

/// The `samples:` block as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSamples {
    pub(super) n: Option<Spanned<i64>>,
    pub(super) method: Option<Spanned<String>>,
    pub(super) seed: Option<Spanned<i64>>,
    pub(super) bootstrap: Option<Spanned<i64>>,
}
