//! Study manifests: YAML as typed (serde-saphyr, unknown keys rejected) turned into a
//! validated [`Manifest`]. Every error names the file, line and column, the key, the value
//! given and what is allowed.

use crate::model::{
    ArchForm, Discretisation, JointOrientation, Load, Shape, WeightModel, t_over_r_from_k,
};
use crate::scene::Find;
use serde::de::{self, Deserializer, Visitor};
use serde::{Deserialize, Serialize};
use serde_saphyr::{Location, Spanned};
use std::fmt;
use std::path::{Path, PathBuf};

/// A manifest that could not be read or is not valid.
#[derive(Debug, thiserror::Error)]
#[error("{}", self.render())]
pub struct ManifestError {
    /// The manifest file.
    pub path: PathBuf,
    /// 1-based line and column, when known.
    pub position: Option<(u64, u64)>,
    /// The key at fault (dotted path), when known.
    pub key: Option<String>,
    /// What is wrong, with the value given and what is allowed.
    pub message: String,
}

impl ManifestError {
    fn render(&self) -> String {
        let mut s = self.path.display().to_string();
        if let Some((l, c)) = self.position {
            s.push_str(&format!(":{l}:{c}"));
        }
        s.push_str(": ");
        if let Some(k) = &self.key {
            s.push_str(&format!("key `{k}`: "));
        }
        s.push_str(&self.message);
        s
    }
}

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
struct RawArch {
    shape: Option<Spanned<String>>,
    eccentricity: Option<Spanned<f64>>,
    half_angle_deg: Option<Spanned<f64>>,
    joints: Option<Spanned<String>>,
    weight: Option<Spanned<String>>,
    voussoirs: Option<Spanned<RawVoussoirs>>,
}

/// One grid axis as written: `{from, to, steps}` or `{values: [...]}`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawAxis {
    from: Option<Spanned<Number>>,
    to: Option<Spanned<Number>>,
    steps: Option<Spanned<i64>>,
    values: Option<Vec<Spanned<Number>>>,
}

/// The `grid:` block as written.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawGrid {
    k: Option<Spanned<RawAxis>>,
    t_over_r: Option<Spanned<RawAxis>>,
    mu: Option<Spanned<RawAxis>>,
    half_angle_deg: Option<Spanned<RawAxis>>,
    voussoirs: Option<Spanned<RawAxis>>,
    at_deg: Option<Spanned<RawAxis>>,
}

/// One load case as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLoadCase {
    name: Spanned<String>,
    kind: Spanned<String>,
    at_deg: Option<Spanned<f64>>,
    lambda: Option<Spanned<f64>>,
    find: Option<Spanned<String>>,
}

/// A scene listed for drawing.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScene {
    k: Option<Spanned<f64>>,
    t_over_r: Option<Spanned<f64>>,
    mu: Spanned<Number>,
}

/// Boundary location settings as written.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBoundaries {
    tolerance: Option<Spanned<f64>>,
}

/// The manifest as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawManifest {
    name: Spanned<String>,
    title: Option<String>,
    description: Option<String>,
    #[serde(default)]
    arch: RawArch,
    grid: Option<RawGrid>,
    load_cases: Option<Vec<Spanned<RawLoadCase>>>,
    find: Option<Spanned<String>>,
    scenes: Option<Vec<Spanned<RawScene>>>,
    boundaries: Option<RawBoundaries>,
}

/// The kind of a load case.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LoadKind {
    /// Self-weight only (symmetric).
    SelfWeight,
    /// Self-weight and a horizontal body force λ·(weight) toward +x.
    Horizontal,
    /// Self-weight and a vertical point load λ·W_total on the extrados at `at_deg`.
    Point,
}

impl LoadKind {
    /// The manifest name.
    pub fn as_str(self) -> &'static str {
        match self {
            LoadKind::SelfWeight => "self_weight",
            LoadKind::Horizontal => "horizontal",
            LoadKind::Point => "point",
        }
    }

    /// True when the load case has a live part scaled by λ.
    pub fn is_live(self) -> bool {
        self != LoadKind::SelfWeight
    }
}

/// A named load case.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LoadCase {
    /// Unique name.
    pub name: String,
    /// Kind.
    pub kind: LoadKind,
    /// Position of a point load, degrees from the crown (`None` when the grid has an
    /// `at_deg` axis, and for other kinds).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub at_deg: Option<f64>,
    /// The given load factor λ of the live part (state, thickness and friction studies).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda: Option<f64>,
    /// What the cases of this load case compute: the load case's own `find`, or the study's.
    pub find: Find,
}

