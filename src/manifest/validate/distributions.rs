//! The distributions of the `uncertain:` block, each checked as written: its name, its own
//! keys and their values, and its support against the values its parameter may take.

use super::{Ctx, fmt_num};
use super::{MAX_AXIS_STEPS, MAX_K};
use crate::manifest::error::ManifestError;
use crate::manifest::raw::{RawAxis, RawDistribution, RawParam};
use crate::manifest::types::ArchOptions;
use crate::manifest::uncertain::ParamName;
use crate::model::t_over_r_from_k;
use crate::sampling::Distribution;
use serde_saphyr::{Location, Spanned};

/// The values a parameter may take: a closed range for continuous distributions (whose
/// samples never hit an end of their support), with the ends a discrete value may take.
pub(super) struct Allowed {
    lo: f64,
    hi: f64,
    /// The ends themselves allowed as discrete values.
    lo_inclusive: bool,
    hi_inclusive: bool,
    text: String,
}

pub(super) fn allowed(name: ParamName, arch: &ArchOptions, alpha_lo: f64) -> Allowed {
    let t_max = t_over_r_from_k(MAX_K);
    let (lo, hi, lo_inc, hi_inc, text) = match name {
        ParamName::K => (1.0, MAX_K, false, true, format!("(1, {MAX_K}]")),
        ParamName::TOverR => (0.0, t_max, false, true, format!("(0, {t_max:.4}]")),
        ParamName::Mu => (0.0, f64::INFINITY, true, true, "[0, inf]".to_string()),
        ParamName::HalfAngleDeg => (0.0, 180.0, false, false, "(0, 180) degrees".into()),
        ParamName::Eccentricity => (
            0.0,
            crate::analysis::forms::MAX_ECCENTRICITY,
            true,
            true,
            crate::analysis::forms::ECCENTRICITY_RANGE.into(),
        ),
        ParamName::Voussoirs => (
            1.0,
            f64::INFINITY,
            true,
            true,
            "integers ≥ 1 or continuum".into(),
        ),
        ParamName::AtDeg => {
            let a = alpha_lo.min(arch.half_angle_deg);
            (
                -a,
                a,
                true,
                true,
                format!("[−{a}, {a}] degrees (within the half-angle)"),
            )
        }
        ParamName::AtX => (0.0, 1.0, true, true, "[0, 1]".into()),
        ParamName::Lambda => (0.0, f64::INFINITY, true, false, "[0, inf)".into()),
    };
    Allowed {
        lo,
        hi,
        lo_inclusive: lo_inc,
        hi_inclusive: hi_inc,
        text,
    }
}

/// The values of an axis of a distribution's parameter (`{values: [...]}` or
/// `{from, to, steps}`), in their order; `key` names it in messages.
fn param_axis(ax: &RawAxis, at: Location, key: &str, cx: &Ctx) -> Result<Vec<f64>, ManifestError> {
    let values = match (&ax.values, &ax.from, &ax.to, &ax.steps, &ax.also) {
        (Some(v), None, None, None, None) if !v.is_empty() => {
            v.iter().map(|x| x.value.0).collect::<Vec<f64>>()
        }
        (None, Some(f), Some(t), Some(n), None)
            if (1..=MAX_AXIS_STEPS).contains(&n.value)
                && f.value.0.is_finite()
                && t.value.0.is_finite() =>
        {
            super::grid::decimal_range(f.value.0, t.value.0, n.value as usize)
        }
        _ => {
            return Err(cx.err(
                Some(at),
                key,
                format!(
                    "a distribution's parameter is a number, or an axis of values \
                     {{values: [...]}} or {{from, to, steps}} (finite ends, 1 to \
                     {MAX_AXIS_STEPS} steps): each grid point then has its own distribution"
                ),
            ));
        }
    };
    if let Some(v) = values.iter().find(|v| !v.is_finite()) {
        return Err(cx.err(
            Some(at),
            key,
            format!(
                "value {} is not allowed: a distribution's parameter is finite",
                fmt_num(*v)
            ),
        ));
    }
    if let Some(v) = repeated(&values) {
        return Err(cx.err(
            Some(at),
            key,
            format!("value {} is listed twice", fmt_num(v)),
        ));
    }
    Ok(values)
}

/// A value that stands twice in `values`, if one does.
fn repeated(values: &[f64]) -> Option<f64> {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    sorted.windows(2).find(|w| w[0] == w[1]).map(|w| w[0])
}

