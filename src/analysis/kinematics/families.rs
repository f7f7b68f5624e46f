//! The paper's families of one-degree-of-freedom mechanisms (Figs. 3, 4, 5) for any arch.
//!
//! A whole arch with rigid blocks moves with one degree of freedom when
//! - four hinges cut it into three blocks (Fig. 3): their faces alternate, and the two
//!   opposite modes are E I E I and I E I E from left to right;
//! - one sliding joint and three alternating hinges cut it (Fig. 4), the slide at a
//!   springing or between two hinges, or a hinge that also slides (La Hire) with two more
//!   hinges; each of the three couplings in its two opposite modes gives six families;
//! - three sliding joints cut it into two translating blocks (Fig. 5), the middle block
//!   driven inward or outward: two families.
//!
//! Joint positions are fractions of the half-embrace angle α (−1 and 1 are the springings),
//! so the same families exist for segmental and horseshoe arches; [`REPRESENTATIVE`] is a
//! generic choice where every family is admissible for K from 1.02 to 3 and α from 60° to
//! 150°. The velocity field of each family is its one mode, signed by normality at the hinges
//! (the sliding families by the sense given to their last joint).

use super::{
    ActiveJoint, FlowRule, KinematicsError, KinematicsSettings, ModeStatus, Modes,
    mechanism_modes_with,
};
use crate::analysis::statics::ArchGeometry;
use crate::analysis::types::{Face, MechanismKind, Sense};

/// One joint of a family template: position as a fraction of α and its role.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TemplateJoint {
    /// θ/α, in [−1, 1].
    pub fraction: f64,
    /// Face of the hinge, if the joint rotates.
    pub hinge: Option<Face>,
    /// True when the joint slides.
    pub slides: bool,
    /// Required sense of sliding (used to orient the purely sliding families).
    pub sense: Option<Sense>,
}

const fn h(fraction: f64, face: Face) -> TemplateJoint {
    TemplateJoint {
        fraction,
        hinge: Some(face),
        slides: false,
        sense: None,
    }
}

const fn s(fraction: f64, sense: Option<Sense>) -> TemplateJoint {
    TemplateJoint {
        fraction,
        hinge: None,
        slides: true,
        sense,
    }
}

const fn lh(fraction: f64, face: Face) -> TemplateJoint {
    TemplateJoint {
        fraction,
        hinge: Some(face),
        slides: true,
        sense: None,
    }
}

/// A family of mechanisms: its name, the paper's figure and its joints.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FamilyTemplate {
    /// Stable identifier, filename-safe (e.g. `mixed-inner-b`).
    pub id: &'static str,
    /// Figure of the paper it belongs to (3, 4 or 5).
    pub figure: u8,
    /// Rotational, mixed or sliding.
    pub kind: MechanismKind,
    /// A one-line description (pattern of faces left to right: E extrados, I intrados,
    /// S sliding, LH La Hire).
    pub description: &'static str,
    /// The joints, left to right.
    pub joints: &'static [TemplateJoint],
}

use Face::{Extrados as E, Intrados as I};

/// The ten families at representative positions (fractions of α).
pub const REPRESENTATIVE: [FamilyTemplate; 10] = [
    FamilyTemplate {
        id: "rotational-a",
        figure: 3,
        kind: MechanismKind::Rotational,
        description: "four hinges E I E I",
        joints: &[h(-1.0, E), h(-0.45, I), h(0.15, E), h(0.7, I)],
    },
    FamilyTemplate {
        id: "rotational-b",
        figure: 3,
        kind: MechanismKind::Rotational,
        description: "four hinges I E I E",
        joints: &[h(-1.0, I), h(-0.45, E), h(0.15, I), h(0.7, E)],
    },
    FamilyTemplate {
        id: "mixed-springing-a",
        figure: 4,
        kind: MechanismKind::Mixed,
        description: "sliding springing, hinges I E I",
        joints: &[s(-1.0, None), h(-0.45, I), h(0.15, E), h(0.7, I)],
    },
    FamilyTemplate {
        id: "mixed-springing-b",
        figure: 4,
        kind: MechanismKind::Mixed,
        description: "sliding springing, hinges E I E",
        joints: &[s(-1.0, None), h(-0.45, E), h(0.15, I), h(0.7, E)],
    },
    FamilyTemplate {
        id: "mixed-inner-a",
        figure: 4,
        kind: MechanismKind::Mixed,
        description: "hinges I, S, E I: sliding between hinges",
        joints: &[h(-1.0, I), s(-0.65, None), h(0.2, E), h(0.55, I)],
    },
    FamilyTemplate {
        id: "mixed-inner-b",
        figure: 4,
        kind: MechanismKind::Mixed,
        description: "hinges E, S, I E: sliding between hinges",
        joints: &[h(-1.0, E), s(-0.65, None), h(0.2, I), h(0.55, E)],
    },
    FamilyTemplate {
        id: "mixed-la-hire-a",
        figure: 4,
        kind: MechanismKind::Mixed,
        description: "La Hire: hinges E, LH I, I",
        joints: &[h(-1.0, E), lh(-0.2, I), h(1.0, I)],
    },
    FamilyTemplate {
        id: "mixed-la-hire-b",
        figure: 4,
        kind: MechanismKind::Mixed,
        description: "La Hire: hinges I, LH E, E",
        joints: &[h(-1.0, I), lh(-0.2, E), h(1.0, E)],
    },
    FamilyTemplate {
        id: "sliding-a",
        figure: 5,
        kind: MechanismKind::Sliding,
        description: "three sliding joints, middle block inward",
        joints: &[s(-1.0, None), s(-0.35, None), s(0.35, Some(Sense::Inward))],
    },
    FamilyTemplate {
        id: "sliding-b",
        figure: 5,
        kind: MechanismKind::Sliding,
        description: "three sliding joints, middle block outward",
        joints: &[s(-1.0, None), s(-0.35, None), s(0.35, Some(Sense::Outward))],
    },
];

