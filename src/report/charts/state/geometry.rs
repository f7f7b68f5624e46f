//! The geometry of a drawn state, from the general statics of its own arch, form and load
//! ([`ArchModel`]): the outline (two circular arcs per half, about centres offset by
//! d = e(1 + K)/2 for a pointed arch), the joints between voussoirs and the supports as the
//! model defines them (radial or vertical), hinges and sliding joints at the model's joints,
//! and the live load at its point.

use crate::analysis::forms::ArchModel;
use crate::analysis::statics::Condition;
use crate::analysis::statics::{ArchGeometry, Joint};
use crate::figdata::general::{active_joint_parameter, model_of_state};
use crate::plot::state::{DrawnHinge, DrawnJoint, DrawnLoad, DrawnSlide, DrawnSupport, Xy};
use crate::report::format::short;
use crate::store::StateRow;

/// Points per arc of the outline.
const ARC_POINTS: usize = 180;

/// Everything a state drawing takes from the arch.
#[derive(Debug, Clone, PartialEq)]
pub struct StateGeometry {
    /// The closed outline.
    pub outline: Vec<Xy>,
    /// Joints between voussoirs.
    pub voussoir_joints: Vec<DrawnJoint>,
    /// Supports, left then right.
    pub supports: [DrawnSupport; 2],
    /// Hinges.
    pub hinges: Vec<DrawnHinge>,
    /// Sliding joints.
    pub sliding: Vec<DrawnSlide>,
    /// The live load.
    pub load: Option<DrawnLoad>,
    /// Why nothing is drawn, when the row names no valid arch.
    pub note: Option<String>,
}

fn xy(p: [f64; 2]) -> Xy {
    (p[0], p[1])
}

/// The outline of the arch: the intrados from the left springing over the apex to the right
/// springing, then the extrados back. The right half is the part of the annulus 1 ≤ ρ ≤ K
/// about (−d, 0) with x ≥ 0, from its apex (ψ₁ = asin d on the intrados, asin(d/K) on the
/// extrados) to the springing at ψ = α; the left half is its mirror image.
pub fn outline(model: &ArchModel) -> Vec<Xy> {
    let alpha = model.arch().half_angle;
    let k = model.arch().k;
    let psi_1 = model.first_joint();
    let d = psi_1.sin();
    let psi_e = (d / k).asin();
    let arc = |rho: f64, from: f64, to: f64| -> Vec<Xy> {
        (0..=ARC_POINTS)
            .map(|i| {
                let psi = from + (to - from) * i as f64 / ARC_POINTS as f64;
                (-d + rho * psi.sin(), rho * psi.cos())
            })
            .collect()
    };
    let mirror = |v: Vec<Xy>| -> Vec<Xy> { v.into_iter().rev().map(|p| (-p.0, p.1)).collect() };
    let right_in = arc(1.0, psi_1, alpha);
    let right_ex = arc(k, alpha, psi_e);
    let mut out = mirror(right_in.clone());
    out.extend(right_in);
    out.extend(right_ex.iter().copied());
    out.extend(mirror(right_ex));
    out.dedup_by(|a, b| (a.0 - b.0).abs() < 1e-12 && (a.1 - b.1).abs() < 1e-12);
    out
}

fn drawn(model: &ArchModel, j: &Joint) -> DrawnJoint {
    DrawnJoint {
        intrados: xy(j.intrados),
        extrados: xy(j.extrados),
        angle_deg: model.angle_deg(j.theta),
    }
}

fn support(model: &ArchModel, side: f64) -> DrawnSupport {
    let j = model.joint(model.arch().half_angle.next_up() * side);
    let n = j.normal();
    DrawnSupport {
        intrados: xy(j.intrados),
        extrados: xy(j.extrados),
        into_ground: (side * n[0], side * n[1]),
    }
}

/// Arrows drawn over a patch load, its ends included.
const PATCH_ARROWS: usize = 6;

/// The live load of the state, labelled with its λ.
fn load(model: &ArchModel, s: &StateRow) -> Option<DrawnLoad> {
    let label = format!("λ = {}", s.load_factor.map_or("—".into(), short));
    match s.load.as_str() {
        "point" => {
            if let Some([x0, x1]) = model.patch_load() {
                let at = (0..PATCH_ARROWS)
                    .map(|i| {
                        let x = x0 + (x1 - x0) * i as f64 / (PATCH_ARROWS - 1) as f64;
                        xy(model.extrados_above(x))
                    })
                    .collect();
                return Some(DrawnLoad::Patch { at, label });
            }
            // The load's own extrados point (on a keystone or on the springing wedge of a
            // vertical-joint arch it is not the extrados end of a joint).
            let (_, at) = model.point_load()?;
            Some(DrawnLoad::Point { at: xy(at), label })
        }
        "horizontal" => {
            // Arrows onto the extrados of the left half, the side the force pushes from.
            let (a, p) = (model.arch().half_angle, model.first_joint());
            let at = [0.3, 0.6, 0.9]
                .iter()
                .map(|&f: &f64| xy(model.joint(-(p + f * (a - p))).extrados))
                .collect();
            Some(DrawnLoad::Horizontal { at, label })
        }
        _ => None,
    }
}

