//! The work equation of a mechanism at a limit state (paper §4, eqs. 9 and 11).
//!
//! For a velocity field of the blocks and an equilibrated state, virtual work gives
//! dL^(a) + dL^(r,n) + dL^(r,t) = 0, where dL^(a) is the work of the loads and the reactive
//! work at each active joint is split into its normal part N δr_G^n + M_G δω (dL^(r,n)) and its
//! tangential part T δr^t (dL^(r,t)). At collapse the paper requires dL^(r,n) = 0 (normality at
//! the hinges) and dL^(r,t) = −μ R^n |dr^t| at the sliding joints (maximum dissipation), so that
//! dL^(a) = −dL^(r,t) ≥ 0, with dL^(a) = 0 for a rotational mechanism (eq. 9).
//!
//! Units: forces over W_half, lengths over r, so works are over W_half·r per unit virtual
//! time of the normalised field (largest block-corner speed 1).

use super::VelocityField;
use crate::analysis::statics::{ArchGeometry, Resultant};
use crate::analysis::symmetric::CriticalState;

/// An equilibrated limit state in the statics conventions: the crown force F₀ and moment M₀
/// about the origin (the internal force of the left part on the right part at θ = 0), the load
/// factor λ and the friction coefficient.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LimitState {
    /// F₀ = (F_x, F_y) over W_half.
    pub crown_force: [f64; 2],
    /// M₀ about the origin over W_half·r; NaN when the state does not fix it (a purely
    /// sliding state), in which case moments are left out of the work (they multiply zero
    /// relative rotations there).
    pub crown_moment_origin: f64,
    /// λ, the multiplier of the live load.
    pub load_factor: f64,
    /// μ = tan φ (may be infinite when nothing slides).
    pub mu: f64,
}

impl LimitState {
    /// The symmetric state of a [`CriticalState`]: F₀ = (h, 0) and M₀ = −m.
    pub fn symmetric(state: &CriticalState) -> Self {
        LimitState {
            crown_force: [state.thrust_over_half_weight, 0.0],
            crown_moment_origin: -state.crown_moment,
            load_factor: 0.0,
            mu: state.mu,
        }
    }
}

/// The internal force at a joint, in the joint's frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointForce {
    /// N = F·ν, compression positive (R^n of the paper), over W_half.
    pub normal: f64,
    /// T = F·τ, over W_half.
    pub tangential: f64,
    /// M_G = M − G × F, moment about the joint centre, over W_half·r (NaN when M₀ is).
    pub moment_centre: f64,
}

/// The internal force of the left part on the right part at joint θ:
/// F = F₀ + C_d(θ) + λ C_l(θ), M = M₀ + C_d^M(θ) + λ C_l^M(θ) (statics.rs).
pub fn joint_force<G: ArchGeometry + ?Sized>(
    geom: &G,
    state: &LimitState,
    theta: f64,
) -> JointForce {
    let d = geom.dead_load(theta);
    let l = geom.live_load(theta);
    let lam = state.load_factor;
    let f = [
        state.crown_force[0] + d.fx + lam * l.fx,
        state.crown_force[1] + d.fy + lam * l.fy,
    ];
    let m = state.crown_moment_origin + d.m + lam * l.m;
    let j = geom.joint(theta);
    let g = [
        0.5 * (j.intrados[0] + j.extrados[0]),
        0.5 * (j.intrados[1] + j.extrados[1]),
    ];
    let (tau, nu) = (j.along(), j.normal());
    JointForce {
        normal: f[0] * nu[0] + f[1] * nu[1],
        tangential: f[0] * tau[0] + f[1] * tau[1],
        moment_centre: m - (g[0] * f[1] - g[1] * f[0]),
    }
}

/// The terms of the work equation for one mechanism at one state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorkEquation {
    /// dL^(a): work of the loads (dead load, plus λ times the live load) on the block
    /// velocities, over W_half·r.
    pub work_loads: f64,
    /// dL^(r,t) = −μ Σ R^n |dr^t| over the sliding joints (eq. 11), over W_half·r.
    pub work_friction: f64,
    /// dL^(r,n) of the state's reactions: Σ (N δr_G^n + M_G δω) over the active joints; zero
    /// at collapse (eq. 11), a check of the normality between state and mechanism.
    pub work_normal: f64,
    /// Σ T δr^t of the state's reactions: equals `work_friction` when every slip opposes the
    /// friction force of a joint on the cone.
    pub work_tangential: f64,
    /// Σ over blocks of |f||u| + |ω||m|: the size of the work the loads could do on each
    /// block (force times speed of its reference point, moment about it times rotation), the
    /// scale against which dL^(a) = 0 is judged.
    pub load_scale: f64,
    /// |dL^(a) + dL^(r,t)| / max(|dL^(a)|, |dL^(r,t)|, load_scale): zero when eq. (11) holds.
    pub work_residual: f64,
}

/// Power of a load resultant (force and moment about the origin) on a rigid velocity, and an
/// upper bound of its magnitude: |f||u| + |ω||m_ref| with m_ref the moment about the block's
/// reference point.
fn load_power(r: Resultant, v: &super::RigidVelocity) -> (f64, f64) {
    let p = v.reference;
    let m_ref = r.m - (p[0] * r.fy - p[1] * r.fx);
    let u = v.translation;
    // f·u + ω m_ref.
    let power = r.fx * u[0] + r.fy * u[1] + v.rotation * m_ref;
    let bound = r.fx.hypot(r.fy) * u[0].hypot(u[1]) + (v.rotation * m_ref).abs();
    (power, bound)
}

/// The work equation (eqs. 9 and 11) of a field at a state. The load of a block [a, b] is the
/// difference of the cumulative resultants C(b) − C(a), so the weight model (annular sector
/// at its centroid or centreline) enters exactly through [`ArchGeometry::dead_load`].
pub fn work_equation<G: ArchGeometry + ?Sized>(
    geom: &G,
    state: &LimitState,
    field: &VelocityField,
) -> WorkEquation {
    let lam = state.load_factor;
    let load = |t: f64| geom.dead_load(t).plus(geom.live_load(t).scale(lam));
    let mut work_loads = 0.0;
    let mut load_scale = 0.0;
    for b in field.blocks() {
        let r = load(b.theta_to).plus(load(b.theta_from).scale(-1.0));
        let (w, bound) = load_power(r, &b.velocity);
        work_loads += w;
        load_scale += bound;
    }
    let mut work_friction = 0.0;
    let mut work_normal = 0.0;
    let mut work_tangential = 0.0;
    let with_moments = state.crown_moment_origin.is_finite();
    for m in &field.joints {
        let f = joint_force(geom, state, m.joint.theta);
        // δω = ω_right − ω_left = −δα.
        let moment = if with_moments {
            -f.moment_centre * m.relative_rotation
        } else {
            0.0
        };
        work_normal += f.normal * m.opening + moment;
        // T δr^t with δr^t of the right part relative to the left part along τ.
        let crown_side = if m.joint.theta >= 0.0 { 1.0 } else { -1.0 };
        work_tangential += f.tangential * (-crown_side * m.slip);
        if m.joint.slides && m.slip != 0.0 {
            work_friction -= state.mu * f.normal * m.slip.abs();
        }
    }
    let denom = work_loads
        .abs()
        .max(work_friction.abs())
        .max(load_scale)
        .max(f64::MIN_POSITIVE);
    WorkEquation {
        work_loads,
        work_friction,
        work_normal,
        work_tangential,
        load_scale,
        work_residual: (work_loads + work_friction).abs() / denom,
    }
}
