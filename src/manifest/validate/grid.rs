//! The `grid:` block: which axes the load cases' finds allow and need, and the values of
//! each axis (a list or a range), checked against the parameter they span.

use super::{Ctx, fmt_num};
use crate::manifest::error::ManifestError;
use crate::manifest::raw::{Number, RawAxis, RawGrid, RawNamesAxis};
use crate::manifest::types::{AxisName, GridAxis, LoadCase};
use crate::scene::Find;
use serde_saphyr::{Location, Spanned};

/// Largest number of steps of one axis.
pub const MAX_AXIS_STEPS: i64 = 100_000;

/// The grid axes in plan order, after checking them against the load cases' finds.
pub(super) fn validate_grid(
    g: Option<&RawGrid>,
    lcs: &[LoadCase],
    uncertain: &[GridAxis],
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
    let finds = distinct_finds(lcs);
    if let [find] = finds[..] {
        check_axes_the_find_finds(g, find, cx)?;
    }
    check_axes_are_spanned(g, lcs, &finds, cx)?;
    let axes = grid_axes(g, cx)?;
    // An uncertain K or μ is as good as an axis.
    let with_uncertain: Vec<GridAxis> = axes.iter().chain(uncertain).cloned().collect();
    check_needed_axes(&with_uncertain, lcs, &finds, cx)?;
    Ok(axes)
}

/// The distinct finds of the load cases, in order of first appearance.
fn distinct_finds(lcs: &[LoadCase]) -> Vec<Find> {
    let mut finds: Vec<Find> = Vec::new();
    for lc in lcs {
        if !finds.contains(&lc.find) {
            finds.push(lc.find);
        }
    }
    finds
}

/// A study with one find has no axis for what that find finds itself.
fn check_axes_the_find_finds(g: &RawGrid, find: Find, cx: &Ctx) -> Result<(), ManifestError> {
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
    Ok(())
}

/// Every K, t/R_c or μ axis is spanned by at least one load case.
fn check_axes_are_spanned(
    g: &RawGrid,
    lcs: &[LoadCase],
    finds: &[Find],
    cx: &Ctx,
) -> Result<(), ManifestError> {
    let spanned = |axis: AxisName| lcs.iter().any(|lc| lc.spans(axis));
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
    Ok(())
}

/// The axes given, with their values, in plan order: outermost first (geometry, then K,
/// then μ innermost).
fn grid_axes(g: &RawGrid, cx: &Ctx) -> Result<Vec<GridAxis>, ManifestError> {
    let mut axes = Vec::new();
    if let Some(ax) = &g.half_angle_deg {
        axes.push(GridAxis {
            name: AxisName::HalfAngleDeg,
            values: axis_values(AxisName::HalfAngleDeg, ax, cx)?,
        });
    }
    if let Some(ax) = &g.eccentricity {
        axes.push(GridAxis {
            name: AxisName::Eccentricity,
            values: axis_values(AxisName::Eccentricity, ax, cx)?,
        });
    }
    if let Some(ax) = &g.joints {
        axes.push(GridAxis {
            name: AxisName::Joints,
            values: joint_values(ax, cx)?,
        });
    }
    for (name, ax) in [
        (AxisName::Voussoirs, &g.voussoirs),
        (AxisName::AtDeg, &g.at_deg),
        (AxisName::AtX, &g.at_x),
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
    Ok(axes)
}

/// A `joints` axis: `radial` and/or `vertical`, each once, coded [`crate::manifest::JOINTS_RADIAL`]
/// and [`crate::manifest::JOINTS_VERTICAL`].
fn joint_values(ax: &Spanned<RawNamesAxis>, cx: &Ctx) -> Result<Vec<f64>, ManifestError> {
    let key = "grid.joints.values";
    if ax.value.values.is_empty() {
        return Err(cx.err(
            Some(ax.referenced),
            key,
            "the list `values` is empty: give radial, vertical or both",
        ));
    }
    let mut out = Vec::new();
    for v in &ax.value.values {
        let Some(j) = crate::model::JointOrientation::parse(&v.value) else {
            return Err(cx.err(
                Some(v.referenced),
                key,
                format!("value {:?} is not allowed: use radial or vertical", v.value),
            ));
        };
        let code = crate::manifest::axis_value_of_joints(j);
        if out.contains(&code) {
            return Err(cx.err(
                Some(v.referenced),
                key,
                format!(
                    "value {:?} is repeated: each value may appear once",
                    v.value
                ),
            ));
        }
        out.push(code);
    }
    Ok(out)
}

/// Every load case has the K and μ axes its find needs.
fn check_needed_axes(
    axes: &[GridAxis],
    lcs: &[LoadCase],
    finds: &[Find],
    cx: &Ctx,
) -> Result<(), ManifestError> {
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
            return Err(cx.err_unplaced(
                "grid",
                format!(
                    "{} needs a k (or t_over_r) axis, or an uncertain k",
                    whose(lc)
                ),
            ));
        }
        if lc.find.needs_mu() && !has_mu && lc.find != Find::Thickness {
            return Err(cx.err_unplaced(
                "grid",
                format!(
                    "{} needs a mu axis (use values: [inf] for infinite friction)",
                    whose(lc)
                ),
            ));
        }
    }
    Ok(())
}