/// The parameters of a distribution given as axes, with their values: (field, values).
pub(super) fn distribution_axes(
    name: ParamName,
    d: &Spanned<RawDistribution>,
    cx: &Ctx,
) -> Result<Vec<(&'static str, Vec<f64>)>, ManifestError> {
    let r = &d.value;
    let fields: [(&'static str, &Option<Spanned<RawParam>>); 8] = [
        ("mean", &r.mean),
        ("sd", &r.sd),
        ("median", &r.median),
        ("cov", &r.cov),
        ("from", &r.from),
        ("to", &r.to),
        ("alpha", &r.alpha),
        ("beta", &r.beta),
    ];
    let mut out = Vec::new();
    for (field, v) in fields {
        if let Some(Spanned {
            value: RawParam::Axis(ax),
            referenced,
            ..
        }) = v
        {
            let key = format!("uncertain.{}.{field}", name.as_str());
            out.push((field, param_axis(ax, *referenced, &key, cx)?));
        }
    }
    Ok(out)
}

/// The distribution as written, with its parameters checked.
pub(super) fn distribution(
    name: ParamName,
    d: &Spanned<RawDistribution>,
    over: Option<(&str, f64)>,
    cx: &Ctx,
) -> Result<Distribution, ManifestError> {
    let r = &d.value;
    let base = format!("uncertain.{}", name.as_str());
    let kind = r.distribution.value.as_str();
    // The keys each distribution takes; any other key given is refused.
    let keys: &[&str] = match kind {
        "normal" => &["mean", "sd"],
        "lognormal" => &["median", "cov", "mean", "sd"],
        "uniform" => &["from", "to"],
        "truncated_normal" => &["mean", "sd", "from", "to"],
        "beta" => &["alpha", "beta", "from", "to"],
        "discrete" => &["values", "weights"],
        other => {
            return Err(cx.err(
                Some(r.distribution.referenced),
                &format!("{base}.distribution"),
                format!(
                    "value {other:?} is not allowed: use normal, lognormal, uniform, \
                     truncated_normal, beta or discrete"
                ),
            ));
        }
    };
    check_keys(d, (kind, keys), &base, cx)?;
    let c = Checker {
        d,
        base: &base,
        kind,
        keys,
        over,
        cx,
    };
    let (need, positive, finite) = (
        |k: &str, v: Option<f64>| c.need(k, v),
        |k: &str, v: f64| c.positive(k, v),
        |k: &str, v: f64| c.finite(k, v),
    );
    let range = |from: f64, to: f64| c.range(from, to);
    Ok(match kind {
        "normal" => Distribution::Normal {
            mean: finite("mean", need("mean", c.num("mean", &r.mean))?)?,
            sd: positive("sd", need("sd", c.num("sd", &r.sd))?)?,
        },
        "lognormal" => match (
            c.num("median", &r.median),
            c.num("cov", &r.cov),
            c.num("mean", &r.mean),
            c.num("sd", &r.sd),
        ) {
            (Some(m), Some(c), None, None) => {
                Distribution::lognormal_from_median_cov(positive("median", m)?, positive("cov", c)?)
            }
            (None, None, Some(m), Some(s)) => {
                Distribution::lognormal_from_mean_sd(positive("mean", m)?, positive("sd", s)?)
            }
            _ => {
                return Err(cx.err(
                    Some(d.referenced),
                    &base,
                    "a lognormal distribution is given by `median` and `cov` (coefficient of \
                     variation), or by `mean` and `sd`",
                ));
            }
        },
        "uniform" => {
            let from = finite("from", need("from", c.num("from", &r.from))?)?;
            let to = finite("to", need("to", c.num("to", &r.to))?)?;
            let (from, to) = range(from, to)?;
            Distribution::Uniform { from, to }
        }
        "truncated_normal" => truncated_normal(&c)?,
        "beta" => {
            let alpha = positive("alpha", need("alpha", c.num("alpha", &r.alpha))?)?;
            let beta = positive("beta", need("beta", c.num("beta", &r.beta))?)?;
            let from = finite("from", c.num("from", &r.from).unwrap_or(0.0))?;
            let to = finite("to", c.num("to", &r.to).unwrap_or(1.0))?;
            let (from, to) = range(from, to)?;
            Distribution::Beta {
                alpha,
                beta,
                from,
                to,
            }
        }
        _ => discrete(r, &base, d.referenced, cx)?,
    })
}

/// The messages of one distribution's parameters.
struct Checker<'a> {
    d: &'a Spanned<RawDistribution>,
    base: &'a str,
    kind: &'a str,
    keys: &'a [&'a str],
    /// A parameter given as an axis, at one of its values.
    over: Option<(&'a str, f64)>,
    cx: &'a Ctx<'a>,
}

