//! The right half of a mirror-symmetric arch under symmetric loads, in the symmetric
//! unknowns: the crown shear F_y is zero and only the joints with θ ≥ 0 give rows.
//!
//! For such an arch the rows of joint −θ at (F_x, F_y, M₀) are those of joint θ at
//! (F_x, −F_y, M₀) ([`ArchGeometry::mirror_symmetric`]), so the set of (x, τ) that satisfies
//! every row is symmetric under F_y ↦ −F_y. It is convex, so with any point it holds the mean
//! of the point and its mirror image, which has F_y = 0 and the same τ: the largest τ over
//! the whole arch is attained at F_y = 0, where the left half's rows repeat the right half's.
//! The margin over the right half with F_y = 0 is therefore the margin of the whole arch,
//! with the distance to each row plane still measured in (F_x, F_y, M₀), from half the
//! joints. The rows that hold with equality in every optimal state are the same too (a row
//! slack in some optimal state is slack in the mean of that state and its mirror image), so
//! the active rows of the whole arch are those of the half and their mirror images.

use super::{ActiveRow, Settings};
use crate::analysis::statics::{ArchGeometry, Condition, Joint, Resultant};

/// The right half of a mirror-symmetric arch: the whole arch's joints and loads, with the
/// joints restricted to θ ≥ 0.
pub(super) struct HalfArch<'g, G: ?Sized>(pub(super) &'g G);

impl<G: ArchGeometry + ?Sized> ArchGeometry for HalfArch<'_, G> {
    fn half_angle(&self) -> f64 {
        self.0.half_angle()
    }

    fn joint(&self, theta: f64) -> Joint {
        self.0.joint(theta)
    }

    fn dead_load(&self, theta: f64) -> Resultant {
        self.0.dead_load(theta)
    }

    fn live_load(&self, theta: f64) -> Resultant {
        self.0.live_load(theta)
    }

    /// The joints from the crown (or the first joint right of a keystone) to the right
    /// support: the upper half of the symmetric list, taken by position so that a crown
    /// joint computed a rounding error below zero is kept.
    fn discrete_joints(&self) -> Option<Vec<f64>> {
        let mut joints = self.0.discrete_joints()?;
        let right = joints.split_off(joints.len() / 2);
        Some(right)
    }

    fn families(&self) -> Vec<[f64; 2]> {
        self.0
            .families()
            .into_iter()
            .filter(|f| f[1] >= 0.0)
            .map(|[lo, hi]| [lo.max(0.0), hi])
            .collect()
    }

    fn isolated_joints(&self) -> Vec<f64> {
        let mut joints = self.0.isolated_joints();
        joints.retain(|&t| t >= 0.0);
        joints
    }

    fn angle_deg(&self, theta: f64) -> f64 {
        self.0.angle_deg(theta)
    }

    fn relaxed(&self, theta: f64, condition: Condition) -> bool {
        self.0.relaxed(theta, condition)
    }
}

/// The settings of a problem on the half arch: the sampling of the continuum as dense as on
/// the whole arch, so half the samples and half the first joints.
pub(super) fn half_settings(settings: &Settings) -> Settings {
    Settings {
        exchange_samples: settings.exchange_samples.div_ceil(2),
        exchange_initial_joints: settings.exchange_initial_joints.div_ceil(2),
        ..*settings
    }
}

/// The active rows of the whole arch from those of its right half: each row right of the
/// crown with its mirror image. The rows are written for the part right of a joint, so a
/// sliding row changes sense at the mirror image (the crown-side part moves the same way on
/// both halves), while a hinge keeps its face.
pub(super) fn mirrored<G: ArchGeometry + ?Sized>(
    geom: &G,
    active: Vec<ActiveRow>,
) -> Vec<ActiveRow> {
    // A discrete arch names its left joints by its own parameters, which may differ from
    // the mirror images of the right ones in the last bit.
    let joints = geom.discrete_joints();
    let own = |t: f64| {
        joints
            .iter()
            .flatten()
            .copied()
            .min_by(|a, b| (a - t).abs().total_cmp(&(b - t).abs()))
            .unwrap_or(t)
    };
    let mut all = Vec::with_capacity(2 * active.len());
    for r in &active {
        let theta = own(-r.theta);
        // The crown joint is its own mirror image, also where an even voussoir count puts
        // it a rounding error right of zero.
        if r.theta > 0.0 && theta != r.theta {
            all.push(ActiveRow {
                angle_deg: geom.angle_deg(theta),
                theta,
                condition: mirror_condition(r.condition),
                slack: r.slack,
            });
        }
    }
    all.extend(active);
    all.sort_by(|a, b| a.angle_deg.total_cmp(&b.angle_deg));
    all
}

/// The condition at −θ that is the mirror image of `condition` at θ.
fn mirror_condition(condition: Condition) -> Condition {
    match condition {
        Condition::Intrados => Condition::Intrados,
        Condition::Extrados => Condition::Extrados,
        Condition::SlideOutward => Condition::SlideInward,
        Condition::SlideInward => Condition::SlideOutward,
    }
}

