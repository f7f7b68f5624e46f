//! The rows of the state space (F_x, F_y, M₀, λ) with the twist that each row's flow rule
//! allows: the relative velocity (v₀, ω) of the right part of a joint over its left part when
//! the joint moves as that row's limit permits.
//!
//! A row's coefficients on (F_x, F_y, M₀) pair with a relative velocity (v₀ at the origin, ω)
//! exactly as the joint force does: the power of the force of the left part on the right part
//! is F·v₀ + M₀ ω. A no-tension row (eq. 1) is the moment of that force about a face point, so
//! its coefficients are the rotation about that point: normality at a hinge. A Coulomb row
//! (eq. 3) mixes the shear T and the normal force N; without dilatancy the joint slips along
//! τ without opening, so its twist is the translation along ±τ alone (the non-associative
//! flow rule). A joint moves with the relative velocity −Σ κ_i t_i (κ_i ≥ 0) of the twists of
//! its rows at their limit; the blocks close up between the fixed supports exactly when
//! Σ κ_i t_i = 0 over all moving joints, since the three redundant unknowns are the force and
//! moment that every joint transmits in a self-stress.

use crate::analysis::statics::{ArchGeometry, Condition, JointFrame, Row, joint_rows};

/// What a row of the state space is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum RowKind {
    /// A row of joint `joint` (an index into [`StateRows::thetas`]).
    Joint {
        /// Index of the joint.
        joint: usize,
        /// The condition at its limit.
        condition: Condition,
        /// The twist its flow rule allows, unit length; `None` when it allows none.
        twist: Option<[f64; 3]>,
        /// True for a Coulomb row at μ = ∞ (N ≥ 0 alone): its joint may slip only when it
        /// carries no force at all.
        zero_force_only: bool,
    },
    /// A bound that keeps the walk finite (λ ≥ 0, λ ≤ cap, |x| ≤ cap): no joint behind it.
    Bound,
}

/// Rows a·y ≤ b over y = (F_x, F_y, M₀, λ), each scaled to |a| = 1.
#[derive(Debug, Clone, PartialEq, Default)]
pub(super) struct StateRows {
    pub a: Vec<[f64; 4]>,
    pub b: Vec<f64>,
    pub kind: Vec<RowKind>,
    /// The joint parameters, increasing.
    pub thetas: Vec<f64>,
}

fn unit(v: [f64; 3]) -> Option<[f64; 3]> {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    (n > 0.0 && n.is_finite()).then(|| [v[0] / n, v[1] / n, v[2] / n])
}

impl StateRows {
    /// The rows of the joints `thetas` (increasing) at friction angle φ, with λ in
    /// `lambda` = [from, to] (from = to pins it) and |F_x|, |F_y|, |M₀| ≤ `state_cap`. The
    /// Coulomb rows are scaled by cos φ (statics.rs), so below [`COS_PHI_INFINITE`] μ counts
    /// as infinite.
    pub fn new<G: ArchGeometry + ?Sized>(
        geom: &G,
        thetas: &[f64],
        phi: f64,
        lambda: [f64; 2],
        state_cap: f64,
    ) -> Self {
        Self::from_frames(&frames(geom, thetas), phi, lambda, state_cap)
    }

    /// [`StateRows::new`] from the frames of the joints ([`frames`]).
    pub fn from_frames(frames: &[JointFrame], phi: f64, lambda: [f64; 2], state_cap: f64) -> Self {
        let mut rows = StateRows {
            thetas: frames.iter().map(|f| f.theta).collect(),
            ..StateRows::default()
        };
        let n = 4 * frames.len() + 8;
        rows.a.reserve(n);
        rows.b.reserve(n);
        rows.kind.reserve(n);
        for (joint, frame) in frames.iter().enumerate() {
            let all = frame.rows(phi);
            let tau = frame.joint.along();
            for (i, condition) in Condition::ALL.into_iter().enumerate() {
                if let Some(r) = scaled(&all[i], tau, phi) {
                    rows.push(
                        r.a,
                        r.b,
                        RowKind::Joint {
                            joint,
                            condition,
                            twist: r.twist,
                            zero_force_only: r.zero_force_only,
                        },
                    );
                }
            }
        }
        rows.push([0.0, 0.0, 0.0, -1.0], -lambda[0], RowKind::Bound);
        rows.push([0.0, 0.0, 0.0, 1.0], lambda[1], RowKind::Bound);
        for i in 0..3 {
            for s in [1.0, -1.0] {
                let mut a = [0.0; 4];
                a[i] = s;
                rows.push(a, state_cap, RowKind::Bound);
            }
        }
        rows
    }

    fn push(&mut self, a: [f64; 4], b: f64, kind: RowKind) {
        self.a.push(a);
        self.b.push(b);
        self.kind.push(kind);
    }

    /// Number of rows.
    pub fn len(&self) -> usize {
        self.a.len()
    }
}

/// The frames of the joints `thetas` of `geom`.
pub(super) fn frames<G: ArchGeometry + ?Sized>(geom: &G, thetas: &[f64]) -> Vec<JointFrame> {
    thetas.iter().map(|&t| JointFrame::of(geom, t)).collect()
}

/// One row of a joint scaled to unit length, with its twist.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct JointRowAt {
    /// Coefficients on (F_x, F_y, M₀, λ).
    pub a: [f64; 4],
    /// Right-hand side.
    pub b: f64,
    /// The twist its flow rule allows, unit length.
    pub twist: Option<[f64; 3]>,
    /// True for a Coulomb row at μ = ∞ ([`RowKind::Joint`]).
    pub zero_force_only: bool,
}

/// The row of `condition` at joint θ and friction angle φ; `None` when the row is left out
/// (relaxed) or degenerate.
pub(super) fn row_at<G: ArchGeometry + ?Sized>(
    geom: &G,
    theta: f64,
    phi: f64,
    condition: Condition,
) -> Option<JointRowAt> {
    let i = Condition::ALL.iter().position(|c| *c == condition)?;
    let r = joint_rows(geom, theta, phi)[i];
    scaled(&r, geom.joint(theta).along(), phi)
}

/// A row of the statics scaled to unit length, with its twist (τ the joint's direction).
fn scaled(r: &Row, tau: [f64; 2], phi: f64) -> Option<JointRowAt> {
    let condition = r.condition;
    let a = [r.a[0], r.a[1], r.a[2], r.a_lambda];
    let n = a.iter().map(|v| v * v).sum::<f64>().sqrt();
    if n == 0.0 || !n.is_finite() {
        return None;
    }
    let twist = match condition {
        Condition::Intrados | Condition::Extrados => unit(r.a),
        Condition::SlideOutward => unit([tau[0], tau[1], 0.0]),
        Condition::SlideInward => unit([-tau[0], -tau[1], 0.0]),
    };
    Some(JointRowAt {
        a: [a[0] / n, a[1] / n, a[2] / n, a[3] / n],
        b: r.b / n,
        twist,
        zero_force_only: phi.cos() <= COS_PHI_INFINITE && !condition.is_rotational(),
    })
}

/// cos φ at or below which the Coulomb rows are those of μ = ∞.
pub(super) const COS_PHI_INFINITE: f64 = 1e-12;
