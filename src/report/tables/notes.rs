//! Notes in words on what a reader would otherwise take for a defect of the run: cases where
//! no requested μ lets the arch stand under its own weight, and load positions at which λ
//! is unbounded, slivers punched by a point load, and sliding on the edges of a pointed
//! arch's crown wedge. Each note names the counts and the values behind it, from the stored data.

use crate::report::data::{RunData, given_position};
use crate::report::format::compact;
use crate::report::format::{given, position_deg};
use crate::store::ResultRow;

/// At most this many values listed in a note.
const LISTED: usize = 8;

/// `values` as a list of at most [`LISTED`] of them, with how many more there are.
fn listed(values: &[String]) -> String {
    let mut s = values
        .iter()
        .take(LISTED)
        .cloned()
        .collect::<Vec<_>>()
        .join(", ");
    if values.len() > LISTED {
        s.push_str(&format!(" and {} more", values.len() - LISTED));
    }
    s
}

/// Sorted distinct values.
fn distinct(mut v: Vec<f64>) -> Vec<f64> {
    v.retain(|x| !x.is_nan());
    v.sort_by(f64::total_cmp);
    v.dedup();
    v
}

/// The notes of a run, each a sentence or two.
pub fn notes(data: &RunData) -> Vec<String> {
    let mut out = super::uncertainty::notes(data);
    out.extend(never_stands(data));
    out.extend(unbounded(data));
    out.extend(slivers(data));
    out.extend(crown_wedge(data));
    out
}

/// Two sliding angles closer than this (degrees) are one joint.
const SAME_ANGLE_DEG: f64 = 1e-6;

/// Mechanisms of a pointed arch of radial joints that slide at ±ψ₁ = asin(e (1 + K)/2), the
/// first radial joints: the edges of the crown wedge, which holds no joint but the vertical
/// crown joint and so slides as one block.
fn crown_wedge(data: &RunData) -> Option<String> {
    // The form of each mechanism is its state's (it varies along eccentricity and joints
    // axes).
    let psi1 = |m: &crate::store::MechanismRow| -> Option<f64> {
        let s = data.states.iter().find(|s| s.state_id == m.state_id)?;
        (s.shape == "pointed" && s.joint_orientation == "radial")
            .then(|| (s.eccentricity * (1.0 + m.k) / 2.0).asin().to_degrees())
    };
    let on_edge: Vec<&crate::store::MechanismRow> = data
        .mechanisms
        .iter()
        .filter(|m| m.flow_rule == "non_associative")
        .filter(|m| {
            psi1(m).is_some_and(|p| {
                (m.sliding_angles_deg.iter()).any(|a| (a.abs() - p).abs() <= SAME_ANGLE_DEG)
            })
        })
        .collect();
    let first = on_edge.first()?;
    let drawn = data
        .mechanisms
        .iter()
        .filter(|m| m.flow_rule == "non_associative")
        .count();
    Some(format!(
        "In {} of the {drawn} mechanisms drawn the arch slides at ±ψ₁ = asin(e (1 + K)/2), the \
         first radial joints of the pointed arch ({} first: K = {}, μ = {}, ψ₁ = {:.4}°): these \
         are the edges of the crown wedge, which holds no joint but the vertical crown joint, so \
         the wedge between them moves as one block. The angle follows from e and K; it is not a \
         joint picked at an odd place.",
        on_edge.len(),
        first.state_id,
        compact(first.k),
        compact(first.mu),
        psi1(first).unwrap_or(f64::NAN),
    ))
}

