//! The mechanism of a complete solution: the relative velocity of each moving joint from the
//! weights of its rows' twists, the blocks' velocities by adding them up from the left
//! support, and the check of the flow rules and of the work equation (paper eq. 11) computed
//! from those velocities and the state's joint forces alone.

use crate::analysis::statics::{ArchGeometry, Resultant};
use crate::analysis::types::{Face, Hinge, Mechanism, Sense, SlidingJoint};

/// A planar rigid velocity: velocity of the origin and angular velocity (counter-clockwise).
pub(super) type Twist = [f64; 3];

fn velocity_at(t: &Twist, p: [f64; 2]) -> [f64; 2] {
    [t[0] - t[2] * p[1], t[1] + t[2] * p[0]]
}

/// The state at which a mechanism is checked: crown force and moment, λ and μ.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StateY {
    /// (F_x, F_y, M₀, λ).
    pub y: [f64; 4],
    /// μ = tan φ (∞ allowed).
    pub mu: f64,
}

/// The work equation and the flow rules of a mechanism at its state, from the block
/// velocities (largest block-corner speed 1) and the joint forces.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WorkCheck {
    /// dL^(a): work of the loads on the blocks, over W_half·r.
    pub work_loads: f64,
    /// dL^(r,t): Σ T δr^t over the moving joints (−μ Σ N |δr^t| under maximum dissipation).
    pub work_friction: f64,
    /// dL^(r,n): Σ (N δr_G^n + M_G δω) over the moving joints (zero under normality).
    pub work_normal: f64,
    /// |dL^(a) + dL^(r,n) + dL^(r,t)| over the largest of its terms (eq. 11 holds at zero).
    pub work_residual: f64,
    /// Largest breach of a flow rule, relative to the joint force: a face pressing into its
    /// neighbour, a normal force working on an opening, a slip not opposed by μN.
    pub flow_violation: f64,
}

/// A mechanism named by its motion: hinges where a joint turns about a closed face, sliding
/// joints where it slips, joints that open at both faces (lift-off).
#[derive(Debug, Clone, PartialEq)]
pub struct MovingMechanism {
    /// Hinges and sliding joints.
    pub mechanism: Option<Mechanism>,
    /// Angles (degrees) of the joints that open at both faces.
    pub lifted_deg: Vec<f64>,
    /// The work equation and flow rules checked.
    pub work: WorkCheck,
}

/// A moving joint: its parameter and relative velocity of the right part over the left.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct JointMove {
    pub theta: f64,
    pub relative: Twist,
}

/// Threshold (relative to the largest corner speed 1) below which a motion is none.
const TOL_MOTION: f64 = 1e-9;

/// The blocks between consecutive moving joints, each with its velocity: the sum of the
/// relative velocities of the joints on its left.
fn blocks_of(moves: &[JointMove]) -> Vec<(f64, f64, Twist)> {
    let mut t: Twist = [0.0; 3];
    moves
        .windows(2)
        .map(|w| {
            for (tc, rc) in t.iter_mut().zip(&w[0].relative) {
                *tc += rc;
            }
            (w[0].theta, w[1].theta, t)
        })
        .collect()
}

/// The largest speed of a block corner (the joint ends of each block).
fn corner_speed<G: ArchGeometry + ?Sized>(geom: &G, blocks: &[(f64, f64, Twist)]) -> f64 {
    let mut top = 0.0_f64;
    for (from, to, tw) in blocks {
        for theta in [*from, *to] {
            let j = geom.joint(theta);
            for p in [j.intrados, j.extrados] {
                let v = velocity_at(tw, p);
                top = top.max(v[0].hypot(v[1]));
            }
        }
    }
    top
}

/// What one moving joint does at the state: its works, its breach of the flow rules and how
/// it moves.
struct JointReport {
    /// F·v₀ + M ω of the joint force on its relative velocity.
    total: f64,
    /// T δr^t.
    tangential: f64,
    /// Largest breach of a flow rule: openings at the unit corner speed, works relative to
    /// the joint's own.
    flow: f64,
    /// The face that stays closed while the joint turns about it.
    hinge: Option<Face>,
    /// The sense in which the crown-side part slips.
    slip: Option<Sense>,
    /// True when both faces open.
    lifted: bool,
}

