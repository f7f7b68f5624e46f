//! Pure mechanics: statics, the paper's domains, regimes and critical values.
//!
//! No I/O, no threads. Everything is normalised: lengths over the intrados radius r,
//! thrusts over the half weight W_half.

pub mod circular;
pub mod forms;
pub mod gap;
pub mod general;
pub mod kinematics;
pub mod lp;
pub mod roots;
pub mod settings;
pub mod statics;
pub mod symmetric;
pub mod types;
pub mod windows;

pub use types::{Face, Hinge, Interval, Mechanism, MechanismKind, Regime, Sense, SlidingJoint};

#[cfg(test)]
mod hard_cases;
