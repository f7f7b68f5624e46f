//! Cross-checks of the load cases against the find, the grid and the form of the arch;
//! every message names the key and the value at fault, where it was written.

use super::{Ctx, fmt_num};
use crate::manifest::error::ManifestError;
use crate::manifest::raw::{RawAxis, RawLoadCase, RawManifest};
use crate::manifest::types::{ArchOptions, AxisName, GridAxis, LoadCase, LoadKind};
use crate::model::{ArchForm, Discretisation, JointOrientation, Shape};
use crate::scene::Find;
use serde_saphyr::{Location, Spanned};

/// Where the keys of the i-th load case were written.
struct Written<'a> {
    lcs: &'a [Spanned<RawLoadCase>],
}

impl Written<'_> {
    fn case(&self, i: usize) -> Option<Location> {
        self.lcs.get(i).map(|l| l.referenced)
    }

    fn kind(&self, i: usize) -> Option<Location> {
        self.lcs.get(i).map(|l| l.value.kind.referenced)
    }

    fn lambda(&self, i: usize) -> Option<Location> {
        self.lcs
            .get(i)
            .and_then(|l| l.value.lambda.as_ref())
            .map(|l| l.referenced)
    }

    fn at_deg(&self, i: usize) -> Option<Location> {
        self.lcs
            .get(i)
            .and_then(|l| l.value.at_deg.as_ref())
            .map(|a| a.referenced)
    }
}

/// The position of a point load, with where it was written and its key.
type Position = (f64, Option<Location>, &'static str);

/// Runs every cross-check, in the order the errors are reported.
pub(super) fn check_loads(
    raw: &RawManifest,
    arch: &ArchOptions,
    grid: &[GridAxis],
    lcs: &[LoadCase],
    cx: &Ctx,
) -> Result<(), ManifestError> {
    let written = Written {
        lcs: raw.load_cases.as_deref().unwrap_or(&[]),
    };
    let at_axis = raw.grid.as_ref().and_then(|g| g.at_deg.as_ref());
    let x_axis = raw.grid.as_ref().and_then(|g| g.at_x.as_ref());
    if let (Some(_), Some(x)) = (at_axis, x_axis) {
        return Err(cx.err(
            Some(x.referenced),
            "grid.at_x",
            "a study has one position axis: at_deg (degrees) or at_x (x/L), not both",
        ));
    }
    for (i, lc) in lcs.iter().enumerate() {
        check_find_fits_load(i, lc, &written, cx)?;
        check_lambda_fits_find(i, lc, &written, cx)?;
        let axis = match (at_axis, x_axis) {
            (Some(a), _) => Some((a, "grid.at_deg")),
            (None, Some(x)) => Some((x, "grid.at_x")),
            (None, None) => None,
        };
        check_position_source(i, lc, axis, &written, cx)?;
    }
    let alphas =
        axis_values(grid, AxisName::HalfAngleDeg).unwrap_or_else(|| vec![arch.half_angle_deg]);
    let alpha_min = alphas.iter().copied().fold(f64::INFINITY, f64::min);
    let alpha_max = alphas.iter().copied().fold(0.0, f64::max);
    let positions = point_positions(lcs, at_axis, grid, &written);
    check_positions_on_arch(&positions, alpha_min, cx)?;
    for (i, lc) in lcs.iter().enumerate() {
        let at_xs = lc
            .at_x
            .map(|x| vec![x])
            .or_else(|| axis_values(grid, AxisName::AtX))
            .unwrap_or_default();
        let patch = Patch {
            lc,
            at_xs: &at_xs,
            alpha_max,
            at: written.lcs.get(i).and_then(|l| l.value.width.as_ref()),
        };
        check_patch(&patch, cx)?;
    }
    // Every form of the study: the arch's, or one per value of its eccentricity and joints
    // axes.
    for form in study_forms(arch, grid) {
        check_form_fits_finds(raw, lcs, &form, cx)?;
        check_vertical_joints(raw, &form, alpha_max, cx)?;
        check_keystone(raw, arch, &form, grid, cx)?;
        let span = Span {
            form: &form,
            alphas: &alphas,
        };
        check_positions_x(raw, lcs, grid, &span, cx)?;
        if let Shape::Pointed { eccentricity: e } = form.shape
            && e > 0.0
        {
            let pointed = Pointed {
                form: &form,
                e,
                alphas: &alphas,
            };
            check_pointed_arch(raw, grid, &pointed, &positions, cx)?;
        }
    }
    Ok(())
}

pub(super) use crate::manifest::types::study_forms;

/// A load case's patch, with the positions it is centred on when given as x/L.
struct Patch<'a> {
    lc: &'a LoadCase,
    at_xs: &'a [f64],
    alpha_max: f64,
    at: Option<&'a Spanned<f64>>,
}