/// A family on a given arch with its mechanism.
#[derive(Debug, Clone, PartialEq)]
pub struct Family {
    /// The template.
    pub template: FamilyTemplate,
    /// Its active joints on this arch.
    pub joints: Vec<ActiveJoint>,
    /// The compatibility analysis: one degree of freedom and one admissible field when the
    /// positions suit the arch.
    pub modes: Modes,
}

/// The joints of a template on an arch of half-angle α (radians).
pub fn template_joints(t: &FamilyTemplate, alpha: f64) -> Vec<ActiveJoint> {
    t.joints
        .iter()
        .map(|j| ActiveJoint {
            theta: j.fraction * alpha,
            hinge: j.hinge,
            slides: j.slides,
            sense: j.sense,
        })
        .collect()
}

/// One family on an arch with the default settings ([`family_with`]).
pub fn family<G: ArchGeometry + ?Sized>(
    geom: &G,
    template: &FamilyTemplate,
) -> Result<Family, KinematicsError> {
    family_with(geom, template, &KinematicsSettings::DEFAULT)
}

/// One family on an arch (any template, e.g. one with other positions).
pub fn family_with<G: ArchGeometry + ?Sized>(
    geom: &G,
    template: &FamilyTemplate,
    settings: &KinematicsSettings,
) -> Result<Family, KinematicsError> {
    let joints = template_joints(template, geom.half_angle());
    let modes = mechanism_modes_with(geom, &joints, FlowRule::NonAssociative, false, settings)?;
    Ok(Family {
        template: *template,
        joints,
        modes,
    })
}

/// The smallest margin of a family's mode: min over hinges of the rotation in the sense of
/// normality and over sliding joints of |slip| (normalised field); negative or zero when the
/// family is not admissible or does not move every joint.
pub fn margin(f: &Family) -> f64 {
    if f.modes.status != ModeStatus::Admissible || f.modes.dof != 1 {
        return f64::NEG_INFINITY;
    }
    let Some(field) = f.modes.fields.first() else {
        return f64::NEG_INFINITY;
    };
    field
        .joints
        .iter()
        .map(|j| {
            let rot = match j.joint.hinge {
                Some(Face::Intrados) => j.relative_rotation,
                Some(Face::Extrados) => -j.relative_rotation,
                None => f64::INFINITY,
            };
            let slip = if j.joint.slides {
                j.slip.abs()
            } else {
                f64::INFINITY
            };
            rot.min(slip)
        })
        .fold(f64::INFINITY, f64::min)
}

/// The family of `template` at the inner positions (on a grid of α/10, springings kept)
/// that give the largest [`margin`]; `None` when no grid position is admissible.
fn best_positions<G: ArchGeometry + ?Sized>(
    geom: &G,
    template: &FamilyTemplate,
    settings: &KinematicsSettings,
) -> Option<Family> {
    const STEPS: i32 = 10;
    let alpha = geom.half_angle();
    let base = template_joints(template, alpha);
    let free: Vec<usize> = (0..base.len())
        .filter(|&i| template.joints[i].fraction.abs() < 1.0)
        .collect();
    let grid: Vec<f64> = (1 - STEPS..=STEPS)
        .map(|i| f64::from(i) / f64::from(STEPS))
        .collect();
    let mut best: Option<(f64, Family)> = None;
    let mut choice = vec![0usize; free.len()];
    // Increasing grid indices for the free joints, between their fixed neighbours.
    loop {
        let mut joints = base.clone();
        for (k, &i) in free.iter().enumerate() {
            joints[i].theta = grid[choice[k]] * alpha;
        }
        let ordered = joints.windows(2).all(|w| w[0].theta < w[1].theta);
        if ordered
            && let Ok(modes) =
                mechanism_modes_with(geom, &joints, FlowRule::NonAssociative, false, settings)
        {
            let fam = Family {
                template: *template,
                joints,
                modes,
            };
            let m = margin(&fam);
            if m > 0.0 && best.as_ref().is_none_or(|(b, _)| m > *b) {
                best = Some((m, fam));
            }
        }
        // Next combination (odometer over the grid).
        let mut k = 0;
        loop {
            if k == choice.len() {
                return best.map(|(_, f)| f);
            }
            choice[k] += 1;
            if choice[k] < grid.len() {
                break;
            }
            choice[k] = 0;
            k += 1;
        }
    }
}

/// The ten families of Figs. 3–5 on an arch: at the [`REPRESENTATIVE`] positions when the
/// family is admissible there, otherwise at the grid positions (steps of α/10) with the
/// largest margin; a family with no admissible position on the grid is returned at the
/// representative positions with its status.
pub fn families<G: ArchGeometry + ?Sized>(geom: &G) -> Result<Vec<Family>, KinematicsError> {
    families_with(geom, &KinematicsSettings::DEFAULT)
}

/// [`families`] with the given settings.
pub fn families_with<G: ArchGeometry + ?Sized>(
    geom: &G,
    settings: &KinematicsSettings,
) -> Result<Vec<Family>, KinematicsError> {
    REPRESENTATIVE
        .iter()
        .map(|t| {
            let f = family_with(geom, t, settings)?;
            if margin(&f) > 0.0 {
                return Ok(f);
            }
            Ok(best_positions(geom, t, settings).unwrap_or(f))
        })
        .collect()
}