/// The geometry of a state row's arch with its hinges, sliding joints and load.
pub fn of_state(s: &StateRow) -> StateGeometry {
    let model = match model_of_state(s) {
        Ok(m) => m,
        Err(e) => {
            let none = DrawnSupport {
                intrados: (0.0, 0.0),
                extrados: (0.0, 0.0),
                into_ground: (0.0, -1.0),
            };
            return StateGeometry {
                outline: Vec::new(),
                voussoir_joints: Vec::new(),
                supports: [none, none],
                hinges: Vec::new(),
                sliding: Vec::new(),
                load: None,
                note: Some(format!("{e:#}")),
            };
        }
    };
    let joints = model.discrete_joints().unwrap_or_default();
    let inner = joints.len().saturating_sub(1);
    let voussoir_joints = joints
        .iter()
        .take(inner)
        .skip(1)
        .map(|&t| drawn(&model, &model.joint(t)))
        .collect();
    let hinges = s
        .joints
        .hinge_angles_deg
        .iter()
        .zip(&s.joints.hinge_faces)
        .map(|(&a, f)| {
            let face = if f == "extrados" {
                Condition::Extrados
            } else {
                Condition::Intrados
            };
            let theta = active_joint_parameter(&model, s, a, &[face]);
            DrawnHinge {
                joint: drawn(&model, &model.joint(theta)),
                extrados: f == "extrados",
            }
        })
        .collect();
    let sliding = s
        .joints
        .sliding_angles_deg
        .iter()
        .zip(&s.joints.sliding_senses)
        .map(|(&a, sense)| {
            let slides = [Condition::SlideOutward, Condition::SlideInward];
            let j = model.joint(active_joint_parameter(&model, s, a, &slides));
            let n = j.normal();
            // The normal points from the left part into the right one: the crown lies to the
            // left of a joint of the right half.
            let side = if a >= 0.0 { -1.0 } else { 1.0 };
            DrawnSlide {
                joint: drawn(&model, &j),
                outward: sense == "outward",
                crown_side: (side * n[0], side * n[1]),
            }
        })
        .collect();
    StateGeometry {
        outline: outline(&model),
        voussoir_joints,
        supports: [support(&model, -1.0), support(&model, 1.0)],
        hinges,
        sliding,
        load: load(&model, s),
        note: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(k: f64, e: f64, joints: &str, load: &str, at_deg: Option<f64>) -> StateRow {
        StateRow {
            state_id: "t".into(),
            k,
            half_angle_deg: 90.0,
            weight: "annular".into(),
            voussoirs: Some(6),
            shape: if e > 0.0 { "pointed" } else { "circular" }.into(),
            eccentricity: e,
            joint_orientation: joints.into(),
            load: load.into(),
            at_deg,
            load_factor: Some(0.25),
            ..StateRow::default()
        }
    }

    fn near(p: Xy, q: Xy) -> bool {
        (p.0 - q.0).abs() < 1e-12 && (p.1 - q.1).abs() < 1e-12
    }

    #[test]
    fn a_vertical_joint_arch_slides_on_its_vertical_sections_and_hinges_at_its_supports() {
        // The critical friction at K = 1.1158 (the rotational/mixed bifurcation): sliding at
        // ±90° and hinges at ±90° extrados, where 90° names both the vertical section x = ±1
        // and the radial support beyond it.
        use crate::model::{
            Arch, ArchForm, Discretisation, Friction, JointOrientation, Load, Shape, WeightModel,
        };
        use crate::scene::{self, Find, Scene};
        let k = 1.1158;
        let arch = Arch::new(k, 90.0, WeightModel::Annular, Discretisation::Continuum).unwrap();
        let sol = scene::solve(&Scene {
            arch,
            friction: Friction::new(f64::INFINITY).unwrap(),
            find: Find::Friction,
            form: ArchForm {
                shape: Shape::Circular,
                joints: JointOrientation::Vertical,
                keystone: false,
            },
            load: Load::SelfWeight,
            lambda: 0.0,
        });
        let mut r = row(k, 0.0, "vertical", "self_weight", None);
        r.voussoirs = None;
        r.mu = sol.mu_crit.unwrap();
        r.load_factor = None;
        r.thrust_over_half_weight = sol.thrust_over_half_weight;
        r.crown_moment = sol.crown_moment;
        r.crown_shear = sol.crown_shear;
        r.joints.hinge_angles_deg = sol.hinges.iter().map(|h| h.angle_deg).collect();
        r.joints.hinge_faces = sol.hinges.iter().map(|h| h.face.as_str().into()).collect();
        r.joints.sliding_angles_deg = sol.sliding_joints.iter().map(|j| j.angle_deg).collect();
        r.joints.sliding_senses = (sol.sliding_joints.iter())
            .map(|j| j.sense.as_str().into())
            .collect();
        assert_eq!(r.joints.sliding_angles_deg, vec![-90.0, 90.0]);
        let g = of_state(&r);
        for slide in &g.sliding {
            let j = &slide.joint;
            assert!((j.intrados.0.abs() - 1.0).abs() < 1e-12, "{j:?}");
            assert!(
                (j.extrados.0 - j.intrados.0).abs() < 1e-12,
                "not vertical: {j:?}"
            );
        }
        let springing_hinges = (g.hinges.iter())
            .filter(|h| h.joint.intrados.1.abs() < 1e-12)
            .count();
        assert_eq!(springing_hinges, 2, "{:?}", g.hinges);
        for h in g.hinges.iter().filter(|h| h.joint.intrados.1.abs() < 1e-12) {
            assert!((h.joint.extrados.0.abs() - k).abs() < 1e-12, "{h:?}");
        }
    }

    #[test]
    fn pointed_outline_meets_at_the_analytic_apexes() {
        // Intrados arcs of radius 1 about (∓d, 0), d = e(1 + K)/2: they meet on x = 0 at
        // height √(1 − d²); the extrados arcs (radius K) at √(K² − d²).
        let (k, e) = (1.3, 0.2);
        let d = e * (1.0 + k) / 2.0;
        for joints in ["radial", "vertical"] {
            let g = of_state(&row(k, e, joints, "self_weight", None));
            // The intrados: the points at distance 1 from the centre of their own half.
            let top_in = g
                .outline
                .iter()
                .filter(|p| ((p.0.abs() + d).hypot(p.1) - 1.0).abs() < 1e-12)
                .fold(f64::NEG_INFINITY, |m, p| m.max(p.1));
            assert!((top_in - (1.0 - d * d).sqrt()).abs() < 1e-12, "{top_in}");
            assert!(
                g.outline
                    .iter()
                    .any(|&p| near(p, (0.0, (1.0 - d * d).sqrt())))
            );
            assert!(
                g.outline
                    .iter()
                    .any(|&p| near(p, (0.0, (k * k - d * d).sqrt())))
            );
            // Springings: the radial support joints at ψ = 90° about (±d, 0).
            let [l, r] = g.supports;
            assert!(near(r.intrados, (1.0 - d, 0.0)) && near(r.extrados, (k - d, 0.0)));
            assert!(near(l.intrados, (d - 1.0, 0.0)) && near(l.extrados, (d - k, 0.0)));
            assert!((r.into_ground.1 + 1.0).abs() < 1e-12 && (l.into_ground.1 + 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn joints_are_drawn_radial_or_vertical_as_the_model_defines_them() {
        let (k, e) = (1.3, 0.2);
        let d = e * (1.0 + k) / 2.0;
        let radial = of_state(&row(k, e, "radial", "self_weight", None));
        let vertical = of_state(&row(k, e, "vertical", "self_weight", None));
        assert_eq!(radial.voussoir_joints.len(), 5);
        assert_eq!(vertical.voussoir_joints.len(), 5);
        for j in &vertical.voussoir_joints {
            assert!((j.intrados.0 - j.extrados.0).abs() < 1e-12, "{j:?}");
        }
        for j in radial.voussoir_joints.iter().filter(|j| j.angle_deg != 0.0) {
            // On the line through the centre of its own half, (∓d, 0).
            let c = if j.intrados.0 > 0.0 { -d } else { d };
            let cross = (j.intrados.0 - c) * j.extrados.1 - (j.extrados.0 - c) * j.intrados.1;
            assert!(cross.abs() < 1e-12, "{j:?}");
        }
        // Every joint end lies on the outline's arcs.
        for j in radial
            .voussoir_joints
            .iter()
            .chain(&vertical.voussoir_joints)
        {
            let c = if j.intrados.0 >= 0.0 { -d } else { d };
            assert!(((j.intrados.0 - c).hypot(j.intrados.1) - 1.0).abs() < 1e-12);
            assert!(((j.extrados.0 - c).hypot(j.extrados.1) - k).abs() < 1e-12);
        }
    }

    #[test]
    fn a_point_load_is_drawn_at_the_extrados_end_of_its_joint() {
        let (k, e) = (1.3, 0.2);
        let d = e * (1.0 + k) / 2.0;
        let t = (-40.0f64).to_radians();
        let g = of_state(&row(k, e, "radial", "point", Some(-40.0)));
        let Some(DrawnLoad::Point { at, label }) = g.load else {
            panic!("no point load");
        };
        assert!(near(at, (d + k * t.sin(), k * t.cos())), "{at:?}");
        assert_eq!(label, "λ = 0.2500");
        let g = of_state(&row(k, e, "vertical", "point", Some(-40.0)));
        let Some(DrawnLoad::Point { at, .. }) = g.load else {
            panic!("no point load");
        };
        // The top of the vertical joint through the intrados point at ψ = 40°.
        assert!((at.0 - (d + t.sin())).abs() < 1e-12, "{at:?}");
        assert!(((at.0 - d).hypot(at.1) - k).abs() < 1e-12, "{at:?}");
        let g = of_state(&row(k, 0.0, "radial", "horizontal", None));
        assert!(
            matches!(g.load, Some(DrawnLoad::Horizontal { ref at, .. }) if at.len() == 3 && at.iter().all(|p| p.0 < 0.0))
        );
    }
}
