//! The joints a walk uses and the joints it must add: a discrete arch of a few joints is
//! walked on all of them; a continuum on sampled joints, and a large discrete arch on some of
//! its own, completed by an exchange: the joints where the walk's answer violates a row are
//! added until it violates none.

use super::Settings;
use super::load_factor::initial_joints;
use crate::analysis::general;
use crate::analysis::statics::{ArchGeometry, joint_rows};

/// The joints of the first walk: `None` for all of a small discrete arch's own joints.
pub(super) fn initial<G: ArchGeometry + ?Sized>(geom: &G, settings: &Settings) -> Option<Vec<f64>> {
    match geom.discrete_joints() {
        None => Some(initial_joints(geom, settings)),
        Some(all) => {
            initial_picks(all.len(), settings).map(|ix| ix.iter().map(|&i| all[i]).collect())
        }
    }
}

/// The indices of the first walk's joints among a discrete arch's `len` joints: `None` for
/// all of them (a small arch).
pub(super) fn initial_picks(len: usize, settings: &Settings) -> Option<Vec<usize>> {
    (len > settings.exchange_above).then(|| evenly_spaced(len, settings.discrete_joints))
}

/// `n` of `len` joints, evenly spaced by index, the first and last among them.
fn evenly_spaced(len: usize, n: usize) -> Vec<usize> {
    if len <= n.max(2) {
        return (0..len).collect();
    }
    // At most one pick per joint: the indices k·last/(n − 1) increase strictly when n ≤ len.
    let (n, last) = (n.max(2), len - 1);
    (0..n).map(|k| k * last / (n - 1)).collect()
}

/// Adds the joint angles `cuts` to `walked` (increasing, each once): the exchange's step on
/// joints named by angle. Returns how many joints `walked` then holds.
pub(super) fn add_angles(walked: &mut Vec<f64>, cuts: Vec<f64>) -> usize {
    walked.extend(cuts);
    walked.sort_by(f64::total_cmp);
    walked.dedup();
    walked.len()
}

/// True when an exchange has grown the walked joints beyond [`Settings::max_walk_joints`].
pub(super) fn too_many(walked: &[f64], settings: &Settings) -> bool {
    walked.len() > settings.max_walk_joints
}

/// The joints of [`violated`] that are not among `walked` (increasing): the walk holds the
/// rows of its own joints to its tolerance, so only the others are new.
pub(super) fn violated_elsewhere<G: ArchGeometry + ?Sized>(
    geom: &G,
    phi: f64,
    y: &[f64; 4],
    walked: &[f64],
) -> Vec<f64> {
    let mut cuts = violated(geom, phi, y);
    cuts.retain(|c| walked.binary_search_by(|w| w.total_cmp(c)).is_err());
    cuts
}

/// The joints at which the state y = (F_x, F_y, M₀, λ) violates a row at friction angle φ:
/// the refined local maxima over a continuum's families; on a discrete arch, the most violated
/// joint of each run of neighbouring violated joints (its neighbours follow it in a later
/// round if they still need to).
fn violated<G: ArchGeometry + ?Sized>(geom: &G, phi: f64, y: &[f64; 4]) -> Vec<f64> {
    let general_settings = general::Settings::default();
    let Some(all) = geom.discrete_joints() else {
        return general::violated_joints(geom, phi, y, &general_settings)
            .into_iter()
            .map(|c| c.0)
            .collect();
    };
    let tol =
        general_settings.tol_exchange * (1.0 + y[..3].iter().fold(0.0_f64, |m, v| m.max(v.abs())));
    let excess = |t: f64| {
        joint_rows(geom, t, phi)
            .iter()
            .filter_map(|r| {
                let n = (r.a[0] * r.a[0] + r.a[1] * r.a[1] + r.a[2] * r.a[2]).sqrt();
                let v = r.a[0] * y[0] + r.a[1] * y[1] + r.a[2] * y[2] + r.a_lambda * y[3] - r.b;
                (n > 0.0).then(|| v / n)
            })
            .fold(f64::NEG_INFINITY, f64::max)
    };
    let mut out = Vec::new();
    let mut run: Option<(f64, f64)> = None;
    for t in all {
        let e = excess(t);
        if e > tol {
            if run.is_none_or(|(_, worst)| e > worst) {
                run = Some((t, e));
            }
        } else if let Some((at, _)) = run.take() {
            out.push(at);
        }
    }
    out.extend(run.map(|(at, _)| at));
    out
}
