//! The joints a walk uses and the joints it must add: a discrete arch is walked on all its
//! joints; a continuum on sampled joints, completed by an exchange: the joints where the
//! walk's answer violates a row are added until it violates none.

use super::Settings;
use super::load_factor::initial_joints;
use crate::analysis::general;
use crate::analysis::statics::{ArchGeometry, joint_rows};

/// The joints of the first walk: `None` for all of a discrete arch's own joints.
pub(super) fn initial<G: ArchGeometry + ?Sized>(geom: &G, settings: &Settings) -> Option<Vec<f64>> {
    match geom.discrete_joints() {
        None => Some(initial_joints(geom, settings)),
        Some(_) => None,
    }
}

/// True when the arch has more joints than a walk takes ([`Settings::max_walk_joints`]).
pub(super) fn too_many<G: ArchGeometry + ?Sized>(geom: &G, settings: &Settings) -> bool {
    geom.discrete_joints()
        .is_some_and(|j| j.len() > settings.max_walk_joints)
}

/// The joints at which the state y = (F_x, F_y, M₀, λ) violates a row at friction angle φ:
/// the refined local maxima over a continuum's families, every joint of a discrete arch.
pub(super) fn violated<G: ArchGeometry + ?Sized>(geom: &G, phi: f64, y: &[f64; 4]) -> Vec<f64> {
    let general_settings = general::Settings::default();
    match geom.discrete_joints() {
        None => general::violated_joints(geom, phi, y, &general_settings)
            .into_iter()
            .map(|c| c.0)
            .collect(),
        Some(all) => {
            let tol = general_settings.tol_exchange
                * (1.0 + y[..3].iter().fold(0.0_f64, |m, v| m.max(v.abs())));
            all.into_iter()
                .filter(|&t| {
                    joint_rows(geom, t, phi).iter().any(|r| {
                        let n = (r.a[0] * r.a[0] + r.a[1] * r.a[1] + r.a[2] * r.a[2]).sqrt();
                        let v =
                            r.a[0] * y[0] + r.a[1] * y[1] + r.a[2] * y[2] + r.a_lambda * y[3] - r.b;
                        n > 0.0 && v / n > tol
                    })
                })
                .collect()
        }
    }
}
