//! The linear programmes of the general route: the rows a·z ≤ b over z = (F_x, F_y, M₀, t)
//! of a set of joints, with t the margin τ or the load factor λ.

use super::RowSet;
use crate::analysis::statics::{ArchGeometry, Condition, Row, joint_rows};

/// The objective of every programme here: maximise the fourth unknown (τ or λ).
pub const OBJECTIVE: [f64; 4] = [0.0, 0.0, 0.0, 1.0];

/// The auxiliary row −λ ≤ 0 of a load-factor programme.
const LAMBDA_NON_NEGATIVE: [f64; 4] = [0.0, 0.0, 0.0, -1.0];

/// The joint and condition of a row of a [`LinearRows`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointRow {
    /// Joint parameter θ, radians.
    pub theta: f64,
    /// The condition.
    pub condition: Condition,
}

/// A programme "maximise [`OBJECTIVE`]·z subject to a z ≤ b" over z = (F_x, F_y, M₀, t),
/// with t = τ (margin) or λ (load factor). The first `joints.len()` rows belong to joints;
/// the rest (the cap τ ≤ τ_cap) are auxiliary.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LinearRows {
    /// Row coefficients.
    pub a: Vec<[f64; 4]>,
    /// Right-hand sides.
    pub b: Vec<f64>,
    /// The joint of each joint row.
    pub joints: Vec<JointRow>,
}

/// What the fourth unknown is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Objective {
    /// τ, with λ held fixed.
    Margin { lambda: f64, cap: f64 },
    /// λ.
    LoadFactor,
}

/// |(a_x, a_y, a_M)|.
pub(super) fn norm3(a: &[f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

/// The programme row of a joint row.
pub(super) fn lp_row(r: &Row, objective: Objective) -> ([f64; 4], f64) {
    match objective {
        Objective::Margin { lambda, .. } => (
            [r.a[0], r.a[1], r.a[2], norm3(&r.a)],
            r.b - r.a_lambda * lambda,
        ),
        Objective::LoadFactor => ([r.a[0], r.a[1], r.a[2], r.a_lambda], r.b),
    }
}

/// Distance by which z violates the row (a·z − b)/|a|; with `homogeneous`, a·z/|a| (for a
/// ray of an unbounded programme).
pub(super) fn violation(r: &Row, objective: Objective, z: &[f64; 4], homogeneous: bool) -> f64 {
    let (a, b) = lp_row(r, objective);
    let s =
        a[0] * z[0] + a[1] * z[1] + a[2] * z[2] + a[3] * z[3] - if homogeneous { 0.0 } else { b };
    let n = norm3(&r.a);
    if n > 0.0 { s / n } else { s }
}

impl LinearRows {
    pub(super) fn push_joint<G: ArchGeometry + ?Sized>(
        &mut self,
        geom: &G,
        theta: f64,
        phi: f64,
        set: RowSet,
        objective: Objective,
    ) {
        for r in joint_rows(geom, theta, phi) {
            if set.includes(r.condition) {
                self.push_row(&r, objective);
            }
        }
    }

    pub(super) fn push_row(&mut self, r: &Row, objective: Objective) {
        let (a, b) = lp_row(r, objective);
        self.push_lp_row(
            a,
            b,
            JointRow {
                theta: r.theta,
                condition: r.condition,
            },
        );
    }

    /// Adds the programme row a·z ≤ b of a joint row.
    pub(super) fn push_lp_row(&mut self, a: [f64; 4], b: f64, joint: JointRow) {
        // Joint rows come first: insert before the auxiliary rows.
        let at = self.joints.len();
        self.a.insert(at, a);
        self.b.insert(at, b);
        self.joints.push(joint);
    }

    /// The margin programme at the given joints: rows a·x + τ|a| ≤ b − a_λ λ, and τ ≤ cap.
    pub fn margin<G: ArchGeometry + ?Sized>(
        geom: &G,
        thetas: &[f64],
        phi: f64,
        set: RowSet,
        lambda: f64,
        cap: f64,
    ) -> Self {
        let mut rows = LinearRows {
            a: vec![OBJECTIVE],
            b: vec![cap],
            joints: Vec::new(),
        };
        for &t in thetas {
            rows.push_joint(geom, t, phi, set, Objective::Margin { lambda, cap });
        }
        rows
    }

    /// The load-factor programme at the given joints: rows a·x + a_λ λ ≤ b, and λ ≥ 0.
    pub fn load_factor<G: ArchGeometry + ?Sized>(
        geom: &G,
        thetas: &[f64],
        phi: f64,
        set: RowSet,
    ) -> Self {
        let mut rows = LinearRows::new(Objective::LoadFactor);
        for &t in thetas {
            rows.push_joint(geom, t, phi, set, Objective::LoadFactor);
        }
        rows
    }

    /// Adds the auxiliary rows F_y ≤ 0 and −F_y ≤ 0 of a problem in the symmetric unknowns
    /// (`half`): the crown shear is zero.
    pub(super) fn fixing_crown_shear(mut self, half: bool) -> Self {
        if half {
            for sign in [1.0, -1.0] {
                self.a.push([0.0, sign, 0.0, 0.0]);
                self.b.push(0.0);
            }
        }
        self
    }

    pub(super) fn new(objective: Objective) -> Self {
        match objective {
            Objective::Margin { cap, .. } => LinearRows {
                a: vec![OBJECTIVE],
                b: vec![cap],
                joints: Vec::new(),
            },
            // λ ≥ 0: the live load acts in its own sense.
            Objective::LoadFactor => LinearRows {
                a: vec![LAMBDA_NON_NEGATIVE],
                b: vec![0.0],
                joints: Vec::new(),
            },
        }
    }
}
