//! Bifurcation points of the collapse curve, characterised by the analysis (paper §5).
//!
//! Under symmetric self-weight the collapse curve of an arch has at most three parts, in
//! order of decreasing μ: rotational (H^r has shrunk to a single thrust h_r, at the
//! rotational K_c, and h_r lies inside H^s), mixed (H^r and H^s touch at an end of each) and
//! sliding (H^s has shrunk to a single thrust h_s, at μ_min, and h_s lies inside H^r). Hence
//! two kinds of bifurcation:
//! - rotational/mixed: the rotational collapse state at the μ where h_r reaches the edge of
//!   H^s, i.e. μ_c at the rotational K_c ([`Landmarks::rotational_mixed`]);
//! - mixed/sliding: the collapse thickness at μ_min, where h_s reaches the edge of H^r
//!   ([`Landmarks::mixed_sliding`]).
//!
//! Which of them a study contains is read from the mechanism changes between consecutive
//! located collapse points, and each is confirmed by a bracketing search between those
//! points on its own continuous margin (h_r inside H^s(μ); h_s inside H^r(K)).

use super::grid::Grid;
use super::probe::{Probe, root, thrust_inside};
use super::{Bifurcation, BoundaryPoint};
use crate::analysis::MechanismKind;
use crate::analysis::symmetric::CriticalState;
use std::sync::OnceLock;

/// The two kinds of bifurcation of a symmetric arch.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kind {
    /// Rotational and mixed mechanisms coexist (paper Fig. 6).
    RotationalMixed,
    /// Mixed and sliding mechanisms coexist (paper Fig. 7).
    MixedSliding,
}

impl Kind {
    /// (mechanism on the lower-μ side, mechanism on the higher-μ side).
    fn mechanisms(self) -> (MechanismKind, MechanismKind) {
        match self {
            Kind::RotationalMixed => (MechanismKind::Mixed, MechanismKind::Rotational),
            Kind::MixedSliding => (MechanismKind::Sliding, MechanismKind::Mixed),
        }
    }
}

/// The critical states of one arch that organise its regime map, each computed once.
pub(crate) struct Landmarks<'a> {
    /// Counted analyses of the arch.
    pub probe: Probe<'a>,
    rotational: OnceLock<Option<CriticalState>>,
    sliding: OnceLock<Option<CriticalState>>,
    rotational_mixed: OnceLock<Option<CriticalState>>,
    mixed_sliding: OnceLock<Option<CriticalState>>,
}

impl<'a> Landmarks<'a> {
    /// The landmarks of the probe's arch (nothing is computed until asked for).
    pub fn new(probe: Probe<'a>) -> Self {
        Landmarks {
            probe,
            rotational: OnceLock::new(),
            sliding: OnceLock::new(),
            rotational_mixed: OnceLock::new(),
            mixed_sliding: OnceLock::new(),
        }
    }

    /// The rotational limit state: K_c at infinite friction, where H^r shrinks to a point.
    pub fn rotational(&self) -> Option<&CriticalState> {
        self.rotational
            .get_or_init(|| self.probe.thickness(f64::INFINITY).found().cloned())
            .as_ref()
    }

    /// The sliding threshold state: μ_min, where H^s shrinks to a point.
    pub fn sliding(&self) -> Option<&CriticalState> {
        self.sliding
            .get_or_init(|| self.probe.sliding_threshold().found().cloned())
            .as_ref()
    }

    /// The rotational/mixed bifurcation: μ_c at the rotational K_c, with every joint active.
    pub fn rotational_mixed(&self) -> Option<&CriticalState> {
        self.rotational_mixed
            .get_or_init(|| {
                // `friction` at K_c itself locates μ against the plateau of the margin, so the
                // rotational state's own K is used, no nudge.
                let k = self.rotational()?.k;
                self.probe.friction(k).found().cloned()
            })
            .as_ref()
    }

    /// The mixed/sliding bifurcation: K_c at μ_min, with every joint active.
    pub fn mixed_sliding(&self) -> Option<&CriticalState> {
        self.mixed_sliding
            .get_or_init(|| {
                let mu = self.sliding()?.mu;
                // μ_min is on the feasible side of its root; tan(atan μ) may round it just
                // below, where H^s is empty: step up a few ulps if so.
                [0.0, 4.0, 16.0, 64.0].into_iter().find_map(|n| {
                    let m = mu * (1.0 + n * f64::EPSILON);
                    self.probe.thickness(m).found().cloned()
                })
            })
            .as_ref()
    }

    /// The coexisting state of a kind of bifurcation.
    pub fn state(&self, kind: Kind) -> Option<&CriticalState> {
        match kind {
            Kind::RotationalMixed => self.rotational_mixed(),
            Kind::MixedSliding => self.mixed_sliding(),
        }
    }
}

/// A bifurcation record of a grid's arch.
pub(crate) fn record(grid: &Grid, kind: Kind, state: &CriticalState) -> Bifurcation {
    let (a, b) = kind.mechanisms();
    Bifurcation {
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
        mechanism_a: a,
        mechanism_b: b,
        state: state.clone(),
    }
}

/// Largest distance between a characterised point and the located one that still counts as
/// the same point.
pub(crate) fn slack(tol: f64, x: f64) -> f64 {
    2.0 * tol + 1e-12 * (1.0 + x.abs())
}

/// Confirms by a bracketing search that the root of margin `f` in [lo, hi] is `x` (within
/// the tolerance); without a sign change in the bracket, that `x` lies in it.
fn confirm(mut f: impl FnMut(f64) -> f64, lo: f64, hi: f64, x: f64, tol: f64) -> bool {
    let s = slack(tol, x);
    let (g_lo, g_hi) = (f(lo) >= 0.0, f(hi) >= 0.0);
    if g_lo != g_hi {
        root(f, lo, hi, g_hi, tol).is_some_and(|r| (r - x).abs() <= s)
    } else {
        x >= lo - s && x <= hi + s
    }
}