/// A patch load lies within the span of an arch with α ≤ 90° (where a vertical meets the
/// extrados once). Centres given in degrees are checked where each case's model is built:
/// their x/L moves with K on a pointed or vertical-joint arch.
fn check_patch(p: &Patch, cx: &Ctx) -> Result<(), ManifestError> {
    let Some(w) = p.lc.width.filter(|&w| w > 0.0) else {
        return Ok(());
    };
    let refuse = |why: String| {
        Err(cx.err(
            p.at.map(|s| s.referenced),
            "load_cases.width",
            format!("value {} is not allowed: {why}", fmt_num(w)),
        ))
    };
    if p.alpha_max > 90.0 {
        return refuse(format!(
            "a patch load is spread over a horizontal length of the extrados, which needs              half-angles of at most 90° (the grid reaches {}°)",
            fmt_num(p.alpha_max)
        ));
    }
    let tol = crate::analysis::settings::GeometrySettings::DEFAULT.tol_patch_span;
    if let Some(&x) = p
        .at_xs
        .iter()
        .find(|&&x| x - 0.5 * w < -tol || x + 0.5 * w > 1.0 + tol)
    {
        return refuse(format!(
            "load case {:?} centred at x/L = {} would run from x/L = {} to {}, past a              springing: the patch must lie within [0, 1]",
            p.lc.name,
            fmt_num(x),
            fmt_num(x - 0.5 * w),
            fmt_num(x + 0.5 * w)
        ));
    }
    Ok(())
}

fn axis_values(grid: &[GridAxis], n: AxisName) -> Option<Vec<f64>> {
    grid.iter().find(|a| a.name == n).map(|a| a.values.clone())
}

/// A load-factor study needs a live load; thrust and thresholds studies are for
/// self-weight only.
fn check_find_fits_load(
    i: usize,
    lc: &LoadCase,
    written: &Written,
    cx: &Ctx,
) -> Result<(), ManifestError> {
    let live = lc.kind.is_live();
    let find = lc.find;
    if find == Find::LoadFactor && !live {
        return Err(cx.err(
            written.kind(i),
            "load_cases.kind",
            format!(
                "load case {:?} is self_weight: a load_factor study needs a live load (horizontal or point)",
                lc.name
            ),
        ));
    }
    if matches!(find, Find::Thrust | Find::Thresholds) && live {
        return Err(cx.err(
            written.kind(i),
            "load_cases.kind",
            format!(
                "load case {:?} is {}: a {find} study is defined for self_weight only",
                lc.name,
                lc.kind.as_str()
            ),
        ));
    }
    Ok(())
}

/// A live load has its load factor given, except in a load-factor study, which finds it.
fn check_lambda_fits_find(
    i: usize,
    lc: &LoadCase,
    written: &Written,
    cx: &Ctx,
) -> Result<(), ManifestError> {
    match (lc.kind.is_live(), lc.find, lc.lambda) {
        (true, Find::LoadFactor, Some(l)) => Err(cx.err(
            written.lambda(i),
            "load_cases.lambda",
            format!(
                "value {} is not allowed: a load_factor study finds λ itself; remove `lambda` from load case {:?}",
                fmt_num(l),
                lc.name
            ),
        )),
        (true, f, None) if f != Find::LoadFactor => Err(cx.err(
            written.case(i),
            "load_cases.lambda",
            format!(
                "load case {:?} ({}) needs its load factor in a `{f}` study: add `lambda: L` (L ≥ 0), or use `find: load_factor`",
                lc.name,
                lc.kind.as_str()
            ),
        )),
        _ => Ok(()),
    }
}