#[cfg(test)]
mod tests {
    //! The half route against the three-unknown programme over the whole arch, on every
    //! symmetric form: margins, critical values and their mechanisms.

    use super::super::{Critical, RowSet, friction, margin, sliding_threshold, thickness_with};
    use super::*;
    use crate::analysis::forms::ArchModel;
    use crate::model::{
        Arch, ArchForm, Discretisation, Friction, JointOrientation, Load, Shape, WeightModel,
    };
    use approx::assert_relative_eq;

    const WHOLE: Settings = Settings {
        symmetric_half: false,
        ..Settings::DEFAULT
    };
    const HALF: Settings = Settings::DEFAULT;

    /// (e, joints, keystone, weight, discretisation, α in degrees): one arch of every kind
    /// the half route takes, the crown a joint or inside a keystone.
    type Kind = (
        f64,
        JointOrientation,
        bool,
        WeightModel,
        Discretisation,
        f64,
    );

    fn kinds() -> Vec<Kind> {
        use Discretisation::{Continuum, Voussoirs};
        use JointOrientation::{Radial, Vertical};
        use WeightModel::{Annular, Centreline};
        vec![
            (0.2, Radial, false, Annular, Continuum, 90.0),
            (0.2, Radial, true, Annular, Continuum, 90.0),
            (0.1213, Radial, false, Annular, Continuum, 45.37),
            (0.0, Vertical, false, Annular, Continuum, 90.0),
            (0.0, Vertical, false, Centreline, Continuum, 80.0),
            (0.3, Vertical, false, Annular, Voussoirs(9), 90.0),
            (0.2, Radial, false, Centreline, Voussoirs(12), 90.0),
            (0.0, Radial, false, Annular, Voussoirs(11), 90.0),
            (0.0, Radial, false, Annular, Continuum, 60.0),
        ]
    }

    fn model(kind: &Kind, k: f64) -> Option<ArchModel> {
        let (e, joints, keystone, weight, disc, alpha) = *kind;
        let shape = if e == 0.0 {
            Shape::Circular
        } else {
            Shape::Pointed { eccentricity: e }
        };
        let form = ArchForm {
            shape,
            joints,
            keystone,
        };
        ArchModel::new(
            Arch::new(k, alpha, weight, disc).ok()?,
            form,
            Load::SelfWeight,
        )
        .ok()
    }

    /// Joints by angle (degrees) and face or sense (intrados, outward: true).
    type Joints = Vec<(f64, bool)>;

    /// The hinges and sliding joints of a critical state, for comparison.
    fn pattern(c: &Critical) -> (Joints, Joints) {
        let m = c
            .found()
            .and_then(|s| s.mechanism.clone())
            .expect("a mechanism");
        let h = m
            .hinges
            .iter()
            .map(|h| (h.angle_deg, h.face == crate::analysis::Face::Intrados));
        let s = m
            .sliding_joints
            .iter()
            .map(|s| (s.angle_deg, s.sense == crate::analysis::Sense::Outward));
        (h.collect(), s.collect())
    }

    fn assert_same_pattern(half: &Critical, whole: &Critical, what: &str) {
        let (hh, hs) = pattern(half);
        let (wh, ws) = pattern(whole);
        assert_eq!(hh.len(), wh.len(), "{what}: hinges {hh:?} against {wh:?}");
        assert_eq!(hs.len(), ws.len(), "{what}: sliding {hs:?} against {ws:?}");
        for (a, b) in hh.iter().zip(&wh).chain(hs.iter().zip(&ws)) {
            assert_eq!(a.1, b.1, "{what}: {hh:?} {hs:?} against {wh:?} {ws:?}");
            // A hinge sits where a joint's violation has a flat maximum: a margin known to
            // 1e-13 places it to about √1e-13 rad, 2e-5°.
            assert!(
                (a.0 - b.0).abs() <= 1e-4,
                "{what}: {hh:?} {hs:?} against {wh:?} {ws:?}"
            );
        }
    }

