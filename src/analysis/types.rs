//! Outcomes of an analysis: regimes, hinges, sliding joints, mechanisms and intervals.

use serde::{Deserialize, Serialize};
use std::fmt;

/// The face of a joint at which a hinge forms.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Face {
    /// Inner surface (radius r).
    Intrados,
    /// Outer surface (radius R).
    Extrados,
}

impl Face {
    /// `intrados` or `extrados`.
    pub fn as_str(self) -> &'static str {
        match self {
            Face::Intrados => "intrados",
            Face::Extrados => "extrados",
        }
    }

    /// Parses the name written by [`Face::as_str`].
    pub fn parse(s: &str) -> Option<Self> {
        [Face::Intrados, Face::Extrados]
            .into_iter()
            .find(|f| f.as_str() == s)
    }
}

/// A hinge: the line of thrust touches a face at a joint.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Hinge {
    /// Joint angle from the crown, degrees, positive to the right.
    pub angle_deg: f64,
    /// Face touched.
    pub face: Face,
}

/// The sense of relative sliding at a joint: how the part nearer the crown moves relative to
/// the part nearer the springing, along the joint (radially for radial joints).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Sense {
    /// The crown-side part moves outward (away from the centre), T = +μN.
    Outward,
    /// The crown-side part moves inward (toward the centre), T = −μN.
    Inward,
}

impl Sense {
    /// `outward` or `inward`.
    pub fn as_str(self) -> &'static str {
        match self {
            Sense::Outward => "outward",
            Sense::Inward => "inward",
        }
    }

    /// Parses the name written by [`Sense::as_str`].
    pub fn parse(s: &str) -> Option<Self> {
        [Sense::Outward, Sense::Inward]
            .into_iter()
            .find(|d| d.as_str() == s)
    }
}

/// A joint where the resultant lies on the friction cone.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SlidingJoint {
    /// Joint angle from the crown, degrees, positive to the right.
    pub angle_deg: f64,
    /// Sense of the relative displacement.
    pub sense: Sense,
}

/// The type of a collapse mechanism (paper Figs. 3, 4, 5).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, PartialOrd, Ord)]
#[serde(rename_all = "lowercase")]
pub enum MechanismKind {
    /// Hinges only.
    Rotational,
    /// Hinges and sliding joints.
    Mixed,
    /// Sliding joints only.
    Sliding,
}

impl MechanismKind {
    /// `rotational`, `mixed` or `sliding`.
    pub fn as_str(self) -> &'static str {
        match self {
            MechanismKind::Rotational => "rotational",
            MechanismKind::Mixed => "mixed",
            MechanismKind::Sliding => "sliding",
        }
    }

    /// Parses the name written by [`MechanismKind::as_str`].
    pub fn parse(s: &str) -> Option<Self> {
        [
            MechanismKind::Rotational,
            MechanismKind::Mixed,
            MechanismKind::Sliding,
        ]
        .into_iter()
        .find(|m| m.as_str() == s)
    }

    /// Classifies a set of active hinges and sliding joints.
    pub fn from_counts(hinges: usize, sliding: usize) -> Option<Self> {
        match (hinges > 0, sliding > 0) {
            (true, false) => Some(MechanismKind::Rotational),
            (true, true) => Some(MechanismKind::Mixed),
            (false, true) => Some(MechanismKind::Sliding),
            (false, false) => None,
        }
    }
}

impl fmt::Display for MechanismKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// The active pattern of a limit state: hinges and sliding joints of the whole arch.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Mechanism {
    /// Rotational, mixed or sliding.
    pub kind: MechanismKind,
    /// Hinges, ordered by angle.
    pub hinges: Vec<Hinge>,
    /// Sliding joints, ordered by angle.
    pub sliding_joints: Vec<SlidingJoint>,
}

impl Mechanism {
    /// A mechanism from its active joints; `None` when nothing is active.
    pub fn from_parts(mut hinges: Vec<Hinge>, mut sliding: Vec<SlidingJoint>) -> Option<Self> {
        hinges.sort_by(|a, b| a.angle_deg.total_cmp(&b.angle_deg));
        sliding.sort_by(|a, b| a.angle_deg.total_cmp(&b.angle_deg));
        let kind = MechanismKind::from_counts(hinges.len(), sliding.len())?;
        Some(Mechanism {
            kind,
            hinges,
            sliding_joints: sliding,
        })
    }
}

/// The regime of a point (K, μ, loads) (docs/mechanics.md §1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, PartialOrd, Ord)]
#[serde(rename_all = "lowercase")]
pub enum Regime {
    /// An admissible state exists: H^r ∩ H^s ≠ ∅.
    Stable,
    /// H^r = ∅ (too thin whatever the friction), H^s ≠ ∅.
    Rotational,
    /// Both non-empty but disjoint.
    Mixed,
    /// H^s = ∅ (too little friction whatever the thickness), H^r ≠ ∅.
    Sliding,
    /// Both empty.
    None,
}

impl Regime {
    /// All regimes, in display order.
    pub const ALL: [Regime; 5] = [
        Regime::Stable,
        Regime::Rotational,
        Regime::Mixed,
        Regime::Sliding,
        Regime::None,
    ];

    /// `stable`, `rotational`, `mixed`, `sliding` or `none`.
    pub fn as_str(self) -> &'static str {
        match self {
            Regime::Stable => "stable",
            Regime::Rotational => "rotational",
            Regime::Mixed => "mixed",
            Regime::Sliding => "sliding",
            Regime::None => "none",
        }
    }

    /// Parses the name written by [`Regime::as_str`].
    pub fn parse(s: &str) -> Option<Self> {
        Regime::ALL.into_iter().find(|r| r.as_str() == s)
    }
}

impl fmt::Display for Regime {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// A closed interval of thrusts (H/W_half); ends may be infinite, `lo > hi` means empty.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Interval {
    /// Lower end.
    pub lo: f64,
    /// Upper end.
    pub hi: f64,
}

impl Interval {
    /// The empty interval.
    pub const EMPTY: Interval = Interval {
        lo: f64::INFINITY,
        hi: f64::NEG_INFINITY,
    };

    /// True when no value lies in it.
    pub fn is_empty(&self) -> bool {
        !(self.lo <= self.hi)
    }

    /// hi − lo: negative when the interval is empty, +∞ when an end is infinite, NaN when an
    /// end is.
    pub fn width(&self) -> f64 {
        self.hi - self.lo
    }

    /// Intersection of two intervals.
    pub fn intersect(&self, other: &Interval) -> Interval {
        Interval {
            lo: self.lo.max(other.lo),
            hi: self.hi.min(other.hi),
        }
    }

    /// The lower end when the interval is non-empty and the end finite.
    pub fn finite_lo(&self) -> Option<f64> {
        (!self.is_empty() && self.lo.is_finite()).then_some(self.lo)
    }

    /// The upper end when the interval is non-empty and the end finite.
    pub fn finite_hi(&self) -> Option<f64> {
        (!self.is_empty() && self.hi.is_finite()).then_some(self.hi)
    }
}