/// A point load is positioned by its `at_deg` or `at_x`, or by the grid's at_deg or at_x
/// axis (exactly one of them, with the axis's key); a position axis is for point loads
/// only.
fn check_position_source(
    i: usize,
    lc: &LoadCase,
    at_axis: Option<(&Spanned<RawAxis>, &'static str)>,
    written: &Written,
    cx: &Ctx,
) -> Result<(), ManifestError> {
    let own = lc.at_deg.or(lc.at_x);
    match (lc.kind, at_axis, own) {
        (LoadKind::Point, Some(_), Some(a)) => Err(cx.err(
            written.at_deg(i).or(written.case(i)),
            if lc.at_deg.is_some() {
                "load_cases.at_deg"
            } else {
                "load_cases.at_x"
            },
            format!(
                "value {} is not allowed: the grid's position axis gives the position of load case {:?}; remove one of them",
                fmt_num(a),
                lc.name
            ),
        )),
        (LoadKind::Point, None, None) => Err(cx.err(
            written.case(i),
            "load_cases.at_deg",
            format!(
                "point load case {:?} needs its position: add `at_deg: DEG` (degrees from the crown, in [−α, α]), `at_x: X` (x/L in [0, 1]) or a grid axis `at_deg` or `at_x`",
                lc.name
            ),
        )),
        (kind, Some((ax, key)), _) if kind != LoadKind::Point => Err(cx.err(
            Some(ax.referenced),
            key,
            format!(
                "an at_deg or at_x axis positions point loads, but load case {:?} is {}: give it a study of its own",
                lc.name,
                kind.as_str()
            ),
        )),
        _ => Ok(()),
    }
}

/// Thrust and thresholds studies are defined for the circular arch with radial joints.
fn check_form_fits_finds(
    raw: &RawManifest,
    lcs: &[LoadCase],
    form: &ArchForm,
    cx: &Ctx,
) -> Result<(), ManifestError> {
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
    Ok(())
}

/// Vertical joints need α ≤ 90°.
fn check_vertical_joints(
    raw: &RawManifest,
    form: &ArchForm,
    alpha_max: f64,
    cx: &Ctx,
) -> Result<(), ManifestError> {
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
    Ok(())
}

/// A keystone needs a pointed arch with radial joints in the continuum, or an odd voussoir
/// count (every count of a voussoirs axis).
fn check_keystone(
    raw: &RawManifest,
    arch: &ArchOptions,
    form: &ArchForm,
    grid: &[GridAxis],
    cx: &Ctx,
) -> Result<(), ManifestError> {
    let counts = match axis_values(grid, AxisName::Voussoirs) {
        Some(values) => values
            .iter()
            .map(|&v| {
                if v.is_infinite() {
                    Discretisation::Continuum
                } else {
                    Discretisation::Voussoirs(v as u32)
                }
            })
            .collect(),
        None => vec![arch.voussoirs],
    };
    for joints in counts {
        if let Err(why) = form.check_keystone(joints) {
            return Err(cx.err(
                raw.arch.keystone.as_ref().map(|k| k.referenced),
                "arch.keystone",
                format!("value true is not allowed: {why}"),
            ));
        }
    }
    Ok(())
}

/// Positions of point loads with where they were written: the load cases' own, then the
/// grid's at_deg axis.
fn point_positions(
    lcs: &[LoadCase],
    at_axis: Option<&Spanned<RawAxis>>,
    grid: &[GridAxis],
    written: &Written,
) -> Vec<Position> {
    let mut positions: Vec<Position> = Vec::new();
    for (i, lc) in lcs.iter().enumerate() {
        if let Some(a) = lc.at_deg {
            positions.push((a, written.at_deg(i), "load_cases.at_deg"));
        }
    }
    if let (Some(ax), Some(vals)) = (at_axis, axis_values(grid, AxisName::AtDeg)) {
        for v in vals {
            positions.push((v, Some(ax.referenced), "grid.at_deg"));
        }
    }
    positions
}

/// A point load lies on the arch: within ± the smallest half-angle.
fn check_positions_on_arch(
    positions: &[Position],
    alpha_min: f64,
    cx: &Ctx,
) -> Result<(), ManifestError> {
    for &(a, at, key) in positions {
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
    Ok(())
}

/// The form of the arch and its half-angles.
struct Span<'a> {
    form: &'a ArchForm,
    alphas: &'a [f64],
}

/// Positions as x/L need α ≤ 90° (beyond, a vertical line meets the extrados twice), and on
/// a pointed arch with radial joints and no keystone must miss the wedge between the crown
/// joint and the first joints at every K of the grid.
fn check_positions_x(
    raw: &RawManifest,
    lcs: &[LoadCase],
    grid: &[GridAxis],
    span: &Span,
    cx: &Ctx,
) -> Result<(), ManifestError> {
    let x_axis = raw.grid.as_ref().and_then(|g| g.at_x.as_ref());
    let written = raw.load_cases.as_deref().unwrap_or(&[]);
    let mut xs: Vec<(f64, Option<Location>, &str)> = Vec::new();
    for (i, lc) in lcs.iter().enumerate() {
        if let Some(x) = lc.at_x {
            let at = written
                .get(i)
                .and_then(|l| l.value.at_x.as_ref())
                .map(|a| a.referenced);
            xs.push((x, at, "load_cases.at_x"));
        }
    }
    if let (Some(ax), Some(vals)) = (x_axis, axis_values(grid, AxisName::AtX)) {
        xs.extend(
            vals.into_iter()
                .map(|v| (v, Some(ax.referenced), "grid.at_x")),
        );
    }
    let Some(&(x0, at0, key0)) = xs.first() else {
        return Ok(());
    };
    if let Some(alpha) = span.alphas.iter().copied().find(|&a| a > 90.0) {
        return Err(cx.err(
            at0,
            key0,
            format!(
                "value {} is not allowed with a half-angle of {}°: positions as x/L need α ≤ 90° (beyond, a vertical line meets the extrados twice); give the position as at_deg",
                fmt_num(x0),
                fmt_num(alpha)
            ),
        ));
    }
    let form = span.form;
    if form.shape.eccentricity() == 0.0 || form.keystone || form.joints != JointOrientation::Radial
    {
        return Ok(());
    }
    let ks = k_values(grid).unwrap_or_default();
    for &(x, at, key) in &xs {
        for &k in &ks {
            for &alpha in span.alphas {
                let psi_1 = form.centre_offset(k).min(1.0).asin();
                let inside = form
                    .extrados_at_x(k, alpha.to_radians(), x)
                    .is_some_and(|(_, xx, psi)| xx != 0.0 && psi < psi_1);
                if inside {
                    return Err(cx.err(
                        at,
                        key,
                        format!(
                            "value {} is not allowed: at K = {k} this point of the extrados lies above the wedge between the crown joint and the first joints (±{:.6}°) of the pointed arch, where no joint exists; add `keystone: true` to load the keystone",
                            fmt_num(x),
                            psi_1.to_degrees()
                        ),
                    ));
                }
            }
        }
    }
    Ok(())
}

/// A pointed arch of eccentricity `e` > 0 and its half-angles.
struct Pointed<'a> {
    form: &'a ArchForm,
    e: f64,
    alphas: &'a [f64],
}