    #[test]
    fn half_margins_equal_whole_margins() {
        for kind in kinds() {
            for k in [1.08, 1.15, 1.3] {
                let Some(m) = model(&kind, k) else { continue };
                assert!(m.mirror_symmetric());
                for mu in [0.2, 0.45, 1.5] {
                    let phi = f64::atan(mu);
                    for set in [RowSet::Rotational, RowSet::Sliding, RowSet::All] {
                        let h = margin(&m, phi, set, &HALF);
                        let w = margin(&m, phi, set, &WHOLE);
                        assert_eq!(h.outcome, w.outcome, "{kind:?} K {k} μ {mu} {set:?}");
                        assert!(
                            (h.margin - w.margin).abs() <= 1e-11,
                            "{kind:?} K {k} μ {mu} {set:?}: {} against {}",
                            h.margin,
                            w.margin
                        );
                        assert_eq!(h.crown.shear_over_half_weight, 0.0);
                        // Half the joints: fewer rows in the final programme.
                        assert!(
                            h.rows < w.rows,
                            "{kind:?}: {} rows against {}",
                            h.rows,
                            w.rows
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn half_critical_values_and_mechanisms_equal_whole_ones() {
        for kind in kinds() {
            let make = |k: f64| model(&kind, k);
            let k_max = 3.0;
            for mu in [f64::INFINITY, 0.6, 0.4] {
                let f = if mu.is_finite() {
                    Friction::new(mu).unwrap()
                } else {
                    Friction::INFINITE
                };
                let h = thickness_with(make, k_max, None, f, &HALF);
                let w = thickness_with(make, k_max, None, f, &WHOLE);
                match (h.found(), w.found()) {
                    (Some(hs), Some(ws)) => {
                        let (kh, kw) = (hs.k.unwrap(), ws.k.unwrap());
                        assert_relative_eq!(kh, kw, max_relative = 1e-10);
                        assert_same_pattern(&h, &w, &format!("{kind:?} K_c at μ {mu}"));
                        // μ_c at each route's own K_c (at μ = ∞ the bifurcation friction,
                        // on the knife edge where the rotational margin is zero): the same
                        // friction both ways.
                        let fh = friction(&model(&kind, kh).unwrap(), &HALF);
                        let fw = friction(&model(&kind, kw).unwrap(), &WHOLE);
                        if let (Some(a), Some(b)) = (fh.found(), fw.found()) {
                            assert_relative_eq!(a.mu, b.mu, max_relative = 1e-9);
                        } else {
                            assert_eq!(
                                fh.found().is_some(),
                                fw.found().is_some(),
                                "{kind:?} μ {mu} K {kh}: {fh:?} against {fw:?}"
                            );
                        }
                    }
                    _ => assert_eq!(
                        std::mem::discriminant(&h),
                        std::mem::discriminant(&w),
                        "{kind:?} μ {mu}: {h:?} against {w:?}"
                    ),
                }
            }
            let m = model(&kind, 1.25).unwrap();
            let (h, w) = (sliding_threshold(&m, &HALF), sliding_threshold(&m, &WHOLE));
            let (a, b) = (h.found().unwrap().mu, w.found().unwrap().mu);
            assert_relative_eq!(a, b, max_relative = 1e-9);
            assert_same_pattern(&h, &w, &format!("{kind:?} μ_min"));
        }
    }

    /// An even voussoir count whose crown joint is computed a rounding error right of zero
    /// (α = 90°, 26 voussoirs; α = 100°, 10): the crown is not mirrored onto itself, so no
    /// row is active twice, and the collapse thickness is that of the whole arch.
    #[test]
    fn a_crown_joint_right_of_zero_is_its_own_mirror_image() {
        use crate::analysis::statics::ArchGeometry;
        for (alpha, n) in [(90.0, 26), (100.0, 10)] {
            let kind = (
                0.0,
                JointOrientation::Radial,
                false,
                WeightModel::Annular,
                Discretisation::Voussoirs(n),
                alpha,
            );
            let crown = model(&kind, 1.2)
                .unwrap()
                .discrete_joints()
                .unwrap()
                .into_iter()
                .find(|t| t.abs() < 1e-9)
                .unwrap();
            assert!(crown > 0.0, "α {alpha}, {n} voussoirs: crown at {crown}");
            let make = |k: f64| model(&kind, k);
            let h = thickness_with(make, 3.0, None, Friction::INFINITE, &HALF);
            let w = thickness_with(make, 3.0, None, Friction::INFINITE, &WHOLE);
            let (hs, ws) = (h.found().unwrap(), w.found().unwrap());
            assert_relative_eq!(hs.k.unwrap(), ws.k.unwrap(), max_relative = 1e-10);
            let rows: Vec<_> = hs
                .state
                .active
                .iter()
                .map(|r| (r.theta, r.condition))
                .collect();
            for (i, a) in rows.iter().enumerate() {
                assert!(
                    !rows[..i].contains(a),
                    "α {alpha}, {n}: {a:?} twice in {rows:?}"
                );
            }
            assert_same_pattern(&h, &w, &format!("α {alpha}, {n} voussoirs"));
        }
    }

    #[test]
    fn live_loads_and_shared_apex_loads_are_not_mirror_symmetric() {
        let kind = kinds()[0];
        let (e, joints, keystone, weight, disc, alpha) = kind;
        let arch = Arch::new(1.2, alpha, weight, disc).unwrap();
        let form = ArchForm {
            shape: Shape::Pointed { eccentricity: e },
            joints,
            keystone,
        };
        for load in [Load::Horizontal, Load::point(30.0), Load::point(0.0)] {
            let m = ArchModel::new(arch, form, load).unwrap();
            assert!(!m.mirror_symmetric(), "{load:?}");
            assert!(!m.with_shared_apex().mirror_symmetric(), "{load:?}");
        }
    }
}
