//! The `uncertain:` and `samples:` blocks of a sampling study: each distribution checked
//! against the parameter it describes (its support must lie in the values the parameter may
//! take), the correlation, the sample design, and how the study's load cases fit the question.

use super::distributions::{
    allowed, check_support, check_voussoir_counts, distribution, distribution_axes,
};
use super::{Ctx, fmt_num};
use crate::manifest::error::ManifestError;
use crate::manifest::raw::{RawDistribution, RawManifest, RawUncertain};
use crate::manifest::types::{ArchOptions, AxisName, GridAxis, LoadCase, LoadKind};
use crate::manifest::uncertain::{
    Correlation, DEFAULT_BOOTSTRAP, DEFAULT_SAMPLES, DistributionAxis, ParamName, Question,
    Sampling, UncertainParam, with_field,
};
use crate::sampling::{Distribution, MAX_DIMS, Method};
use crate::scene::Find;
use serde_saphyr::Spanned;

/// Largest number of samples of a study (the sensitivity design multiplies it by d + 2).
pub const MAX_SAMPLES: i64 = 1 << 32;

/// Largest number of bootstrap resamples of the Sobol indices.
pub const MAX_BOOTSTRAP: i64 = 100_000;

/// A validated sampling study, with what the other checks need to know of it.
pub(super) struct Validated {
    /// The sampling.
    pub sampling: Sampling,
    /// For the checks of the grid and the loads only: an axis for each uncertain parameter
    /// that a grid axis could span, holding the extreme values its distribution takes.
    pub shadow: Vec<GridAxis>,
}

/// The raw distribution of each parameter, in [`ParamName::ALL`] order.
fn raw_params(u: &RawUncertain) -> Vec<(ParamName, &Spanned<RawDistribution>)> {
    let fields = [
        &u.k,
        &u.t_over_r,
        &u.mu,
        &u.half_angle_deg,
        &u.eccentricity,
        &u.voussoirs,
        &u.at_deg,
        &u.at_x,
        &u.lambda,
    ];
    ParamName::ALL
        .into_iter()
        .zip(fields)
        .filter_map(|(n, f)| f.as_ref().map(|f| (n, f)))
        .collect()
}

/// Validates the sampling of a study whose `find` is `question`, and sets the find of each
/// load case (the state at its λ, or the largest load factor).
pub(super) fn validate(
    raw: &RawManifest,
    question: Question,
    arch: &ArchOptions,
    load_cases: &mut [LoadCase],
    cx: &Ctx,
) -> Result<Validated, ManifestError> {
    let find_at = raw.find.as_ref().map(|f| f.referenced);
    let Some(u) = &raw.uncertain else {
        return Err(cx.err(
            find_at,
            "uncertain",
            format!(
                "a `{question}` study needs an `uncertain:` block giving a distribution to at least \
                 one parameter, e.g. `mu: {{distribution: uniform, from: 0.3, to: 0.5}}`"
            ),
        ));
    };
    if let Some((i, lc)) = raw
        .load_cases
        .iter()
        .flatten()
        .enumerate()
        .find_map(|(i, lc)| lc.value.find.as_ref().map(|f| (i, f)))
    {
        return Err(cx.err(
            Some(lc.referenced),
            "load_cases.find",
            format!(
                "load case {:?} has its own find, but a `{question}` study analyses every load \
                 case for its question: remove `find` from the load case",
                load_cases[i].name
            ),
        ));
    }
    let list = raw_params(&u.value);
    if list.is_empty() {
        return Err(cx.err(
            Some(u.referenced),
            "uncertain",
            "the block gives no distribution: give one to at least one of k, t_over_r, mu, \
             half_angle_deg, eccentricity, voussoirs, at_deg, at_x, lambda",
        ));
    }
    if list.len() > MAX_DIMS / 2 {
        return Err(cx.err(
            Some(u.referenced),
            "uncertain",
            "too many uncertain parameters",
        ));
    }
    check_exclusive(raw, &list, cx)?;
    check_fits_study(raw, question, arch, load_cases, &list, cx)?;
    // Positions lie within the smallest half-angle an uncertain α takes.
    let alpha_lo = match list.iter().find(|(n, _)| *n == ParamName::HalfAngleDeg) {
        Some((_, d)) => {
            distribution(ParamName::HalfAngleDeg, d, None, cx)?
                .support()
                .0
        }
        None => arch.half_angle_deg,
    };
    let (params, axes) = params_of(&list, arch, alpha_lo, cx)?;
    check_thickness_and_friction(raw, question, &list, cx)?;
    let correlation = match &u.value.correlation {
        None => None,
        Some(c) => Some(correlation(c, &params, question, cx)?),
    };
    let (n, method, seed, bootstrap) = samples(raw, question, cx)?;
    for lc in load_cases.iter_mut() {
        // The checks of the loads and the grid see a state or load-factor study: the
        // thickness find of the self-weight margin finds K, which a sampling study gives.
        lc.find = match question.scene_find(lc.kind) {
            Find::Thickness => Find::State,
            f => f,
        };
    }
    let shadow = shadow_axes(&params, &axes);
    Ok(Validated {
        sampling: Sampling {
            question,
            params,
            correlation,
            n,
            method,
            seed,
            bootstrap,
            axes,
        },
        shadow,
    })
}