/// The values of one axis, in the order they are run.
fn axis_values(name: AxisName, ax: &Spanned<RawAxis>, cx: &Ctx) -> Result<Vec<f64>, ManifestError> {
    let key = format!("grid.{}", name.as_str());
    let a = &ax.value;
    match (&a.values, &a.from, &a.to, &a.steps) {
        (Some(vals), None, None, None) if a.also.is_none() => list_values(name, ax, vals, &key, cx),
        (None, Some(from), Some(to), Some(steps)) => {
            let mut vals = range_values(name, Range { from, to, steps }, &key, cx)?;
            for v in a.also.iter().flatten() {
                add_value(name, &mut vals, v, &format!("{key}.also"), cx)?;
            }
            Ok(vals)
        }
        _ => Err(cx.err(
            Some(ax.referenced),
            &key,
            "an axis is either {from, to, steps} (all three, with `also: [...]` for values \
             added to the range such as inf) or {values: [...]}",
        )),
    }
}

/// Adds a valid value to an axis, refusing one it already holds.
fn add_value(
    name: AxisName,
    out: &mut Vec<f64>,
    v: &Spanned<Number>,
    key: &str,
    cx: &Ctx,
) -> Result<(), ManifestError> {
    check_value(name, v.value.0, v.referenced, key, cx)?;
    if out.contains(&v.value.0) {
        return Err(cx.err(
            Some(v.referenced),
            key,
            format!(
                "value {} is repeated: each value may appear once",
                fmt_num(v.value.0)
            ),
        ));
    }
    out.push(v.value.0);
    Ok(())
}

/// An axis given as `{values: [...]}`: at least one value, each valid and given once.
fn list_values(
    name: AxisName,
    ax: &Spanned<RawAxis>,
    vals: &[Spanned<Number>],
    key: &str,
    cx: &Ctx,
) -> Result<Vec<f64>, ManifestError> {
    if vals.is_empty() {
        return Err(cx.err(
            Some(ax.referenced),
            key,
            "the list `values` is empty: give at least one value",
        ));
    }
    let mut out = Vec::with_capacity(vals.len());
    for v in vals {
        add_value(name, &mut out, v, &format!("{key}.values"), cx)?;
    }
    Ok(out)
}

/// An axis given as `{from, to, steps}`, as written.
struct Range<'a> {
    from: &'a Spanned<Number>,
    to: &'a Spanned<Number>,
    steps: &'a Spanned<i64>,
}