/// Point loads on the continuum whose mechanism slides on both sides of the load's joint:
/// a sliver of zero width punched through the arch, whose λ_max the friction on those two
/// joints alone sets.
fn slivers(data: &RunData) -> Option<String> {
    let mut punched: Vec<&crate::store::LoadFactorCase> = data
        .load_factors
        .iter()
        .chain(&data.load_factor_singled)
        .filter(|c| c.voussoirs.is_none() && c.sliding_at_load >= 2 && c.load_factor.is_some())
        .collect();
    punched.sort_by_key(|c| c.row);
    punched.dedup_by_key(|c| c.row);
    let first = punched.first()?;
    let by_x = data.manifest.positions_by_x(&first.load_case);
    let at = match (by_x, first.at_x, first.at_deg) {
        (true, Some(x), _) => format!("x/L = {}", given(x)),
        (_, _, Some(a)) => format!("{}°", position_deg(a)),
        _ => String::new(),
    };
    let lambda = first
        .load_factor
        .map_or(String::new(), |l| format!("{l:.4}"));
    Some(format!(
        "A point load on the continuum punches a sliver of zero width through the arch in {} \
         of the cases drawn (results.parquet row {} first: K = {}, μ = {}, load at {at}, \
         λ_max = {lambda}): the mechanism slides on both sides of the load's joint, so λ_max \
         is what the friction of those two joints alone carries, and it does not change with \
         the thickness. A load spread over a length of the extrados (`width` on the load \
         case), or an arch of voussoirs (`voussoirs`), has no such sliver.",
        punched.len(),
        first.row,
        compact(first.k),
        compact(first.mu),
    ))
}

/// Cases where the arch never stands (see [`never_stands_opening`]), and the K
/// (with the arch of a voussoir axis) at which not one requested μ stands.
fn never_stands(data: &RunData) -> Option<String> {
    let count = data
        .totals
        .by_outcome
        .get("never stands")
        .copied()
        .unwrap_or(0);
    if count == 0 {
        return None;
    }
    let total = data.totals.rows;
    let mut text = never_stands_opening(data, count, total);
    let rows = |r: &&ResultRow| r.find.as_ref() != "state";
    let lines = |stands: bool| -> Vec<(u64, Option<u32>)> {
        let mut v: Vec<(u64, Option<u32>)> = data
            .results
            .iter()
            .filter(rows)
            .filter(|r| (r.outcome.as_deref() != Some("never_stands")) == stands)
            .filter_map(|r| Some((r.k?.to_bits(), r.voussoirs)))
            .collect();
        v.sort_unstable();
        v.dedup();
        v
    };
    let standing = lines(true);
    let none: Vec<f64> = distinct(
        lines(false)
            .into_iter()
            .filter(|l| standing.binary_search(l).is_err())
            .map(|(k, _)| f64::from_bits(k))
            .collect(),
    );
    let mus = distinct(
        data.results
            .iter()
            .filter(rows)
            .filter_map(|r| r.mu)
            .collect(),
    );
    if let (false, Some(&top)) = (none.is_empty(), mus.last()) {
        let ks: Vec<String> = none.iter().map(|&k| compact(k)).collect();
        if top.is_infinite() {
            // μ = ∞ was asked for: no friction at all lets the arch stand at these K.
            text.push_str(&format!(
                " At K = {} no μ stands, not even μ = ∞: the arch is too thin for its form and \
                 load there.",
                listed(&ks)
            ));
            return Some(text);
        }
        text.push_str(&format!(
            " At K = {} not one of the requested μ (up to {}) stands: the arch needs more \
             friction there than the study asks for",
            listed(&ks),
            given(top)
        ));
        match friction_needed(data, &none) {
            Some(needed) => text.push_str(&format!(
                ". The friction it needs under its own weight (the friction find, \
                 `archstudy solve --find friction --k K` with the study's arch): {}.",
                listed(&needed)
            )),
            None => text.push_str(
                "; `archstudy solve --find friction --k K` (with the study's arch) gives the \
                 least μ at which it stands.",
            ),
        }
    }
    Some(text)
}

/// The first sentence of [`never_stands`]: how many cases never stand and what that means for
/// each find among them (no μ for a friction find, no K for a thickness find, not even λ = 0
/// for a load factor).
fn never_stands_opening(data: &RunData, count: usize, total: u64) -> String {
    // What "never stands" means depends on the find: no μ for a friction find, no K for a
    // thickness find, not even λ = 0 for a load factor.
    let mut finds: Vec<&str> = (data.results.iter())
        .filter(|r| r.outcome.as_deref() == Some("never_stands"))
        .map(|r| r.find.as_ref())
        .collect();
    finds.sort_unstable();
    finds.dedup();
    let meaning: Vec<&str> = finds
        .iter()
        .filter_map(|f| match *f {
            "load_factor" => Some(
                "a load-factor case does not stand under its own weight at the μ of the case, \
                 so it has no load factor",
            ),
            "thickness" => Some(
                "a thickness case stands at no K of the scan at the μ (and λ) of the case, so it \
                 has no critical thickness",
            ),
            "thrust" => Some(
                "a thrust case admits no crown thrust at the K and μ of the case (no state \
                 stands there)",
            ),
            "friction" => Some(
                "a friction case stands at no μ, however large, at the K (and λ) of the case, so \
                 it has no critical friction",
            ),
            _ => None,
        })
        .collect();
    let opening = if finds == ["load_factor"] {
        format!("No requested μ stands in {count} of {total} cases")
    } else {
        format!("The arch never stands in {count} of {total} cases")
    };
    format!(
        "{opening} (outcome never_stands in results.parquet): {}; the figures leave those cases \
         out.",
        if meaning.is_empty() {
            "the arch has no value there".to_string()
        } else {
            meaning.join("; ")
        }
    )
}

