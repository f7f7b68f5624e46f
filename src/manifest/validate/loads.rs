//! The `load_cases:` list, each load case on its own: name, kind, position, load factor and
//! find. The cross-checks against the grid and the arch are in `load_checks`.

use super::{Ctx, fmt_num, is_valid_name, parse_find};
use crate::manifest::error::ManifestError;
use crate::manifest::raw::RawLoadCase;
use crate::manifest::types::{LoadCase, LoadKind};
use crate::scene::Find;
use serde_saphyr::Spanned;

/// The load cases (self-weight alone when none is given); `find` is the study's find.
pub(super) fn validate_load_cases(
    l: Option<&[Spanned<RawLoadCase>]>,
    find: Find,
    cx: &Ctx,
) -> Result<Vec<LoadCase>, ManifestError> {
    let Some(list) = l else {
        return Ok(vec![LoadCase {
            name: "self_weight".into(),
            kind: LoadKind::SelfWeight,
            at_deg: None,
            at_x: None,
            width: None,
            lambda: None,
            find,
            sampled: false,
        }]);
    };
    if list.is_empty() {
        return Err(cx.err_unplaced(
            "load_cases",
            "the list is empty: give at least one load case or omit the key",
        ));
    }
    let mut out: Vec<LoadCase> = Vec::new();
    for lc in list {
        let name = &lc.value.name;
        check_name(name, &out, cx)?;
        let kind = kind(lc, cx)?;
        check_position(lc, kind, cx)?;
        check_position_x(lc, kind, cx)?;
        check_width(lc, kind, cx)?;
        check_lambda(lc, kind, cx)?;
        out.push(LoadCase {
            name: name.value.clone(),
            kind,
            at_deg: lc.value.at_deg.as_ref().map(|a| a.value),
            at_x: lc.value.at_x.as_ref().map(|a| a.value),
            width: lc.value.width.as_ref().map(|w| w.value),
            lambda: lc.value.lambda.as_ref().map(|l| l.value),
            find: match &lc.value.find {
                None => find,
                Some(f) => parse_find(f, "load_cases.find", cx)?,
            },
            sampled: false,
        });
    }
    Ok(out)
}

/// A load-case name is a valid name and unique among the cases before it.
fn check_name(name: &Spanned<String>, before: &[LoadCase], cx: &Ctx) -> Result<(), ManifestError> {
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
    if before.iter().any(|o| o.name == name.value) {
        return Err(cx.err(
            Some(name.referenced),
            "load_cases.name",
            format!(
                "value {:?} is a duplicate: load-case names must be unique",
                name.value
            ),
        ));
    }
    Ok(())
}

/// `self_weight`, `horizontal` or `point`.
fn kind(lc: &Spanned<RawLoadCase>, cx: &Ctx) -> Result<LoadKind, ManifestError> {
    match lc.value.kind.value.as_str() {
        "self_weight" => Ok(LoadKind::SelfWeight),
        "horizontal" => Ok(LoadKind::Horizontal),
        "point" => Ok(LoadKind::Point),
        other => Err(cx.err(
            Some(lc.value.kind.referenced),
            "load_cases.kind",
            format!("value {other:?} is not allowed: use self_weight, horizontal or point"),
        )),
    }
}

/// Only a point load has a position, within (−180, 180) degrees.
fn check_position(
    lc: &Spanned<RawLoadCase>,
    kind: LoadKind,
    cx: &Ctx,
) -> Result<(), ManifestError> {
    let Some(a) = &lc.value.at_deg else {
        return Ok(());
    };
    if kind != LoadKind::Point {
        return Err(cx.err(
            Some(a.referenced),
            "load_cases.at_deg",
            format!(
                "value {} is not allowed: only a `point` load case has a position (load case {:?} is {})",
                fmt_num(a.value),
                lc.value.name.value,
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
    Ok(())
}

/// Only a point load has a position as x/L, within [0, 1], and not beside `at_deg`.
fn check_position_x(
    lc: &Spanned<RawLoadCase>,
    kind: LoadKind,
    cx: &Ctx,
) -> Result<(), ManifestError> {
    let Some(x) = &lc.value.at_x else {
        return Ok(());
    };
    let refuse = |why: String| {
        Err(cx.err(
            Some(x.referenced),
            "load_cases.at_x",
            format!("value {} is not allowed: {why}", fmt_num(x.value)),
        ))
    };
    if kind != LoadKind::Point {
        return refuse(format!(
            "only a `point` load case has a position (load case {:?} is {})",
            lc.value.name.value,
            kind.as_str()
        ));
    }
    if lc.value.at_deg.is_some() {
        return refuse("give the position once, as at_deg or as at_x".into());
    }
    if !(0.0..=1.0).contains(&x.value) {
        return refuse(
            "x/L must lie in [0, 1] (0 and 1 the extrados springings, 0.5 the crown)".into(),
        );
    }
    Ok(())
}

/// Only a point load has a width, a fraction of the extrados span in [0, 1].
fn check_width(lc: &Spanned<RawLoadCase>, kind: LoadKind, cx: &Ctx) -> Result<(), ManifestError> {
    let Some(w) = &lc.value.width else {
        return Ok(());
    };
    let refuse = |why: String| {
        Err(cx.err(
            Some(w.referenced),
            "load_cases.width",
            format!("value {} is not allowed: {why}", fmt_num(w.value)),
        ))
    };
    if kind != LoadKind::Point {
        return refuse(format!(
            "only a `point` load case can be spread over a width (load case {:?} is {})",
            lc.value.name.value,
            kind.as_str()
        ));
    }
    if !(0.0..=1.0).contains(&w.value) {
        return refuse(
            "the width is a fraction of the extrados span in [0, 1] (0: a concentrated load)"
                .into(),
        );
    }
    Ok(())
}

/// Only a live load has a load factor, finite and ≥ 0.
fn check_lambda(lc: &Spanned<RawLoadCase>, kind: LoadKind, cx: &Ctx) -> Result<(), ManifestError> {
    let Some(l) = &lc.value.lambda else {
        return Ok(());
    };
    if kind == LoadKind::SelfWeight {
        return Err(cx.err(
            Some(l.referenced),
            "load_cases.lambda",
            format!(
                "value {} is not allowed: load case {:?} is self_weight, which has no live part to scale",
                fmt_num(l.value),
                lc.value.name.value
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
    Ok(())
}