/// The distribution of each uncertain parameter, checked against the values it may take,
/// and the parameters of distributions given as axes.
fn params_of(
    list: &[(ParamName, &Spanned<RawDistribution>)],
    arch: &ArchOptions,
    alpha_lo: f64,
    cx: &Ctx,
) -> Result<(Vec<UncertainParam>, Vec<DistributionAxis>), ManifestError> {
    let mut params = Vec::new();
    let mut axes = Vec::new();
    for (name, d) in list {
        let key = format!("uncertain.{}", name.as_str());
        let dist = distribution(*name, d, None, cx)?;
        check_support(&dist, &allowed(*name, arch, alpha_lo), (d, &key), cx)?;
        if *name == ParamName::Voussoirs {
            check_voussoir_counts(&dist, d, cx)?;
        }
        // Each value of a parameter given as an axis makes a distribution of its own.
        for (field, values) in distribution_axes(*name, d, cx)? {
            for &v in &values {
                let at = distribution(*name, d, Some((field, v)), cx)?;
                check_support(&at, &allowed(*name, arch, alpha_lo), (d, &key), cx)?;
            }
            axes.push(DistributionAxis {
                param: params.len(),
                field,
                values,
            });
        }
        params.push(UncertainParam {
            name: *name,
            distribution: dist,
        });
    }
    Ok((params, axes))
}

/// A parameter is uncertain or a grid axis, not both; K is given one way.
fn check_exclusive(
    raw: &RawManifest,
    list: &[(ParamName, &Spanned<RawDistribution>)],
    cx: &Ctx,
) -> Result<(), ManifestError> {
    let has = |n: ParamName| list.iter().find(|(p, _)| *p == n).map(|(_, d)| d);
    if let (Some(_), Some(t)) = (has(ParamName::K), has(ParamName::TOverR)) {
        return Err(cx.err(
            Some(t.referenced),
            "uncertain.t_over_r",
            "give the thickness one way: an uncertain k or an uncertain t_over_r, not both",
        ));
    }
    if let (Some(_), Some(x)) = (has(ParamName::AtDeg), has(ParamName::AtX)) {
        return Err(cx.err(
            Some(x.referenced),
            "uncertain.at_x",
            "give the load position one way: an uncertain at_deg or an uncertain at_x, not both",
        ));
    }
    let Some(g) = &raw.grid else {
        return Ok(());
    };
    let thickness_axis = g.k.is_some() || g.t_over_r.is_some();
    let position_axis = g.at_deg.is_some() || g.at_x.is_some();
    for (name, d) in list {
        let on_grid = match name {
            ParamName::K | ParamName::TOverR => thickness_axis,
            ParamName::Mu => g.mu.is_some(),
            ParamName::HalfAngleDeg => g.half_angle_deg.is_some(),
            ParamName::Voussoirs => g.voussoirs.is_some(),
            ParamName::AtDeg | ParamName::AtX => position_axis,
            ParamName::Eccentricity | ParamName::Lambda => false,
        };
        if on_grid {
            return Err(cx.err(
                Some(d.referenced),
                &format!("uncertain.{}", name.as_str()),
                format!(
                    "{} is both uncertain and a grid axis: give it a distribution or grid values, \
                     not both",
                    name.as_str()
                ),
            ));
        }
    }
    Ok(())
}

