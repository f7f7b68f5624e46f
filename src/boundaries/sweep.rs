//! Bifurcations of `thickness` and `friction` studies: each traces the collapse curve along
//! one parameter (K_c(μ) along μ, μ_c(K) along K), and a bifurcation shows as a change of
//! the critical state's mechanism between consecutive swept values, or as an end of the
//! traced curve (a thickness sweep ends at μ_min where the sliding segment starts; a
//! friction sweep starts at the rotational K_c where the rotational segment ends).
//!
//! Each change is located by bisection on the swept parameter to the tolerance, and then
//! characterised as in a `state` grid ([`Landmarks`]); a mechanism change that is neither
//! known kind is reported at the bisection point with the union of both sides' joints.

use super::bifurcation::{Kind, Landmarks, merge_coincident, record, slack};
use super::cells::Cell;
use super::grid::Grid;
use super::probe::Probe;
use super::{Bifurcation, Counter};
use crate::analysis::symmetric::{Critical, CriticalState};
use crate::analysis::{Mechanism, MechanismKind};
use crate::scene::Outcome as Answered;
use std::f64::consts::FRAC_PI_2;

/// The parameter a one-dimensional study sweeps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Swept {
    /// μ (a `thickness` study: K_c(μ)).
    Mu,
    /// K (a `friction` study: μ_c(K)).
    K,
}

/// The outcome of a critical-value analysis, as far as bifurcations are concerned.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Outcome {
    Never,
    Always,
    Found(MechanismKind),
}

fn outcome(c: &Critical) -> Outcome {
    match c {
        Critical::Found(s) => Outcome::Found(s.mechanism.kind),
        Critical::NeverStands => Outcome::Never,
        Critical::AlwaysStands => Outcome::Always,
    }
}

fn stored_outcome(cell: Option<Cell>) -> Option<Outcome> {
    match cell? {
        Cell::Found(m) => Some(Outcome::Found(m?)),
        Cell::Other(Answered::NeverStands) => Some(Outcome::Never),
        Cell::Other(Answered::AlwaysStands) => Some(Outcome::Always),
        _ => None,
    }
}

/// The kinds of bifurcation a change of outcome along the sweep can stand for.
fn kinds(swept: Swept, a: Outcome, b: Outcome) -> Vec<Kind> {
    use MechanismKind::*;
    use Outcome::*;
    let pair = |x, y| (a == Found(x) && b == Found(y)) || (a == Found(y) && b == Found(x));
    if pair(Rotational, Mixed) {
        return vec![Kind::RotationalMixed];
    }
    if pair(Mixed, Sliding) {
        return vec![Kind::MixedSliding];
    }
    if pair(Rotational, Sliding) {
        return vec![Kind::RotationalMixed, Kind::MixedSliding];
    }
    let found = match (a, b) {
        (Never, Found(k)) | (Found(k), Never) => k,
        _ => return Vec::new(),
    };
    match (swept, found) {
        (Swept::Mu, Rotational) => vec![Kind::RotationalMixed, Kind::MixedSliding],
        (Swept::Mu, _) => vec![Kind::MixedSliding],
        (Swept::K, Sliding) => vec![Kind::RotationalMixed, Kind::MixedSliding],
        (Swept::K, _) => vec![Kind::RotationalMixed],
    }
}

/// One located change along the sweep: a bracket no wider than the tolerance and the
/// outcomes at its ends.
struct Change {
    lo: f64,
    hi: f64,
    at_lo: Outcome,
    at_hi: Outcome,
}

/// The swept parameter as a bisection variable: φ = atan μ for μ (so that μ = ∞ is an end
/// like any other), K itself for K.
fn to_t(swept: Swept, x: f64) -> f64 {
    match swept {
        Swept::Mu => x.atan(),
        Swept::K => x,
    }
}

fn to_x(swept: Swept, t: f64) -> f64 {
    match swept {
        Swept::Mu if t >= FRAC_PI_2 => f64::INFINITY,
        Swept::Mu => t.tan(),
        Swept::K => t,
    }
}

/// Every change of outcome between x0 (outcome o0) and x1 (outcome o1), by bisection.
fn changes(
    swept: Swept,
    (x0, o0): (f64, Outcome),
    (x1, o1): (f64, Outcome),
    tol: f64,
    eval: &dyn Fn(f64) -> Outcome,
) -> Vec<Change> {
    let mut out = Vec::new();
    let (mut lo, mut at_lo) = (to_t(swept, x0), o0);
    // Each round locates the first change above `lo`; a sweep cell holds at most a few.
    for _ in 0..4 {
        let (mut hi, mut at_hi) = (to_t(swept, x1), o1);
        let mut steps = 0;
        while to_x(swept, hi) - to_x(swept, lo) > tol && steps < 200 {
            let mid = 0.5 * (lo + hi);
            let o = eval(to_x(swept, mid));
            if o == at_lo {
                lo = mid;
            } else {
                (hi, at_hi) = (mid, o);
            }
            steps += 1;
        }
        out.push(Change {
            lo: to_x(swept, lo),
            hi: to_x(swept, hi),
            at_lo,
            at_hi,
        });
        if at_hi == o1 {
            break;
        }
        (lo, at_lo) = (hi, at_hi);
    }
    out
}

/// The state with every joint of two states (the one on the lower-μ side first).
fn union(a: &CriticalState, b: &CriticalState) -> CriticalState {
    let mut hinges = a.mechanism.hinges.clone();
    for h in &b.mechanism.hinges {
        if !hinges
            .iter()
            .any(|g| g.face == h.face && (g.angle_deg - h.angle_deg).abs() < 1e-6)
        {
            hinges.push(*h);
        }
    }
    let mut sliding = a.mechanism.sliding_joints.clone();
    for s in &b.mechanism.sliding_joints {
        if !sliding
            .iter()
            .any(|g| (g.angle_deg - s.angle_deg).abs() < 1e-6)
        {
            sliding.push(*s);
        }
    }
    let mut out = a.clone();
    if let Some(m) = Mechanism::from_parts(hinges, sliding) {
        out.mechanism = m;
    }
    out
}