/// A pointed arch exists only below a largest K, and has no joint between its crown and
/// the keystone's edge, where no point load can sit.
fn check_pointed_arch(
    raw: &RawManifest,
    grid: &[GridAxis],
    p: &Pointed,
    positions: &[Position],
    cx: &Ctx,
) -> Result<(), ManifestError> {
    let Pointed { form, e, alphas } = *p;
    let k_axis = raw
        .grid
        .as_ref()
        .and_then(|g| g.k.as_ref().or(g.t_over_r.as_ref()));
    // No K axis: a thickness find, whose path runs down towards K = 1, where the keystone's
    // extrados and the first joint both come nearest the apex (ψ_e = ψ₁ = asin e).
    let (ks, at_k) = match k_values(grid) {
        Some(ks) => (ks, None),
        None => (
            vec![1.0],
            Some("on the path of a thickness find, which runs down towards K = 1"),
        ),
    };
    let where_k = |k: f64| at_k.map_or_else(|| format!("at K = {k}"), String::from);
    let k_top = ks.iter().copied().fold(1.0, f64::max);
    for &alpha in alphas {
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
    // ψ₁ = asin(e(1 + K)/2) grows with K: the thickest arch has the largest keystone. On a
    // keystone a load lies on its extrados, which starts at the apex, ψ_e = asin(d/K): the
    // thinnest arch has the largest ψ_e.
    let psi_1 = (e * 0.5 * (1.0 + k_top)).min(1.0).asin().to_degrees();
    if form.keystone && form.joints == JointOrientation::Radial {
        let k_low = ks.iter().copied().fold(f64::INFINITY, f64::min);
        let psi_e = (e * 0.5 * (1.0 + k_low) / k_low)
            .min(1.0)
            .asin()
            .to_degrees();
        return match positions.iter().find(|p| p.0 != 0.0 && p.0.abs() < psi_e) {
            Some(&(a, at, key)) => Err(cx.err(
                at,
                key,
                format!(
                    "value {} is not allowed: a point load on the keystone lies on its extrados, which starts at the apex (0°) at ±{psi_e:.6}° from its arc's centre {}; give the load as x/L",
                    fmt_num(a),
                    where_k(k_low)
                ),
            )),
            None => Ok(()),
        };
    }
    for &(a, at, key) in positions {
        if a != 0.0 && a.abs() < psi_1 {
            return Err(cx.err(
                at,
                key,
                format!(
                    "value {} is not allowed: a point load must sit at a joint, and this pointed arch has none between its crown (0°) and ±{psi_1:.6}° {} (with `keystone: true` a load may sit on the keystone)",
                    fmt_num(a),
                    where_k(k_top)
                ),
            ));
        }
    }
    Ok(())
}

/// The K values of the grid's K or t/R_c axis, as K.
fn k_values(grid: &[GridAxis]) -> Option<Vec<f64>> {
    grid.iter()
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
        })
}