/// An axis given as `{from, to, steps}`: `steps` evenly spaced values from `from` to `to`
/// (both included), integers for a voussoir axis.
fn range_values(
    name: AxisName,
    Range { from, to, steps }: Range,
    key: &str,
    cx: &Ctx,
) -> Result<Vec<f64>, ManifestError> {
    if steps.value < 1 || steps.value > MAX_AXIS_STEPS {
        return Err(cx.err(
            Some(steps.referenced),
            &format!("{key}.steps"),
            format!(
                "value {} is not allowed: steps must be an integer in [1, {MAX_AXIS_STEPS}]",
                steps.value
            ),
        ));
    }
    let (f, t) = (from.value.0, to.value.0);
    check_value(name, f, from.referenced, &format!("{key}.from"), cx)?;
    check_value(name, t, to.referenced, &format!("{key}.to"), cx)?;
    if !f.is_finite() || !t.is_finite() {
        return Err(cx.err(
            Some(from.referenced),
            key,
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
        return Err(cx.err(
            Some(to.referenced),
            &format!("{key}.to"),
            format!(
                "the range is empty: from = to = {f} with {} steps; widen it or use steps: 1",
                steps.value
            ),
        ));
    }
    if steps.value == 1 && t != f {
        return Err(cx.err(
            Some(steps.referenced),
            &format!("{key}.steps"),
            format!(
                "one step from {f} to {t} would keep `from` alone and drop `to`; give at least \
                 2 steps to span the range, or `values: [{f}]` for one value"
            ),
        ));
    }
    let vals = decimal_range(f, t, steps.value as usize);
    if name == AxisName::Voussoirs {
        for &v in &vals {
            if v.fract() != 0.0 {
                return Err(cx.err(Some(steps.referenced), key, format!("the range gives a non-integer voussoir count {v}; choose from, to and steps so that every value is an integer, or use `values`")));
            }
        }
    }
    Ok(vals)
}

/// A value of an axis lies in the range of its parameter.
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
        AxisName::Eccentricity => crate::analysis::forms::eccentricity_allowed(v),
        AxisName::Joints => v == 0.0 || v == 1.0,
        AxisName::Voussoirs => {
            v.is_infinite() && v > 0.0 || v.fract() == 0.0 && (1.0..=1e7).contains(&v)
        }
        AxisName::AtDeg => v.is_finite() && v.abs() < 180.0,
        AxisName::AtX => (0.0..=1.0).contains(&v),
    };
    if ok {
        return Ok(());
    }
    let allowed = match name {
        AxisName::K => "K = R/r must be a finite number greater than 1",
        AxisName::TOverR => "t/R_c must lie in (0, 2)",
        AxisName::Mu => "μ must be a number ≥ 0 or inf (NaN and negative values are not allowed)",
        AxisName::HalfAngleDeg => "the half-angle must lie in (0, 180) degrees",
        AxisName::Eccentricity => {
            "the eccentricity of a pointed arch must lie in [0, 0.9999] (0: the semicircle's outline)"
        }
        AxisName::Joints => "the joints are radial or vertical",
        AxisName::Voussoirs => {
            "the voussoir count must be an integer in [1, 10000000], or `continuum`"
        }
        AxisName::AtDeg => "the position of a point load must lie in (−180, 180) degrees",
        AxisName::AtX => {
            "the position of a point load as x/L must lie in [0, 1] (0.5 is the crown)"
        }
    };
    Err(cx.err(
        Some(at),
        key,
        format!("value {} is not allowed: {allowed}", fmt_num(v)),
    ))
}

/// Most decimal places of a range's ends and step for its values to be taken as decimals.
const MAX_RANGE_DECIMALS: i32 = 12;

/// The decimal places of `x` (0 to [`MAX_RANGE_DECIMALS`]), when `x` is a decimal of that
/// many places up to rounding.
fn decimal_places(x: f64) -> Option<i32> {
    (0..=MAX_RANGE_DECIMALS).find(|&d| {
        let scaled = x * 10f64.powi(d);
        scaled.abs() < 2f64.powi(52)
            && (scaled - scaled.round()).abs() <= 1e-9 * scaled.abs().max(1.0)
    })
}