impl Checker<'_> {
    /// The value of a parameter: the override, the number written, or an axis's first value.
    fn num(&self, field: &str, v: &Option<Spanned<RawParam>>) -> Option<f64> {
        if let Some((f, x)) = self.over
            && f == field
        {
            return Some(x);
        }
        match &v.as_ref()?.value {
            RawParam::Value(n) => Some(n.0),
            RawParam::Axis(ax) => match (&ax.values, &ax.from) {
                (Some(vals), _) => vals.first().map(|x| x.value.0),
                (None, Some(f)) => Some(f.value.0),
                _ => None,
            },
        }
    }

    fn need(&self, key: &str, v: Option<f64>) -> Result<f64, ManifestError> {
        v.ok_or_else(|| {
            self.cx.err(
                Some(self.d.referenced),
                &format!("{}.{key}", self.base),
                format!(
                    "a {} distribution needs `{key}` (it takes {})",
                    self.kind,
                    self.keys.join(", ")
                ),
            )
        })
    }

    fn bad(&self, key: &str, v: f64, rule: &str) -> ManifestError {
        self.cx.err(
            Some(self.d.referenced),
            &format!("{}.{key}", self.base),
            format!("value {} is not allowed: {rule}", fmt_num(v)),
        )
    }

    fn positive(&self, key: &str, v: f64) -> Result<f64, ManifestError> {
        if v > 0.0 && v.is_finite() {
            Ok(v)
        } else {
            Err(self.bad(key, v, "it must be a finite number > 0"))
        }
    }

    fn finite(&self, key: &str, v: f64) -> Result<f64, ManifestError> {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.bad(key, v, "it must be a finite number"))
        }
    }

    fn range(&self, from: f64, to: f64) -> Result<(f64, f64), ManifestError> {
        if from.is_nan() || to.is_nan() || from >= to {
            Err(self.bad(
                "to",
                to,
                &format!("`to` must be greater than `from` ({})", fmt_num(from)),
            ))
        } else {
            Ok((from, to))
        }
    }
}

/// A truncated normal: `mean`, `sd` and at least one bound, keeping some of the mass.
fn truncated_normal(c: &Checker) -> Result<Distribution, ManifestError> {
    let r = &c.d.value;
    let mean = c.finite("mean", c.need("mean", c.num("mean", &r.mean))?)?;
    let sd = c.positive("sd", c.need("sd", c.num("sd", &r.sd))?)?;
    if r.from.is_none() && r.to.is_none() {
        return Err(c.cx.err(
            Some(c.d.referenced),
            &format!("{}.from", c.base),
            "a truncated normal distribution needs `from`, `to` or both (the bounds of its \
             truncation)",
        ));
    }
    let from = c.num("from", &r.from).unwrap_or(f64::NEG_INFINITY);
    let to = c.num("to", &r.to).unwrap_or(f64::INFINITY);
    let (from, to) = c.range(from, to)?;
    // A truncation that keeps almost none of the normal's mass is a mistake.
    let z = |x: f64| (x - mean) / sd;
    if z(from) > 37.0 || z(to) < -37.0 {
        return Err(c.bad(
            "from",
            from,
            "the truncation keeps no probability of the normal distribution (its bounds lie \
             more than 37 sd from the mean)",
        ));
    }
    Ok(Distribution::TruncatedNormal { mean, sd, from, to })
}

/// Every key given is one of the distribution's own.
fn check_keys(
    d: &Spanned<RawDistribution>,
    (kind, keys): (&str, &[&str]),
    base: &str,
    cx: &Ctx,
) -> Result<(), ManifestError> {
    let r = &d.value;
    let given: [(&str, Option<Location>); 11] = [
        ("mean", r.mean.as_ref().map(|v| v.referenced)),
        ("sd", r.sd.as_ref().map(|v| v.referenced)),
        ("median", r.median.as_ref().map(|v| v.referenced)),
        ("cov", r.cov.as_ref().map(|v| v.referenced)),
        ("from", r.from.as_ref().map(|v| v.referenced)),
        ("to", r.to.as_ref().map(|v| v.referenced)),
        ("alpha", r.alpha.as_ref().map(|v| v.referenced)),
        ("beta", r.beta.as_ref().map(|v| v.referenced)),
        ("values", r.values.as_ref().map(|_| d.referenced)),
        ("weights", r.weights.as_ref().map(|_| d.referenced)),
        ("distribution", None),
    ];
    for (key, at) in given {
        if let Some(at) = at
            && !keys.contains(&key)
        {
            return Err(cx.err(
                Some(at),
                &format!("{base}.{key}"),
                format!(
                    "`{key}` is not a parameter of a {kind} distribution: give {}",
                    keys.join(", ")
                ),
            ));
        }
    }
    Ok(())
}