fn joint_report<G: ArchGeometry + ?Sized>(
    geom: &G,
    theta: f64,
    rel: &Twist,
    state: &StateY,
    force_scale: f64,
) -> JointReport {
    let j = geom.joint(theta);
    let (tau, nu) = (j.along(), j.normal());
    let c = geom
        .dead_load(theta)
        .plus(geom.live_load(theta).scale(state.y[3]));
    let f = [state.y[0] + c.fx, state.y[1] + c.fy];
    let moment = state.y[2] + c.m;
    let normal = f[0] * nu[0] + f[1] * nu[1];
    let shear = f[0] * tau[0] + f[1] * tau[1];
    let total = f[0] * rel[0] + f[1] * rel[1] + moment * rel[2];
    let vi = velocity_at(rel, j.intrados);
    let ve = velocity_at(rel, j.extrados);
    let open_i = vi[0] * nu[0] + vi[1] * nu[1];
    let open_e = ve[0] * nu[0] + ve[1] * nu[1];
    let along = vi[0] * tau[0] + vi[1] * tau[1];
    let tangential = shear * along;
    // The size of the joint's own works: its force against its relative velocity, term by
    // term (a thin joint turns fast under a small moment), never below the largest joint
    // force at the unit corner speed.
    let size = (f[0].hypot(f[1]) * rel[0].hypot(rel[1]) + (moment * rel[2]).abs()).max(force_scale);
    // No face presses into its neighbour; the normal force does no work (normality).
    let mut flow = (-open_i)
        .max(-open_e)
        .max((total - tangential).abs() / size);
    let slipping = along.abs() > TOL_MOTION;
    if slipping {
        // Maximum dissipation: T δr^t = −μ N |δr^t|.
        let dissipation = if state.mu.is_finite() {
            state.mu * normal * along.abs()
        } else {
            0.0
        };
        flow = flow
            .max((tangential + dissipation).abs() / size)
            .max(tangential / size);
    }
    let (oi, oe) = (open_i > TOL_MOTION, open_e > TOL_MOTION);
    let lifted = oi && oe;
    let crown_side = if theta >= 0.0 { 1.0 } else { -1.0 };
    JointReport {
        total,
        tangential,
        flow,
        hinge: (!lifted && (oi || oe)).then_some(if oe { Face::Intrados } else { Face::Extrados }),
        slip: (slipping && !lifted).then(|| {
            if -crown_side * along > 0.0 {
                Sense::Outward
            } else {
                Sense::Inward
            }
        }),
        lifted,
    }
}

/// Names, normalises and checks the mechanism of moving joints `moves` (increasing θ) at
/// `state`; `None` when nothing moves.
pub(super) fn check<G: ArchGeometry + ?Sized>(
    geom: &G,
    moves: &[JointMove],
    state: &StateY,
    angle_deg: &dyn Fn(f64) -> f64,
) -> Option<MovingMechanism> {
    let blocks = blocks_of(moves);
    let top = corner_speed(geom, &blocks);
    if !(top > 0.0 && top.is_finite()) {
        return None;
    }
    let s = 1.0 / top;
    let lam = state.y[3];
    let load = |th: f64| geom.dead_load(th).plus(geom.live_load(th).scale(lam));
    let mut work_loads = 0.0;
    // The size of the works: each block's load against its velocity, term by term, so that a
    // mechanism on which the loads do no work (a part tipping about a corner through which
    // its load passes) is judged against the work its loads could do.
    let mut scale = 0.0_f64;
    for (from, to, tw) in &blocks {
        let r: Resultant = load(*to).plus(load(*from).scale(-1.0));
        work_loads += s * (r.fx * tw[0] + r.fy * tw[1] + r.m * tw[2]);
        scale += s * ((r.fx * tw[0]).abs() + (r.fy * tw[1]).abs() + (r.m * tw[2]).abs());
    }
    // Joint forces are judged against the largest of them (a joint that lifts off carries
    // none of its own).
    let force_scale = moves
        .iter()
        .map(|m| {
            let c = load(m.theta);
            let f = [state.y[0] + c.fx, state.y[1] + c.fy];
            f[0].hypot(f[1]).max((state.y[2] + c.m).abs())
        })
        .fold(1.0_f64, f64::max);
    let mut work_friction = 0.0;
    let mut work_normal = 0.0;
    let mut flow = 0.0_f64;
    let mut hinges = Vec::new();
    let mut sliding = Vec::new();
    let mut lifted = Vec::new();
    for m in moves {
        let rel = m.relative.map(|v| s * v);
        let r = joint_report(geom, m.theta, &rel, state, force_scale);
        work_friction += r.tangential;
        work_normal += r.total - r.tangential;
        scale = scale.max(r.total.abs()).max(r.tangential.abs());
        flow = flow.max(r.flow);
        let angle = angle_deg(m.theta);
        if r.lifted {
            lifted.push(angle);
        }
        if let Some(face) = r.hinge {
            hinges.push(Hinge {
                angle_deg: angle,
                face,
            });
        }
        if let Some(sense) = r.slip {
            sliding.push(SlidingJoint {
                angle_deg: angle,
                sense,
            });
        }
    }
    let residual = (work_loads + work_friction + work_normal).abs() / scale.max(f64::MIN_POSITIVE);
    Some(MovingMechanism {
        mechanism: Mechanism::from_parts(hinges, sliding),
        lifted_deg: lifted,
        work: WorkCheck {
            work_loads,
            work_friction,
            work_normal,
            work_residual: residual,
            flow_violation: flow,
        },
    })
}