/// The `n` values of a range from `f` to `t`, both included. When the ends and the step are
/// decimals (0.2 to 0.8 in 601 steps: step 0.001), each value is the double nearest its
/// decimal (0.31, not 0.31000000000000005), so that equality filters on the stored values
/// work; otherwise `f + (t − f)·i/(n − 1)`.
pub(crate) fn decimal_range(f: f64, t: f64, n: usize) -> Vec<f64> {
    if n <= 1 {
        return vec![f];
    }
    let gaps = (n - 1) as f64;
    let decimals = [f, t, (t - f) / gaps]
        .into_iter()
        .map(decimal_places)
        .try_fold(0, |d, x| x.map(|x| d.max(x)));
    if let Some(d) = decimals {
        let scale = 10f64.powi(d);
        let (lo, hi) = ((f * scale).round() as i64, (t * scale).round() as i64);
        let gaps = (n - 1) as i64;
        if (hi - lo) % gaps == 0 {
            let step = (hi - lo) / gaps;
            // An integer below 2^53 over an exact power of ten: one correctly rounded
            // division gives the double nearest the decimal.
            return (0..gaps + 1)
                .map(|i| (lo + i * step) as f64 / scale)
                .collect();
        }
    }
    (0..n)
        .map(|i| {
            if i + 1 == n {
                t
            } else {
                f + (t - f) * (i as f64) / gaps
            }
        })
        .collect()
}

#[cfg(test)]
mod range_tests {
    use super::decimal_range;
    use crate::manifest::types::AxisName;

    fn parse(grid: &str) -> Result<crate::manifest::Manifest, crate::manifest::ManifestError> {
        crate::manifest::parse(
            &format!("name: a\ngrid:\n  k: {{values: [1.2]}}\n{grid}"),
            std::path::Path::new("a.yaml"),
        )
    }

    #[test]
    fn one_step_over_a_range_is_refused_rather_than_dropping_its_end() {
        let e = parse("  mu: {from: 0.2, to: 0.4, steps: 1}\n").unwrap_err();
        assert!(
            e.to_string().contains("grid.mu.steps") && e.to_string().contains("at least 2"),
            "{e}"
        );
        assert_eq!(
            parse("  mu: {from: 0.4, to: 0.4, steps: 1}\n")
                .unwrap()
                .grid[1]
                .values,
            [0.4]
        );
    }

    #[test]
    fn a_range_may_also_hold_infinite_friction() {
        let m = parse("  mu: {from: 0.2, to: 0.4, steps: 3, also: [inf]}\n").unwrap();
        let mu = m.grid.iter().find(|a| a.name == AxisName::Mu).unwrap();
        assert_eq!(mu.values, vec![0.2, 0.3, 0.4, f64::INFINITY]);
        let e = parse("  mu: {from: 0.2, to: 0.4, steps: 3, also: [0.3]}\n").unwrap_err();
        assert!(
            e.to_string().contains("grid.mu.also") && e.to_string().contains("repeated"),
            "{e}"
        );
        let e = parse("  mu: {values: [0.2], also: [inf]}\n").unwrap_err();
        assert!(e.to_string().contains("also"), "{e}");
    }

    #[test]
    fn decimal_ranges_hold_the_decimals_the_manifest_implies() {
        let mu = decimal_range(0.2, 0.8, 601);
        assert_eq!(mu.len(), 601);
        assert_eq!(mu[100], 0.3);
        assert_eq!(mu[110], 0.31);
        assert_eq!(mu[600], 0.8);
        assert_eq!(mu.iter().filter(|&&m| m == 0.35).count(), 1);
        let k = decimal_range(1.05, 1.5, 181);
        assert_eq!((k[0], k[2], k[180]), (1.05, 1.055, 1.5));
        assert_eq!(decimal_range(1.0, 64.0, 64)[9], 10.0);
    }

    #[test]
    fn other_ranges_keep_evenly_spaced_values_and_their_ends() {
        let v = decimal_range(0.0, 1.0, 4);
        assert_eq!(v[0], 0.0);
        assert_eq!(v[3], 1.0);
        assert!((v[1] - 1.0 / 3.0).abs() < 1e-15);
        assert_eq!(decimal_range(0.5, 0.5, 1), vec![0.5]);
    }
}