/// The load cases fit the question and the uncertain parameters: a fragility curve is of a
/// live load; an uncertain λ or position replaces the load case's own; an eccentricity is
/// of a pointed arch.
fn check_fits_study(
    raw: &RawManifest,
    question: Question,
    arch: &ArchOptions,
    load_cases: &[LoadCase],
    list: &[(ParamName, &Spanned<RawDistribution>)],
    cx: &Ctx,
) -> Result<(), ManifestError> {
    let at = |i: usize| load_case_at(raw, i);
    if question == Question::Fragility
        && let Some((i, lc)) = load_cases
            .iter()
            .enumerate()
            .find(|(_, l)| !l.kind.is_live())
    {
        return Err(cx.err(
            at(i),
            "load_cases.kind",
            format!(
                "load case {:?} is self_weight: a fragility curve is the distribution of the \
                 largest load factor of a live load (horizontal or point); use `find: \
                 probability` for self-weight",
                lc.name
            ),
        ));
    }
    let has = |n: ParamName| list.iter().any(|(p, _)| *p == n);
    if question == Question::Probability
        && !has(ParamName::Lambda)
        && let Some((i, lc)) = load_cases
            .iter()
            .enumerate()
            .find(|(_, l)| l.kind.is_live() && l.lambda.is_none())
    {
        return Err(cx.err(
            at(i),
            "load_cases.lambda",
            format!(
                "load case {:?} ({}) needs the load factor the probability is asked at: add \
                 `lambda: L` (L ≥ 0) to it or give an uncertain lambda; `find: fragility` gives \
                 the distribution of its largest load factor instead",
                lc.name,
                lc.kind.as_str()
            ),
        ));
    }
    for &(name, d) in list {
        check_param_fits((raw, question, arch), load_cases, (name, d), cx)?;
    }
    Ok(())
}

/// Where load case `i` is written.
fn load_case_at(raw: &RawManifest, i: usize) -> Option<serde_saphyr::Location> {
    raw.load_cases
        .as_ref()
        .and_then(|l| l.get(i))
        .map(|l| l.referenced)
}

/// One uncertain parameter fits the load cases and the arch (see [`check_fits_study`]).
fn check_param_fits(
    (raw, question, arch): (&RawManifest, Question, &ArchOptions),
    load_cases: &[LoadCase],
    (name, d): (ParamName, &Spanned<RawDistribution>),
    cx: &Ctx,
) -> Result<(), ManifestError> {
    let at = |i: usize| load_case_at(raw, i);
    let key = format!("uncertain.{}", name.as_str());
    match name {
        ParamName::Lambda => {
            if question != Question::Probability {
                return Err(cx.err(
                    Some(d.referenced),
                    &key,
                    format!(
                        "a `{question}` study finds the largest load factor λ_max itself: \
                         remove the uncertain lambda (a probability study asks whether the \
                         arch stands at an uncertain λ)"
                    ),
                ));
            }
            if let Some((i, lc)) = load_cases
                .iter()
                .enumerate()
                .find(|(_, l)| l.lambda.is_some())
            {
                return Err(cx.err(
                    at(i),
                    "load_cases.lambda",
                    format!(
                        "load case {:?} gives its own lambda, but λ is uncertain: remove one \
                         of them",
                        lc.name
                    ),
                ));
            }
            if !load_cases.iter().any(|l| l.kind.is_live()) {
                return Err(cx.err(
                    Some(d.referenced),
                    &key,
                    "λ scales a live load, and the study has none: add a horizontal or point \
                     load case",
                ));
            }
        }
        ParamName::AtDeg | ParamName::AtX => {
            if let Some((i, lc)) = load_cases
                .iter()
                .enumerate()
                .find(|(_, l)| l.at_deg.is_some() || l.at_x.is_some())
            {
                return Err(cx.err(
                    at(i),
                    "load_cases.at_deg",
                    format!(
                        "load case {:?} gives its own position, but the position is \
                         uncertain: remove one of them",
                        lc.name
                    ),
                ));
            }
            if let Some(lc) = load_cases.iter().find(|l| l.kind != LoadKind::Point) {
                return Err(cx.err(
                    Some(d.referenced),
                    &key,
                    format!(
                        "an uncertain position places point loads, but load case {:?} is {}: \
                         give it a study of its own",
                        lc.name,
                        lc.kind.as_str()
                    ),
                ));
            }
        }
        ParamName::Eccentricity if arch.shape != "pointed" => {
            return Err(cx.err(
                Some(d.referenced),
                &key,
                "only a pointed arch has an eccentricity: add `shape: pointed` (and its \
                 nominal `eccentricity`) to the arch",
            ));
        }
        _ => {}
    }
    Ok(())
}