/// Bifurcations of one sweep of one grid.
fn sweep(grid: &Grid, swept: Swept, tol: f64, lm: &Landmarks) -> Vec<Bifurcation> {
    let line: Vec<(f64, Option<Outcome>)> = match swept {
        Swept::Mu => (0..grid.mus.len())
            .map(|j| (grid.mus[j], stored_outcome(grid.cell(0, j))))
            .collect(),
        Swept::K => (0..grid.ks.len())
            .map(|i| (grid.ks[i], stored_outcome(grid.cell(i, 0))))
            .collect(),
    };
    let critical = |x: f64| match swept {
        Swept::Mu => lm.probe.thickness(x),
        Swept::K => lm.probe.friction(x),
    };
    let eval = |x: f64| outcome(&critical(x));
    let mut out: Vec<Bifurcation> = Vec::new();
    let mut seen: Vec<Kind> = Vec::new();
    for w in line.windows(2) {
        let ((x0, Some(o0)), (x1, Some(o1))) = (w[0], w[1]) else {
            continue;
        };
        if o0 == o1 {
            continue;
        }
        for ch in changes(swept, (x0, o0), (x1, o1), tol, &eval) {
            let mut confirmed = false;
            for kind in kinds(swept, ch.at_lo, ch.at_hi) {
                let Some(state) = lm.state(kind) else {
                    continue;
                };
                let x = match swept {
                    Swept::Mu => state.mu,
                    Swept::K => state.k,
                };
                // The critical states decide their mechanism with a small activity
                // tolerance, so the bisection may stop a little past the exact point.
                let s = slack(tol, x) + 1e-7 * (1.0 + x.abs());
                if x >= ch.lo - s && x <= ch.hi + s {
                    confirmed = true;
                    if !seen.contains(&kind) {
                        seen.push(kind);
                        out.push(record(grid, kind, state));
                    }
                }
            }
            if !confirmed
                && let (Outcome::Found(ka), Outcome::Found(kb)) = (ch.at_lo, ch.at_hi)
                && let (Some(sa), Some(sb)) = (
                    critical(ch.lo).found().cloned(),
                    critical(ch.hi).found().cloned(),
                )
            {
                // Lower-μ side first: the low end of a μ sweep, the high end of a K sweep.
                let ((ma, sa), (mb, sb)) = match swept {
                    Swept::Mu => ((ka, sa), (kb, sb)),
                    Swept::K => ((kb, sb), (ka, sa)),
                };
                let state = union(&sa, &sb);
                out.push(Bifurcation {
                    load_case: grid.load_case,
                    half_angle_deg: grid.arch.half_angle_deg(),
                    voussoirs: grid.arch.joints.voussoirs(),
                    form: grid.scene.form,
                    at_deg: grid.scene.load.at_deg(),
                    at_x: grid.scene.load.at_x(),
                    axis: None,
                    load_factor: None,
                    k: state.k,
                    mu: state.mu,
                    mechanism_a: ma,
                    mechanism_b: mb,
                    state,
                });
            }
        }
    }
    merge_coincident(&mut out, tol);
    out.sort_by(|a, b| a.k.total_cmp(&b.k));
    out
}

/// Bifurcations of every grid of a `thickness` (swept μ) or `friction` (swept K) study.
pub(crate) fn locate(
    grids: &[Grid],
    swept: Swept,
    tol: f64,
    counter: &Counter,
) -> Vec<Bifurcation> {
    grids
        .iter()
        .flat_map(|g| {
            let lm = Landmarks::new(Probe::new(g.arch, counter));
            sweep(g, swept, tol, &lm)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use MechanismKind::*;

    #[test]
    fn changes_of_outcome_name_their_bifurcations() {
        let f = Outcome::Found;
        assert_eq!(
            kinds(Swept::Mu, f(Mixed), f(Rotational)),
            vec![Kind::RotationalMixed]
        );
        assert_eq!(
            kinds(Swept::Mu, Outcome::Never, f(Mixed)),
            vec![Kind::MixedSliding]
        );
        assert_eq!(
            kinds(Swept::K, Outcome::Never, f(Mixed)),
            vec![Kind::RotationalMixed]
        );
        assert_eq!(
            kinds(Swept::K, f(Mixed), f(Sliding)),
            vec![Kind::MixedSliding]
        );
        assert!(kinds(Swept::K, f(Mixed), Outcome::Always).is_empty());
    }

    #[test]
    fn bisection_finds_every_change_in_a_cell() {
        let f = Outcome::Found;
        let eval = |x: f64| {
            if x < 0.3 {
                Outcome::Never
            } else if x < 0.4 {
                f(Mixed)
            } else {
                f(Rotational)
            }
        };
        let c = changes(
            Swept::Mu,
            (0.1, Outcome::Never),
            (f64::INFINITY, f(Rotational)),
            1e-9,
            &eval,
        );
        assert_eq!(c.len(), 2);
        assert!((c[0].lo - 0.3).abs() < 1e-9 && c[0].hi - c[0].lo <= 1e-9);
        assert_eq!((c[0].at_lo, c[0].at_hi), (Outcome::Never, f(Mixed)));
        assert!((c[1].hi - 0.4).abs() < 1e-9);
        assert_eq!((c[1].at_lo, c[1].at_hi), (f(Mixed), f(Rotational)));
    }
}