impl LoadCase {
    /// The load of this case, with the position `at_deg` of a point load when the grid gives
    /// it.
    pub fn load(&self, axis_at_deg: Option<f64>) -> Load {
        match self.kind {
            LoadKind::SelfWeight => Load::SelfWeight,
            LoadKind::Horizontal => Load::Horizontal,
            LoadKind::Point => Load::Point {
                at_deg: self.at_deg.or(axis_at_deg).unwrap_or(0.0),
            },
        }
    }

    /// True when the cases of this load case span the grid axis `axis`: every axis but the
    /// ones its find finds itself (K for `thickness`, μ for `friction`, both for
    /// `thresholds`).
    pub fn spans(&self, axis: AxisName) -> bool {
        match axis {
            AxisName::K | AxisName::TOverR => self.find.needs_k(),
            AxisName::Mu => self.find.needs_mu(),
            AxisName::HalfAngleDeg | AxisName::Voussoirs | AxisName::AtDeg => true,
        }
    }
}

/// The arch options common to every case (each may be overridden by a grid axis).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ArchOptions {
    /// `circular` or `pointed`.
    pub shape: &'static str,
    /// Eccentricity e of a pointed arch.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub eccentricity: Option<f64>,
    /// Half-embrace angle α in degrees.
    pub half_angle_deg: f64,
    /// `radial` or `vertical`.
    pub joints: &'static str,
    /// Weight model.
    pub weight: WeightModel,
    /// Continuum or voussoirs.
    #[serde(serialize_with = "ser_disc")]
    pub voussoirs: Discretisation,
}

impl ArchOptions {
    /// The outline and joint planes.
    pub fn form(&self) -> ArchForm {
        ArchForm {
            shape: match self.eccentricity {
                Some(eccentricity) if self.shape == "pointed" => Shape::Pointed { eccentricity },
                _ => Shape::Circular,
            },
            joints: JointOrientation::parse(self.joints).unwrap_or_default(),
        }
    }
}

fn ser_disc<S: serde::Serializer>(d: &Discretisation, s: S) -> Result<S::Ok, S::Error> {
    match d {
        Discretisation::Continuum => s.serialize_str("continuum"),
        Discretisation::Voussoirs(n) => s.serialize_u32(*n),
    }
}

/// Which parameter a grid axis spans.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum AxisName {
    /// Thickness ratio K.
    K,
    /// t/R_c (converted to K).
    TOverR,
    /// Friction coefficient.
    Mu,
    /// Half-embrace angle in degrees.
    HalfAngleDeg,
    /// Voussoir count.
    Voussoirs,
    /// Position of a point load, degrees from the crown (an influence line).
    AtDeg,
}

impl AxisName {
    /// The manifest key.
    pub fn as_str(self) -> &'static str {
        match self {
            AxisName::K => "k",
            AxisName::TOverR => "t_over_r",
            AxisName::Mu => "mu",
            AxisName::HalfAngleDeg => "half_angle_deg",
            AxisName::Voussoirs => "voussoirs",
            AxisName::AtDeg => "at_deg",
        }
    }
}

/// A validated grid axis: its values in the order they are run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GridAxis {
    /// The parameter.
    pub name: AxisName,
    /// Values (μ may be infinite).
    pub values: Vec<f64>,
}

/// A scene (K, μ) the report draws.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SceneSpec {
    /// K = R/r.
    pub k: f64,
    /// μ (may be infinite).
    pub mu: f64,
}

/// A validated study manifest.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Manifest {
    /// Study name ([A-Za-z0-9_-]+), names the run directory.
    pub name: String,
    /// Title for reports.
    pub title: Option<String>,
    /// Description for reports.
    pub description: Option<String>,
    /// Arch options.
    pub arch: ArchOptions,
    /// Grid axes, in plan order (outermost first).
    pub grid: Vec<GridAxis>,
    /// Load cases.
    pub load_cases: Vec<LoadCase>,
    /// What each case computes, unless its load case names its own find
    /// ([`LoadCase::find`]).
    pub find: Find,
    /// Scenes to draw.
    pub scenes: Vec<SceneSpec>,
    /// Tolerance for locating boundaries, in K and μ.
    pub boundary_tolerance: f64,
}

