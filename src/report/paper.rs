//! The values the paper prints (§5), for comparison when a study is the paper's case.

/// A printed value: its text as printed and its numeric value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Printed {
    /// As printed.
    pub text: &'static str,
    /// Its value.
    pub value: f64,
}

const fn printed(text: &'static str, value: f64) -> Printed {
    Printed { text, value }
}

/// K^c: rotational collapse thickness for large friction, and K at the rotational/mixed
/// bifurcation.
pub const K_C: Printed = printed("1.1136", 1.1136);
/// μ at the rotational/mixed bifurcation.
pub const MU_ROTATIONAL_MIXED: Printed = printed("0.395", 0.395);
/// μ below which equilibrium is impossible, the μ of the mixed/sliding bifurcation.
pub const MU_MIN: Printed = printed("0.309", 0.309);
/// K at the mixed/sliding bifurcation.
pub const K_MIXED_SLIDING: Printed = printed("1.2205", 1.2205);
/// The sliding joints at μ_min, degrees from the crown.
pub const SLIDING_JOINTS_DEG: &str = "29° and 90°";

/// The printed (μ, K) of a bifurcation between two mechanisms, in either order.
pub fn bifurcation(a: &str, b: &str) -> Option<(Printed, Printed)> {
    match (a.min(b), a.max(b)) {
        ("mixed", "rotational") => Some((MU_ROTATIONAL_MIXED, K_C)),
        ("mixed", "sliding") => Some((MU_MIN, K_MIXED_SLIDING)),
        _ => None,
    }
}