/// Each sample is analysed at its K and μ: each is an uncertain parameter or a grid axis.
fn check_thickness_and_friction(
    raw: &RawManifest,
    question: Question,
    list: &[(ParamName, &Spanned<RawDistribution>)],
    cx: &Ctx,
) -> Result<(), ManifestError> {
    let has = |n: ParamName| list.iter().any(|(p, _)| *p == n);
    let grid = raw.grid.as_ref();
    let k_given = has(ParamName::K)
        || has(ParamName::TOverR)
        || grid.is_some_and(|g| g.k.is_some() || g.t_over_r.is_some());
    let mu_given = has(ParamName::Mu) || grid.is_some_and(|g| g.mu.is_some());
    if !k_given || !mu_given {
        let missing = if k_given {
            "μ: a mu grid axis or an uncertain mu"
        } else {
            "K: a k (or t_over_r) grid axis or an uncertain k (or t_over_r)"
        };
        return Err(cx.err_unplaced(
            "uncertain",
            format!(
                "a `{question}` study analyses each sample at its K and μ, and needs {missing}"
            ),
        ));
    }
    Ok(())
}

fn correlation(
    c: &Spanned<crate::manifest::raw::RawCorrelation>,
    params: &[UncertainParam],
    question: Question,
    cx: &Ctx,
) -> Result<Correlation, ManifestError> {
    let key = "uncertain.correlation";
    if question == Question::Sensitivity {
        return Err(cx.err(
            Some(c.referenced),
            key,
            "Sobol indices apportion the variance among independent parameters: a sensitivity \
             study takes no correlation",
        ));
    }
    let names = &c.value.between.value;
    let index = |s: &str| params.iter().position(|p| p.name.as_str() == s);
    let (first, second) = match names.as_slice() {
        [a, b] if a != b => match (index(a), index(b)) {
            (Some(i), Some(j)) => (i, j),
            _ => {
                let missing = if index(a).is_none() { a } else { b };
                return Err(cx.err(
                    Some(c.value.between.referenced),
                    &format!("{key}.between"),
                    format!(
                        "{missing:?} is not an uncertain parameter of this study: name two of {}",
                        params
                            .iter()
                            .map(|p| p.name.as_str())
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                ));
            }
        },
        _ => {
            return Err(cx.err(
                Some(c.value.between.referenced),
                &format!("{key}.between"),
                "name two different uncertain parameters, e.g. `between: [k, mu]`",
            ));
        }
    };
    let v = c.value.value.value;
    if !(v > -1.0 && v < 1.0) {
        return Err(cx.err(
            Some(c.value.value.referenced),
            &format!("{key}.value"),
            format!(
                "value {} is not allowed: a correlation lies in (−1, 1)",
                fmt_num(v)
            ),
        ));
    }
    Ok(Correlation {
        first,
        second,
        value: v,
    })
}

/// `samples: {n, method, seed, bootstrap}`: n ≥ 2 (≥ 8 for Sobol indices), the method, a
/// seed ≥ 0.
fn samples(
    raw: &RawManifest,
    question: Question,
    cx: &Ctx,
) -> Result<(u64, Method, u64, u64), ManifestError> {
    let Some(s) = &raw.samples else {
        return Ok((DEFAULT_SAMPLES, Method::Sobol, 0, DEFAULT_BOOTSTRAP));
    };
    let least = if question == Question::Sensitivity {
        8
    } else {
        2
    };
    let n = match &s.value.n {
        None => DEFAULT_SAMPLES,
        Some(n) if (least..=MAX_SAMPLES).contains(&n.value) => n.value as u64,
        Some(n) => {
            return Err(cx.err(
                Some(n.referenced),
                "samples.n",
                format!(
                    "value {} is not allowed: the number of samples must lie in [{least}, {MAX_SAMPLES}]",
                    n.value
                ),
            ));
        }
    };
    let method = match &s.value.method {
        None => Method::Sobol,
        Some(m) => Method::parse(&m.value).ok_or_else(|| {
            cx.err(
                Some(m.referenced),
                "samples.method",
                format!(
                    "value {:?} is not allowed: use sobol, lhs or random",
                    m.value
                ),
            )
        })?,
    };
    let seed = match &s.value.seed {
        None => 0,
        Some(v) if v.value >= 0 => v.value as u64,
        Some(v) => {
            return Err(cx.err(
                Some(v.referenced),
                "samples.seed",
                format!("value {} is not allowed: a seed is an integer ≥ 0", v.value),
            ));
        }
    };
    let bootstrap = match &s.value.bootstrap {
        None => DEFAULT_BOOTSTRAP,
        Some(b) if (0..=MAX_BOOTSTRAP).contains(&b.value) => b.value as u64,
        Some(b) => {
            return Err(cx.err(
                Some(b.referenced),
                "samples.bootstrap",
                format!(
                    "value {} is not allowed: the bootstrap resamples lie in [0, {MAX_BOOTSTRAP}]",
                    b.value
                ),
            ));
        }
    };
    Ok((n, method, seed, bootstrap))
}

/// An axis for each uncertain parameter that a grid axis could span, holding the extreme
/// values its distribution takes (for the checks of the loads and the arch only).
fn shadow_axes(params: &[UncertainParam], axes: &[DistributionAxis]) -> Vec<GridAxis> {
    params
        .iter()
        .enumerate()
        .filter_map(|(i, p)| {
            let name = match p.name {
                ParamName::K => AxisName::K,
                ParamName::TOverR => AxisName::TOverR,
                ParamName::Mu => AxisName::Mu,
                ParamName::HalfAngleDeg => AxisName::HalfAngleDeg,
                ParamName::Voussoirs => AxisName::Voussoirs,
                ParamName::AtDeg => AxisName::AtDeg,
                ParamName::AtX => AxisName::AtX,
                ParamName::Eccentricity | ParamName::Lambda => return None,
            };
            // The distribution as written, and each of its variants along an axis of one of
            // its parameters.
            let variants = std::iter::once(p.distribution.clone()).chain(
                (axes.iter().filter(|a| a.param == i)).flat_map(|a| {
                    a.values
                        .iter()
                        .map(|&v| with_field(&p.distribution, a.field, v))
                }),
            );
            let mut values: Vec<f64> = variants
                .flat_map(|d| match d {
                    Distribution::Discrete { values, .. } => values,
                    d => vec![d.quantile(1e-12), d.quantile(1.0 - 1e-12)],
                })
                .collect();
            values.sort_by(f64::total_cmp);
            values.dedup();
            Some(GridAxis { name, values })
        })
        .collect()
}

/// The load cases as the checks of the loads see them: an uncertain λ or position stands in
/// for the load case's own (at its lowest value, at the crown), which the checks require.
pub(super) fn as_checked(sampling: &Sampling, load_cases: &[LoadCase]) -> Vec<LoadCase> {
    let lambda = sampling
        .param(ParamName::Lambda)
        .map(|p| p.distribution.quantile(1e-12));
    let position =
        sampling.param(ParamName::AtDeg).is_some() || sampling.param(ParamName::AtX).is_some();
    load_cases
        .iter()
        .map(|lc| {
            let mut lc = lc.clone();
            if lc.kind.is_live() && lc.find != Find::LoadFactor {
                lc.lambda = lc.lambda.or(lambda);
            }
            if position && lc.kind == LoadKind::Point {
                lc.at_deg = Some(0.0);
            }
            lc
        })
        .collect()
}