/// Default tolerance for boundary location.
pub const DEFAULT_BOUNDARY_TOLERANCE: f64 = 1e-9;

struct Ctx<'a> {
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
        ManifestError {
            path: path.to_path_buf(),
            position,
            key: None,
            message: first,
        }
    })?;
    validate(raw, &Ctx { path })
}

fn validate(raw: RawManifest, cx: &Ctx) -> Result<Manifest, ManifestError> {
    if !is_valid_name(&raw.name.value) {
        return Err(cx.err(
            Some(raw.name.referenced),
            "name",
            format!(
                "value {:?} is not allowed: use letters, digits, `_` and `-` only",
                raw.name.value
            ),
        ));
    }
    let arch = validate_arch(&raw.arch, cx)?;
    let find = match &raw.find {
        None => Find::State,
        Some(f) => parse_find(f, "find", cx)?,
    };
    let load_cases = validate_load_cases(raw.load_cases.as_deref(), find, cx)?;
    let grid = validate_grid(raw.grid.as_ref(), &load_cases, cx)?;
    check_loads(&raw, &arch, &grid, &load_cases, cx)?;
    let mut scenes = Vec::new();
    for s in raw.scenes.iter().flatten() {
        let k = match (&s.value.k, &s.value.t_over_r) {
            (Some(k), None) => {
                if !(k.value > 1.0 && k.value.is_finite()) {
                    return Err(cx.err(
                        Some(k.referenced),
                        "scenes.k",
                        format!("value {} is not allowed: K must be > 1", k.value),
                    ));
                }
                k.value
            }
            (None, Some(t)) => {
                if !(t.value > 0.0 && t.value < 2.0) {
                    return Err(cx.err(
                        Some(t.referenced),
                        "scenes.t_over_r",
                        format!("value {} is not allowed: t/R_c must lie in (0, 2)", t.value),
                    ));
                }
                crate::model::k_from_t_over_r(t.value)
            }
            _ => {
                return Err(cx.err(
                    Some(s.referenced),
                    "scenes",
                    "each scene needs exactly one of k or t_over_r, and mu",
                ));
            }
        };
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
    let boundary_tolerance = match raw.boundaries.as_ref().and_then(|b| b.tolerance.as_ref()) {
        None => DEFAULT_BOUNDARY_TOLERANCE,
        Some(t) => {
            if !(t.value > 0.0 && t.value <= 1e-2) {
                return Err(cx.err(
                    Some(t.referenced),
                    "boundaries.tolerance",
                    format!("value {} is not allowed: it must lie in (0, 0.01]", t.value),
                ));
            }
            t.value.max(1e-13)
        }
    };
    Ok(Manifest {
        name: raw.name.value,
        title: raw.title,
        description: raw.description,
        arch,
        grid,
        load_cases,
        find,
        scenes,
        boundary_tolerance,
    })
}

fn parse_find(f: &Spanned<String>, key: &str, cx: &Ctx) -> Result<Find, ManifestError> {
    Find::parse(&f.value).ok_or_else(|| {
        cx.err(
            Some(f.referenced),
            key,
            format!(
                "value {:?} is not allowed: use state, thickness, friction, thrust, thresholds or load_factor",
                f.value
            ),
        )
    })
}

fn validate_arch(a: &RawArch, cx: &Ctx) -> Result<ArchOptions, ManifestError> {
    let shape: &'static str = match a.shape.as_ref().map(|s| s.value.as_str()) {
        None | Some("circular") => "circular",
        Some("pointed") => "pointed",
        Some(other) => {
            return Err(cx.err(
                a.shape.as_ref().map(|s| s.referenced),
                "arch.shape",
                format!("value {other:?} is not allowed: use circular or pointed"),
            ));
        }
    };
    let eccentricity = match (&a.eccentricity, shape) {
        (None, "pointed") => {
            return Err(cx.err(
                a.shape.as_ref().map(|s| s.referenced),
                "arch.eccentricity",
                "a pointed arch needs `eccentricity: e` with 0 ≤ e < 1 (0.5 is the equilateral arch)",
            ));
        }
        (None, _) => None,
        (Some(e), "pointed") => {
            if !(0.0..1.0).contains(&e.value) {
                return Err(cx.err(
                    Some(e.referenced),
                    "arch.eccentricity",
                    format!(
                        "value {} is not allowed: it must lie in [0, 1)",
                        fmt_num(e.value)
                    ),
                ));
            }
            Some(e.value)
        }
        (Some(e), _) => {
            return Err(cx.err(
                Some(e.referenced),
                "arch.eccentricity",
                format!(
                    "value {} is not allowed: only a pointed arch has an eccentricity (add `shape: pointed`)",
                    fmt_num(e.value)
                ),
            ));
        }
    };
    let joints = match &a.joints {
        None => JointOrientation::Radial,
        Some(j) => JointOrientation::parse(&j.value).ok_or_else(|| {
            cx.err(
                Some(j.referenced),
                "arch.joints",
                format!("value {:?} is not allowed: use radial or vertical", j.value),
            )
        })?,
    };
    let half_angle_deg = match &a.half_angle_deg {
        None => 90.0,
        Some(h) => check_half_angle(h.value, h.referenced, "arch.half_angle_deg", cx)?,
    };
    let weight = match &a.weight {
        None => WeightModel::Annular,
        Some(w) => WeightModel::parse(&w.value).ok_or_else(|| {
            cx.err(
                Some(w.referenced),
                "arch.weight",
                format!(
                    "value {:?} is not allowed: use annular or centreline",
                    w.value
                ),
            )
        })?,
    };
    let voussoirs = match &a.voussoirs {
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
    };
    Ok(ArchOptions {
        shape,
        eccentricity,
        half_angle_deg,
        joints: joints.as_str(),
        weight,
        voussoirs,
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

/// Largest number of steps of one axis.
pub const MAX_AXIS_STEPS: i64 = 100_000;

fn axis_values(name: AxisName, ax: &Spanned<RawAxis>, cx: &Ctx) -> Result<Vec<f64>, ManifestError> {
    let key = format!("grid.{}", name.as_str());
    let a = &ax.value;
    let values = match (&a.values, &a.from, &a.to, &a.steps) {
        (Some(vals), None, None, None) => {
            if vals.is_empty() {
                return Err(cx.err(
                    Some(ax.referenced),
                    &key,
                    "the list `values` is empty: give at least one value",
                ));
            }
            let mut out = Vec::with_capacity(vals.len());
            for v in vals {
                check_value(name, v.value.0, v.referenced, &format!("{key}.values"), cx)?;
                if out.contains(&v.value.0) {
                    return Err(cx.err(
                        Some(v.referenced),
                        &format!("{key}.values"),
                        format!(
                            "value {} is repeated: each value may appear once",
                            fmt_num(v.value.0)
                        ),
                    ));
                }
                out.push(v.value.0);
            }
            out
        }
        (None, Some(from), Some(to), Some(steps)) => {
            if steps.value < 1 || steps.value > MAX_AXIS_STEPS {
                return Err(cx.err(Some(steps.referenced), &format!("{key}.steps"), format!("value {} is not allowed: steps must be an integer in [1, {MAX_AXIS_STEPS}]", steps.value)));
            }
            let (f, t) = (from.value.0, to.value.0);
            check_value(name, f, from.referenced, &format!("{key}.from"), cx)?;
            check_value(name, t, to.referenced, &format!("{key}.to"), cx)?;
            if !f.is_finite() || !t.is_finite() {
                return Err(cx.err(
                    Some(from.referenced),
                    &key,
                    "a range needs finite `from` and `to`; list infinite values under `values`",
                ));
            }
            if t < f {
                return Err(cx.err(
                    Some(to.referenced),
                    &format!("{key}.to"),
                    format!("the range is reversed: from = {f} > to = {t}; give from ≤ to"),
                ));
            }
            if steps.value > 1 && t == f {
                return Err(cx.err(Some(to.referenced), &format!("{key}.to"), format!("the range is empty: from = to = {f} with {} steps; widen it or use steps: 1", steps.value)));
            }
            let n = steps.value as usize;
            let vals: Vec<f64> = if n == 1 {
                vec![f]
            } else {
                (0..n)
                    .map(|i| {
                        if i + 1 == n {
                            t
                        } else {
                            f + (t - f) * (i as f64) / ((n - 1) as f64)
                        }
                    })
                    .collect()
            };
            if name == AxisName::Voussoirs {
                for &v in &vals {
                    if v.fract() != 0.0 {
                        return Err(cx.err(Some(steps.referenced), &key, format!("the range gives a non-integer voussoir count {v}; choose from, to and steps so that every value is an integer, or use `values`")));
                    }
                }
            }
            vals
        }
        _ => {
            return Err(cx.err(
                Some(ax.referenced),
                &key,
                "an axis is either {from, to, steps} (all three) or {values: [...]}",
            ));
        }
    };
    Ok(values)
}

fn check_value(
    name: AxisName,
    v: f64,
    at: Location,
    key: &str,
    cx: &Ctx,
) -> Result<(), ManifestError> {
    let ok = match name {
        AxisName::K => v > 1.0 && v.is_finite(),
        AxisName::TOverR => v > 0.0 && v < 2.0,
        AxisName::Mu => v >= 0.0,
        AxisName::HalfAngleDeg => v > 0.0 && v < 180.0,
        AxisName::Voussoirs => {
            v.is_infinite() && v > 0.0 || v.fract() == 0.0 && (1.0..=1e7).contains(&v)
        }
        AxisName::AtDeg => v.is_finite() && v.abs() < 180.0,
    };
    if ok {
        return Ok(());
    }
    let allowed = match name {
        AxisName::K => "K = R/r must be a finite number greater than 1",
        AxisName::TOverR => "t/R_c must lie in (0, 2)",
        AxisName::Mu => "μ must be a number ≥ 0 or inf (NaN and negative values are not allowed)",
        AxisName::HalfAngleDeg => "the half-angle must lie in (0, 180) degrees",
        AxisName::Voussoirs => {
            "the voussoir count must be an integer in [1, 10000000], or `continuum`"
        }
        AxisName::AtDeg => "the position of a point load must lie in (−180, 180) degrees",
    };
    Err(cx.err(
        Some(at),
        key,
        format!("value {} is not allowed: {allowed}", fmt_num(v)),
    ))
}

fn validate_grid(
    g: Option<&RawGrid>,
    lcs: &[LoadCase],
    cx: &Ctx,
) -> Result<Vec<GridAxis>, ManifestError> {
    let empty = RawGrid::default();
    let g = g.unwrap_or(&empty);
    if let (Some(_), Some(t)) = (&g.k, &g.t_over_r) {
        return Err(cx.err(
            Some(t.referenced),
            "grid.t_over_r",
            "give either a k axis or a t_over_r axis, not both",
        ));
    }
    // The distinct finds of the load cases, in order of first appearance.
    let mut finds: Vec<Find> = Vec::new();
    for lc in lcs {
        if !finds.contains(&lc.find) {
            finds.push(lc.find);
        }
    }
    let spanned = |axis: AxisName| lcs.iter().any(|lc| lc.spans(axis));
    if let [find] = finds[..] {
        if find == Find::Thickness
            && let Some(a) = g.k.as_ref().or(g.t_over_r.as_ref())
        {
            return Err(cx.err(
                Some(a.referenced),
                "grid.k",
                "a `thickness` study finds K itself: remove the k / t_over_r axis",
            ));
        }
        if find == Find::Thresholds
            && let Some(a) = g.k.as_ref().or(g.t_over_r.as_ref()).or(g.mu.as_ref())
        {
            return Err(cx.err(
                Some(a.referenced),
                "grid",
                "a `thresholds` study finds K and μ itself: remove the k, t_over_r and mu axes",
            ));
        }
        if find == Find::Friction
            && let Some(a) = &g.mu
        {
            return Err(cx.err(
                Some(a.referenced),
                "grid.mu",
                "a `friction` study finds μ itself: remove the mu axis",
            ));
        }
    }
    for (name, ax) in [
        (AxisName::K, &g.k),
        (AxisName::TOverR, &g.t_over_r),
        (AxisName::Mu, &g.mu),
    ] {
        if let Some(ax) = ax
            && !spanned(name)
        {
            let finds: Vec<&str> = finds.iter().map(|f| f.as_str()).collect();
            return Err(cx.err(
                Some(ax.referenced),
                &format!("grid.{}", name.as_str()),
                format!(
                    "no load case uses this axis: their finds ({}) find {} themselves; remove the axis",
                    finds.join(", "),
                    if name == AxisName::Mu { "μ" } else { "K" }
                ),
            ));
        }
    }
    let mut axes = Vec::new();
    // Plan order, outermost first: geometry, then K, then μ innermost.
    for (name, ax) in [
        (AxisName::HalfAngleDeg, &g.half_angle_deg),
        (AxisName::Voussoirs, &g.voussoirs),
        (AxisName::AtDeg, &g.at_deg),
        (AxisName::K, &g.k),
        (AxisName::TOverR, &g.t_over_r),
        (AxisName::Mu, &g.mu),
    ] {
        if let Some(ax) = ax {
            axes.push(GridAxis {
                name,
                values: axis_values(name, ax, cx)?,
            });
        }
    }
    let has_k = axes
        .iter()
        .any(|a| matches!(a.name, AxisName::K | AxisName::TOverR));
    let has_mu = axes.iter().any(|a| a.name == AxisName::Mu);
    // Which study needs the axis: the whole study when every load case has the same find.
    let whose = |lc: &LoadCase| {
        if finds.len() == 1 {
            format!("a `{}` study", lc.find)
        } else {
            format!("load case {:?} (find {})", lc.name, lc.find)
        }
    };
    for lc in lcs {
        if lc.find.needs_k() && !has_k {
            return Err(ManifestError {
                path: cx.path.to_path_buf(),
                position: None,
                key: Some("grid".into()),
                message: format!("{} needs a k (or t_over_r) axis", whose(lc)),
            });
        }
        if lc.find.needs_mu() && !has_mu && lc.find != Find::Thickness {
            return Err(ManifestError {
                path: cx.path.to_path_buf(),
                position: None,
                key: Some("grid".into()),
                message: format!(
                    "{} needs a mu axis (use values: [inf] for infinite friction)",
                    whose(lc)
                ),
            });
        }
    }
    Ok(axes)
}

fn validate_load_cases(
    l: Option<&[Spanned<RawLoadCase>]>,
    find: Find,
    cx: &Ctx,
) -> Result<Vec<LoadCase>, ManifestError> {
    let Some(list) = l else {
        return Ok(vec![LoadCase {
            name: "self_weight".into(),
            kind: LoadKind::SelfWeight,
            at_deg: None,
            lambda: None,
            find,
        }]);
    };
    if list.is_empty() {
        return Err(ManifestError {
            path: cx.path.to_path_buf(),
            position: None,
            key: Some("load_cases".into()),
            message: "the list is empty: give at least one load case or omit the key".into(),
        });
    }
    let mut out: Vec<LoadCase> = Vec::new();
    for lc in list {
        let name = &lc.value.name;
        if !is_valid_name(&name.value) {
            return Err(cx.err(
                Some(name.referenced),
                "load_cases.name",
                format!(
                    "value {:?} is not allowed: use letters, digits, `_` and `-` only",
                    name.value
                ),
            ));
        }
        if out.iter().any(|o| o.name == name.value) {
            return Err(cx.err(
                Some(name.referenced),
                "load_cases.name",
                format!(
                    "value {:?} is a duplicate: load-case names must be unique",
                    name.value
                ),
            ));
        }
        let kind = match lc.value.kind.value.as_str() {
            "self_weight" => LoadKind::SelfWeight,
            "horizontal" => LoadKind::Horizontal,
            "point" => LoadKind::Point,
            other => {
                return Err(cx.err(
                    Some(lc.value.kind.referenced),
                    "load_cases.kind",
                    format!("value {other:?} is not allowed: use self_weight, horizontal or point"),
                ));
            }
        };
        if let Some(a) = &lc.value.at_deg {
            if kind != LoadKind::Point {
                return Err(cx.err(
                    Some(a.referenced),
                    "load_cases.at_deg",
                    format!(
                        "value {} is not allowed: only a `point` load case has a position (load case {:?} is {})",
                        fmt_num(a.value),
                        name.value,
                        kind.as_str()
                    ),
                ));
            }
            if !(a.value.is_finite() && a.value.abs() < 180.0) {
                return Err(cx.err(
                    Some(a.referenced),
                    "load_cases.at_deg",
                    format!(
                        "value {} is not allowed: the position must lie in (−180, 180) degrees",
                        fmt_num(a.value)
                    ),
                ));
            }
        }
        if let Some(l) = &lc.value.lambda {
            if kind == LoadKind::SelfWeight {
                return Err(cx.err(
                    Some(l.referenced),
                    "load_cases.lambda",
                    format!(
                        "value {} is not allowed: load case {:?} is self_weight, which has no live part to scale",
                        fmt_num(l.value),
                        name.value
                    ),
                ));
            }
            if !(l.value >= 0.0 && l.value.is_finite()) {
                return Err(cx.err(
                    Some(l.referenced),
                    "load_cases.lambda",
                    format!(
                        "value {} is not allowed: the load factor λ must be a finite number ≥ 0",
                        fmt_num(l.value)
                    ),
                ));
            }
        }
        out.push(LoadCase {
            name: name.value.clone(),
            kind,
            at_deg: lc.value.at_deg.as_ref().map(|a| a.value),
            lambda: lc.value.lambda.as_ref().map(|l| l.value),
            find: match &lc.value.find {
                None => find,
                Some(f) => parse_find(f, "load_cases.find", cx)?,
            },
        });
    }
    Ok(out)
}

/// Cross-checks of the load cases against the find, the grid and the form; every message
/// names the key and the value at fault.
fn check_loads(
    raw: &RawManifest,
    arch: &ArchOptions,
    grid: &[GridAxis],
    lcs: &[LoadCase],
    cx: &Ctx,
) -> Result<(), ManifestError> {
    let raw_lcs: &[Spanned<RawLoadCase>] = raw.load_cases.as_deref().unwrap_or(&[]);
    let raw_grid = raw.grid.as_ref();
    let at_axis = raw_grid.and_then(|g| g.at_deg.as_ref());
    let values = |n: AxisName| grid.iter().find(|a| a.name == n).map(|a| a.values.clone());
    let alphas = values(AxisName::HalfAngleDeg).unwrap_or_else(|| vec![arch.half_angle_deg]);
    let alpha_min = alphas.iter().copied().fold(f64::INFINITY, f64::min);
    let alpha_max = alphas.iter().copied().fold(0.0, f64::max);
    let form = arch.form();
    let kind_at = |i: usize| raw_lcs.get(i).map(|l| l.value.kind.referenced);
    let case_at = |i: usize| raw_lcs.get(i).map(|l| l.referenced);
    for (i, lc) in lcs.iter().enumerate() {
        let live = lc.kind.is_live();
        let find = lc.find;
        if find == Find::LoadFactor && !live {
            return Err(cx.err(
                kind_at(i),
                "load_cases.kind",
                format!(
                    "load case {:?} is self_weight: a load_factor study needs a live load (horizontal or point)",
                    lc.name
                ),
            ));
        }
        if matches!(find, Find::Thrust | Find::Thresholds) && live {
            return Err(cx.err(
                kind_at(i),
                "load_cases.kind",
                format!(
                    "load case {:?} is {}: a {find} study is defined for self_weight only",
                    lc.name,
                    lc.kind.as_str()
                ),
            ));
        }
        let lambda_at = raw_lcs
            .get(i)
            .and_then(|l| l.value.lambda.as_ref())
            .map(|l| l.referenced);
        match (live, find, lc.lambda) {
            (true, Find::LoadFactor, Some(l)) => {
                return Err(cx.err(
                    lambda_at,
                    "load_cases.lambda",
                    format!(
                        "value {} is not allowed: a load_factor study finds λ itself; remove `lambda` from load case {:?}",
                        fmt_num(l),
                        lc.name
                    ),
                ));
            }
            (true, f, None) if f != Find::LoadFactor => {
                return Err(cx.err(
                    case_at(i),
                    "load_cases.lambda",
                    format!(
                        "load case {:?} ({}) needs its load factor in a `{f}` study: add `lambda: L` (L ≥ 0), or use `find: load_factor`",
                        lc.name,
                        lc.kind.as_str()
                    ),
                ));
            }
            _ => {}
        }
        match (lc.kind, at_axis, lc.at_deg) {
            (LoadKind::Point, Some(_), Some(a)) => {
                let at = raw_lcs
                    .get(i)
                    .and_then(|l| l.value.at_deg.as_ref())
                    .map(|a| a.referenced);
                return Err(cx.err(
                    at,
                    "load_cases.at_deg",
                    format!(
                        "value {} is not allowed: the grid's at_deg axis gives the position of load case {:?}; remove one of them",
                        fmt_num(a),
                        lc.name
                    ),
                ));
            }
            (LoadKind::Point, None, None) => {
                return Err(cx.err(
                    case_at(i),
                    "load_cases.at_deg",
                    format!(
                        "point load case {:?} needs its position: add `at_deg: DEG` (degrees from the crown, in [−α, α]) or a grid axis `at_deg`",
                        lc.name
                    ),
                ));
            }
            (kind, Some(ax), _) if kind != LoadKind::Point => {
                return Err(cx.err(
                    Some(ax.referenced),
                    "grid.at_deg",
                    format!(
                        "an at_deg axis positions point loads, but load case {:?} is {}: give it a study of its own",
                        lc.name,
                        kind.as_str()
                    ),
                ));
            }
            _ => {}
        }
    }
    if let Some(find) = lcs
        .iter()
        .map(|lc| lc.find)
        .find(|f| matches!(f, Find::Thrust | Find::Thresholds))
        && !form.is_circular_radial()
    {
        return Err(cx.err(
            raw.arch
                .shape
                .as_ref()
                .or(raw.arch.joints.as_ref())
                .map(|s| s.referenced),
            "find",
            format!("a {find} study is defined for the circular arch with radial joints only"),
        ));
    }
    if form.joints == JointOrientation::Vertical && alpha_max > 90.0 {
        return Err(cx.err(
            raw.arch.joints.as_ref().map(|j| j.referenced),
            "arch.joints",
            format!(
                "value \"vertical\" is not allowed with a half-angle of {}°: vertical joints need α ≤ 90° (beyond, a vertical plane through the intrados crosses the opening)",
                fmt_num(alpha_max)
            ),
        ));
    }
    // Positions of point loads with where they were written.
    let mut positions: Vec<(f64, Option<Location>, &str)> = Vec::new();
    for (i, lc) in lcs.iter().enumerate() {
        if let Some(a) = lc.at_deg {
            let at = raw_lcs
                .get(i)
                .and_then(|l| l.value.at_deg.as_ref())
                .map(|a| a.referenced);
            positions.push((a, at, "load_cases.at_deg"));
        }
    }
    if let (Some(ax), Some(vals)) = (at_axis, values(AxisName::AtDeg)) {
        for v in vals {
            positions.push((v, Some(ax.referenced), "grid.at_deg"));
        }
    }
    for &(a, at, key) in &positions {
        if a.abs() > alpha_min {
            return Err(cx.err(
                at,
                key,
                format!(
                    "value {} is not allowed: a point load must lie on the arch, in [−{alpha_min}, {alpha_min}] degrees (the half-angle)",
                    fmt_num(a)
                ),
            ));
        }
    }
    if let Shape::Pointed { eccentricity: e } = form.shape
        && e > 0.0
    {
        let k_axis = raw_grid.and_then(|g| g.k.as_ref().or(g.t_over_r.as_ref()));
        let ks = grid
            .iter()
            .find(|a| matches!(a.name, AxisName::K | AxisName::TOverR))
            .map(|a| {
                a.values
                    .iter()
                    .map(|&v| {
                        if a.name == AxisName::TOverR {
                            crate::model::k_from_t_over_r(v)
                        } else {
                            v
                        }
                    })
                    .collect::<Vec<_>>()
            });
        if let Some(ks) = ks {
            let k_top = ks.iter().copied().fold(1.0, f64::max);
            for &alpha in &alphas {
                let k_lim = form.max_k(alpha.to_radians());
                if k_top >= k_lim {
                    return Err(cx.err(
                        k_axis.map(|a| a.referenced),
                        "grid.k",
                        format!(
                            "value K = {k_top} is not allowed: a pointed arch with eccentricity {e} and half-angle {alpha}° exists only for K < {k_lim} (its intrados arcs must meet above the springings)"
                        ),
                    ));
                }
            }
            // ψ₁ = asin(e(1 + K)/2) grows with K: the thickest arch has the largest keystone.
            let psi_1 = (e * 0.5 * (1.0 + k_top)).min(1.0).asin().to_degrees();
            for &(a, at, key) in &positions {
                if a != 0.0 && a.abs() < psi_1 {
                    return Err(cx.err(
                        at,
                        key,
                        format!(
                            "value {} is not allowed: a point load must sit at a joint, and this pointed arch has none between its crown (0°) and ±{psi_1:.6}° at K = {k_top}",
                            fmt_num(a)
                        ),
                    ));
                }
            }
        }
    }
    Ok(())
}

impl Manifest {
    /// The K values of the grid (converted from t/R_c when given so), if any.
    pub fn k_values(&self) -> Option<Vec<f64>> {
        self.grid.iter().find_map(|a| match a.name {
            AxisName::K => Some(a.values.clone()),
            AxisName::TOverR => Some(
                a.values
                    .iter()
                    .map(|&x| crate::model::k_from_t_over_r(x))
                    .collect(),
            ),
            _ => None,
        })
    }

    /// t/R_c for a K value.
    pub fn t_over_r(k: f64) -> f64 {
        t_over_r_from_k(k)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(s: &str) -> Result<Manifest, ManifestError> {
        parse(s, Path::new("study.yaml"))
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