/// The friction find of the study's arch under its own weight at each of the first
/// [`LISTED`] thicknesses `ks`, in words: μ_c (the static limit) and, where the gap is open,
/// the μ below which a mechanism can start; "no μ" where none lets it stand. `None` when
/// the grid varies the arch (a half-angle or voussoir axis: the arch of each K is not one).
fn friction_needed(data: &RunData, ks: &[f64]) -> Option<Vec<String>> {
    let arch = &data.manifest.arch;
    if data.manifest.grid.iter().any(|a| {
        matches!(
            a.name.as_str(),
            "half_angle_deg" | "voussoirs" | "eccentricity" | "joints"
        )
    }) {
        return None;
    }
    let needed = ks
        .iter()
        .take(LISTED)
        .map(|&k| {
            let scene = crate::manifest::SceneOptions {
                find: "friction".into(),
                k: Some(k),
                half_angle_deg: arch.half_angle_deg,
                weight: arch.weight.clone(),
                voussoirs: arch.voussoir_count().map(i64::from),
                shape: arch.shape.clone(),
                eccentricity: arch.eccentricity,
                joints: arch.joints.clone(),
                keystone: arch.keystone,
                ..crate::manifest::SceneOptions::default()
            }
            .scene()
            .ok()?;
            let sol = crate::scene::solve(&scene);
            let at = format!("K = {}", compact(k));
            Some(match sol.outcome {
                Some(crate::scene::Outcome::Found) => {
                    let mut s = format!("{at}: μ_c = {}", compact(sol.mu_crit?));
                    if let Some(c) = crate::report::charts::solution::drawn_collapse(&sol) {
                        s.push_str(&format!(
                            " (a mechanism can start below μ = {}: the gap)",
                            compact(c)
                        ));
                    }
                    s
                }
                Some(crate::scene::Outcome::AlwaysStands) => format!("{at}: any μ"),
                _ => format!("{at}: no μ lets it stand"),
            })
        })
        .collect::<Option<Vec<String>>>()?;
    Some(needed)
}

/// Cases whose λ is unbounded, with the load positions (as given) where it is.
fn unbounded(data: &RunData) -> Option<String> {
    let count = data
        .totals
        .by_outcome
        .get("unbounded")
        .copied()
        .unwrap_or(0);
    if count == 0 {
        return None;
    }
    let mut text = format!(
        "λ is unbounded in {count} cases (outcome unbounded, load_factor null in \
         results.parquet): the arch stands under every multiple of the live load there (a point \
         load over a springing, or on a part that carries it straight to a support); the \
         figures leave a gap at those cases."
    );
    let unbounded_rows: Vec<u64> = data
        .results
        .iter()
        .filter(|r| r.outcome.as_deref() == Some("unbounded"))
        .map(|r| r.case_id)
        .collect();
    let mut positions: Vec<String> = Vec::new();
    for lc in &data.manifest.load_cases {
        let by_x = data.manifest.positions_by_x(&lc.name);
        let at = distinct(
            data.load_factors
                .iter()
                .filter(|c| c.load_case == lc.name)
                .filter(|c| unbounded_rows.binary_search(&(c.row as u64)).is_ok())
                .filter_map(|c| given_position(c, by_x))
                .collect(),
        );
        positions.extend(at.into_iter().map(|p| {
            if by_x {
                format!("x/L = {}", given(p))
            } else {
                format!("{}°", position_deg(p))
            }
        }));
    }
    if !positions.is_empty() {
        text.push_str(&format!(
            " Point load positions with an unbounded λ: {}.",
            listed(&positions)
        ));
    }
    Some(text)
}
