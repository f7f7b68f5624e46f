//! Study manifests: YAML as typed (serde-saphyr, unknown keys rejected) turned into a
//! validated [`Manifest`]. Every error names the file, line and column, the key, the value
//! given and what is allowed.

use crate::model::{Discretisation, WeightModel, t_over_r_from_k};
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
                    "inf" | "+inf" | ".inf" | "infinity" | "Inf" | "INF" => {
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
}

/// One load case as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLoadCase {
    name: Spanned<String>,
    kind: Spanned<String>,
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
}

impl LoadKind {
    /// The manifest name.
    pub fn as_str(self) -> &'static str {
        match self {
            LoadKind::SelfWeight => "self_weight",
        }
    }
}

/// A named load case.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LoadCase {
    /// Unique name.
    pub name: String,
    /// Kind.
    pub kind: LoadKind,
}

/// The arch options common to every case (each may be overridden by a grid axis).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ArchOptions {
    /// `circular`.
    pub shape: &'static str,
    /// Half-embrace angle α in degrees.
    pub half_angle_deg: f64,
    /// `radial`.
    pub joints: &'static str,
    /// Weight model.
    pub weight: WeightModel,
    /// Continuum or voussoirs.
    #[serde(serialize_with = "ser_disc")]
    pub voussoirs: Discretisation,
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
    /// What each case computes.
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
        Some(f) => Find::parse(&f.value).ok_or_else(|| {
            cx.err(
                Some(f.referenced),
                "find",
                format!(
                    "value {:?} is not allowed: use state, thickness, friction or thrust",
                    f.value
                ),
            )
        })?,
    };
    let grid = validate_grid(raw.grid.as_ref(), find, cx)?;
    let load_cases = validate_load_cases(raw.load_cases.as_deref(), cx)?;
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

fn validate_arch(a: &RawArch, cx: &Ctx) -> Result<ArchOptions, ManifestError> {
    if let Some(s) = &a.shape
        && s.value != "circular"
    {
        return Err(cx.err(
            Some(s.referenced),
            "arch.shape",
            format!("value {:?} is not allowed: use circular", s.value),
        ));
    }
    if let Some(j) = &a.joints
        && j.value != "radial"
    {
        return Err(cx.err(
            Some(j.referenced),
            "arch.joints",
            format!("value {:?} is not allowed: use radial", j.value),
        ));
    }
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
        shape: "circular",
        half_angle_deg,
        joints: "radial",
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
        AxisName::Voussoirs => v.fract() == 0.0 && (1.0..=1e7).contains(&v),
    };
    if ok {
        return Ok(());
    }
    let allowed = match name {
        AxisName::K => "K = R/r must be a finite number greater than 1",
        AxisName::TOverR => "t/R_c must lie in (0, 2)",
        AxisName::Mu => "μ must be a number ≥ 0 or inf (NaN and negative values are not allowed)",
        AxisName::HalfAngleDeg => "the half-angle must lie in (0, 180) degrees",
        AxisName::Voussoirs => "the voussoir count must be an integer in [1, 10000000]",
    };
    Err(cx.err(
        Some(at),
        key,
        format!("value {} is not allowed: {allowed}", fmt_num(v)),
    ))
}

fn validate_grid(
    g: Option<&RawGrid>,
    find: Find,
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
    if find == Find::Thickness
        && let Some(a) = g.k.as_ref().or(g.t_over_r.as_ref())
    {
        return Err(cx.err(
            Some(a.referenced),
            "grid.k",
            "a `thickness` study finds K itself: remove the k / t_over_r axis",
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
    let mut axes = Vec::new();
    // Plan order, outermost first: geometry, then K, then μ innermost.
    for (name, ax) in [
        (AxisName::HalfAngleDeg, &g.half_angle_deg),
        (AxisName::Voussoirs, &g.voussoirs),
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
    if find.needs_k() && !has_k {
        return Err(ManifestError {
            path: cx.path.to_path_buf(),
            position: None,
            key: Some("grid".into()),
            message: format!("a `{find}` study needs a k (or t_over_r) axis"),
        });
    }
    if find.needs_mu() && !has_mu && find != Find::Thickness {
        return Err(ManifestError {
            path: cx.path.to_path_buf(),
            position: None,
            key: Some("grid".into()),
            message: format!(
                "a `{find}` study needs a mu axis (use values: [inf] for infinite friction)"
            ),
        });
    }
    Ok(axes)
}

fn validate_load_cases(
    l: Option<&[Spanned<RawLoadCase>]>,
    cx: &Ctx,
) -> Result<Vec<LoadCase>, ManifestError> {
    let Some(list) = l else {
        return Ok(vec![LoadCase {
            name: "self_weight".into(),
            kind: LoadKind::SelfWeight,
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
            other => {
                return Err(cx.err(
                    Some(lc.value.kind.referenced),
                    "load_cases.kind",
                    format!("value {other:?} is not allowed: use self_weight"),
                ));
            }
        };
        out.push(LoadCase {
            name: name.value.clone(),
            kind,
        });
    }
    Ok(out)
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