/// A discrete distribution: distinct values, with weights ≥ 0 summing to more than 0 (equal
/// weights when none are given).
fn discrete(
    r: &RawDistribution,
    base: &str,
    at: Location,
    cx: &Ctx,
) -> Result<Distribution, ManifestError> {
    let values: Vec<f64> = match &r.values {
        Some(v) if !v.is_empty() => v.iter().map(|x| x.value.0).collect(),
        _ => {
            return Err(cx.err(
                Some(at),
                &format!("{base}.values"),
                "a discrete distribution needs `values: [...]` (at least one value)",
            ));
        }
    };
    if let Some(v) = values.iter().find(|v| v.is_nan()) {
        return Err(cx.err(
            Some(at),
            &format!("{base}.values"),
            format!(
                "value {} is not allowed: values must be numbers",
                fmt_num(*v)
            ),
        ));
    }
    if let Some(v) = repeated(&values) {
        return Err(cx.err(
            Some(at),
            &format!("{base}.values"),
            format!(
                "value {} is listed twice: each value once, with its weight",
                fmt_num(v)
            ),
        ));
    }
    let weights: Vec<f64> = match &r.weights {
        None => vec![1.0; values.len()],
        Some(w) => {
            if w.len() != values.len() {
                return Err(cx.err(
                    Some(at),
                    &format!("{base}.weights"),
                    format!(
                        "{} weights for {} values: give one weight per value",
                        w.len(),
                        values.len()
                    ),
                ));
            }
            if let Some(bad) = w.iter().find(|x| !(x.value >= 0.0 && x.value.is_finite())) {
                return Err(cx.err(
                    Some(bad.referenced),
                    &format!("{base}.weights"),
                    format!(
                        "value {} is not allowed: a weight is a finite number ≥ 0",
                        fmt_num(bad.value)
                    ),
                ));
            }
            w.iter().map(|x| x.value).collect()
        }
    };
    if weights.iter().sum::<f64>() <= 0.0 {
        return Err(cx.err(
            Some(at),
            &format!("{base}.weights"),
            "the weights sum to 0: give at least one value a positive weight",
        ));
    }
    Ok(Distribution::discrete(values, weights))
}

/// The support of a distribution lies within the values its parameter may take.
pub(super) fn check_support(
    dist: &Distribution,
    allowed: &Allowed,
    (d, key): (&Spanned<RawDistribution>, &str),
    cx: &Ctx,
) -> Result<(), ManifestError> {
    let (lo, hi) = dist.support();
    let inside = match dist {
        Distribution::Discrete { values, .. } => values.iter().all(|&v| {
            (v > allowed.lo || (allowed.lo_inclusive && v == allowed.lo))
                && (v < allowed.hi || (allowed.hi_inclusive && v == allowed.hi))
        }),
        // Continuous: the samples never hit an end of the support (an infinite one least of
        // all), which may close the range.
        _ => lo >= allowed.lo && hi <= allowed.hi,
    };
    if inside {
        return Ok(());
    }
    let hint = match dist {
        Distribution::Normal { .. } => {
            "; a normal distribution takes every real value: use truncated_normal with `from` \
             and `to`, or lognormal for a positive parameter"
        }
        Distribution::LogNormal { .. } => "; use truncated_normal or beta with bounds inside it",
        _ => "",
    };
    Err(cx.err(
        Some(d.referenced),
        key,
        format!(
            "the {} distribution takes values in [{}, {}], which leaves the values {} may take, \
             {}{hint}",
            dist.name(),
            fmt_num(lo),
            fmt_num(hi),
            key.trim_start_matches("uncertain."),
            allowed.text
        ),
    ))
}

/// A voussoir count is an integer (or continuum): only a discrete distribution gives one.
pub(super) fn check_voussoir_counts(
    dist: &Distribution,
    d: &Spanned<RawDistribution>,
    cx: &Ctx,
) -> Result<(), ManifestError> {
    let Distribution::Discrete { values, .. } = dist else {
        return Err(cx.err(
            Some(d.referenced),
            "uncertain.voussoirs",
            format!(
                "a voussoir count is an integer: use a discrete distribution (values with \
                 weights), not {}",
                dist.name()
            ),
        ));
    };
    if let Some(v) = values
        .iter()
        .find(|v| v.is_finite() && (v.fract() != 0.0 || **v > 1e7))
    {
        return Err(cx.err(
            Some(d.referenced),
            "uncertain.voussoirs.values",
            format!(
                "value {} is not allowed: the voussoir count must be an integer in [1, 10000000] \
                 or continuum",
                fmt_num(*v)
            ),
        ));
    }
    Ok(())
}