/// Brackets around the rotational/mixed bifurcation in μ and the mixed/sliding one in K,
/// from consecutive collapse points whose mechanisms differ.
struct Brackets {
    rotational_mixed: Option<(f64, f64)>,
    mixed_sliding: Option<(f64, f64)>,
}

fn ordered(a: f64, b: f64) -> (f64, f64) {
    if a <= b { (a, b) } else { (b, a) }
}

/// A located point of the collapse curve: K, μ and its mechanism.
type CurvePoint = (f64, f64, MechanismKind);

/// The largest (`max`) or smallest value picked from the points by `f`.
fn extreme(curve: &[CurvePoint], f: impl Fn(&CurvePoint) -> Option<f64>, max: bool) -> Option<f64> {
    curve
        .iter()
        .filter_map(f)
        .reduce(if max { f64::max } else { f64::min })
}

fn brackets(curve: &[CurvePoint]) -> Brackets {
    use MechanismKind::*;
    let (mut want_rm, mut want_ms) = (false, false);
    for w in curve.windows(2) {
        match (w[0].2, w[1].2) {
            (Rotational, Mixed) | (Mixed, Rotational) => want_rm = true,
            (Mixed, Sliding) | (Sliding, Mixed) => want_ms = true,
            (Rotational, Sliding) | (Sliding, Rotational) => (want_rm, want_ms) = (true, true),
            _ => {}
        }
    }
    // μ between the rotational points (above) and the others (below).
    let rm = || {
        let below = extreme(curve, |p| (p.2 != Rotational).then_some(p.1), true)?;
        let above = extreme(curve, |p| (p.2 == Rotational).then_some(p.1), false)?;
        Some(ordered(below, above))
    };
    // K between the sliding points (thicker) and the others (thinner).
    let ms = || {
        let thin = extreme(curve, |p| (p.2 != Sliding).then_some(p.0), true)?;
        let thick = extreme(curve, |p| (p.2 == Sliding).then_some(p.0), false)?;
        Some(ordered(thin, thick))
    };
    Brackets {
        rotational_mixed: if want_rm { rm() } else { None },
        mixed_sliding: if want_ms { ms() } else { None },
    }
}

/// The bifurcations along the collapse curve traced by the located points of one grid.
pub(crate) fn on_collapse_curve(
    grid: &Grid,
    lm: &Landmarks,
    points: &[BoundaryPoint],
    tol: f64,
) -> Vec<Bifurcation> {
    let mut curve: Vec<CurvePoint> = points
        .iter()
        .filter(|p| p.on_collapse_curve)
        .filter_map(|p| Some((p.k, p.mu, p.mechanism?)))
        .collect();
    // Along the curve from thin arches at high friction to thick arches at low friction.
    curve.sort_by(|a, b| a.0.total_cmp(&b.0).then(b.1.total_cmp(&a.1)));
    let br = brackets(&curve);
    let mut out = Vec::new();
    if let Some((lo, hi)) = br.rotational_mixed
        && let (Some(rot), Some(co)) = (lm.rotational(), lm.rotational_mixed())
    {
        let h = rot.thrust_over_half_weight;
        if confirm(
            |mu| thrust_inside(&lm.probe.sliding(mu), h),
            lo,
            hi,
            co.mu,
            tol,
        ) {
            out.push(record(grid, Kind::RotationalMixed, co));
        }
    }
    if let Some((lo, hi)) = br.mixed_sliding
        && let (Some(sl), Some(co)) = (lm.sliding(), lm.mixed_sliding())
    {
        let h = sl.thrust_over_half_weight;
        if confirm(|k| lm.probe.rotational_margin_at(k, h), lo, hi, co.k, tol) {
            out.push(record(grid, Kind::MixedSliding, co));
        }
    }
    merge_coincident(&mut out, tol);
    out.sort_by(|a, b| a.k.total_cmp(&b.k));
    out
}

/// Two bifurcations at the same point (H^r and H^s shrink to the same thrust together) are
/// one rotational/sliding bifurcation.
pub(crate) fn merge_coincident(out: &mut Vec<Bifurcation>, tol: f64) {
    if let [a, b] = out.as_slice()
        && (a.k - b.k).abs() <= slack(tol, a.k)
        && (a.mu - b.mu).abs() <= slack(tol, a.mu)
    {
        let mut m = b.clone();
        m.mechanism_a = MechanismKind::Sliding;
        m.mechanism_b = MechanismKind::Rotational;
        *out = vec![m];
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use MechanismKind::*;

    #[test]
    fn brackets_come_from_mechanism_changes() {
        let curve = [
            (1.11, f64::INFINITY, Rotational),
            (1.11, 0.5, Rotational),
            (1.15, 0.36, Mixed),
            (1.2, 0.32, Mixed),
            (1.25, 0.309, Sliding),
        ];
        let b = brackets(&curve);
        assert_eq!(b.rotational_mixed, Some((0.36, 0.5)));
        assert_eq!(b.mixed_sliding, Some((1.2, 1.25)));
        let b = brackets(&curve[..2]);
        assert_eq!((b.rotational_mixed, b.mixed_sliding), (None, None));
        // No mixed point sampled: both kinds are looked for.
        let b = brackets(&[curve[1], curve[4]]);
        assert_eq!(b.rotational_mixed, Some((0.309, 0.5)));
        assert_eq!(b.mixed_sliding, Some((1.11, 1.25)));
    }
}
