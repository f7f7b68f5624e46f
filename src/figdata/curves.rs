//! The curves the figures need that come from evaluating the statics: the thrust bounds of
//! the paper's Fig. 2 against the joint angle and the critical curves K_c(μ), μ_c(K). Pure functions of the analysis; no I/O.

use crate::analysis::circular::{SlidingBound, SymmetricCircular};
use crate::analysis::symmetric;
use crate::model::{Arch, Friction};

/// A sampled curve: (x, y) pairs, NaN in y where the curve does not exist.
pub type Samples = Vec<(f64, f64)>;

/// The six bounds of the paper's Fig. 2 against the joint angle θ (degrees), over W_half.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct DomainCurves {
    /// Eq. (2a) with the crown thrust at the crown extrados: H^{r,e}_min(θ).
    pub h_min_r_extrados: Samples,
    /// Eq. (2b) with the crown thrust at the crown extrados: H^{r,e}_max(θ).
    pub h_max_r_extrados: Samples,
    /// Eq. (2a) with the crown thrust at the crown intrados: H^{r,i}_min(θ).
    pub h_min_r_intrados: Samples,
    /// Eq. (2b) with the crown thrust at the crown intrados: H^{r,i}_max(θ) (where it is an
    /// upper bound: beyond cos θ = 1/K).
    pub h_max_r_intrados: Samples,
    /// Eq. (4a): H^s_min(θ) = W/tan(θ + φ).
    pub h_min_s: Samples,
    /// Eq. (4b): H^s_max(θ) = W/tan(θ − φ), where θ > φ.
    pub h_max_s: Samples,
}

/// The series names of the six bounds, as curves.parquet stores them.
pub const DOMAIN_SERIES: [&str; 6] = [
    "h_min_r_extrados",
    "h_max_r_extrados",
    "h_min_r_intrados",
    "h_max_r_intrados",
    "h_min_s",
    "h_max_s",
];

impl DomainCurves {
    /// One bound by its series name in curves.parquet (`h_min_r_extrados`, …, `h_max_s`);
    /// empty for another name.
    pub fn series(&self, name: &str) -> Samples {
        match name {
            "h_min_r_extrados" => self.h_min_r_extrados.clone(),
            "h_max_r_extrados" => self.h_max_r_extrados.clone(),
            "h_min_r_intrados" => self.h_min_r_intrados.clone(),
            "h_max_r_intrados" => self.h_max_r_intrados.clone(),
            "h_min_s" => self.h_min_s.clone(),
            "h_max_s" => self.h_max_s.clone(),
            _ => Samples::new(),
        }
    }
}

/// The joint angles (radians) at which a figure samples the right half: every joint of a
/// discrete arch, or 361 points of the continuum.
pub fn sample_angles(sym: &SymmetricCircular) -> Vec<f64> {
    match sym.voussoirs {
        Some(_) => sym.half_joints(),
        None => (0..=360)
            .map(|i| sym.alpha * f64::from(i) / 360.0)
            .collect(),
    }
}

/// The thrust h at which the line of thrust through the crown point at height `y_p` (over r)
/// touches the intrados (`lower`) and the extrados (`upper`) of joint θ: the linear forms of
/// eqs. (2a, 2b) solved for h. `None` where the row does not bound h from that side.
fn rotational_bounds(sym: &SymmetricCircular, theta: f64, y_p: f64) -> (Option<f64>, Option<f64>) {
    // L(θ, h) = a + h·c_l ≤ m = h·y_p  and  m ≤ U(θ, h) = b + h·c_u.
    let a = sym.intrados(theta, 0.0);
    let c_l = sym.intrados(theta, 1.0) - a;
    let b = sym.extrados(theta, 0.0);
    let c_u = sym.extrados(theta, 1.0) - b;
    let eps = 1e-12;
    let lower = (y_p - c_l > eps).then(|| a / (y_p - c_l));
    let upper = (y_p - c_u > eps).then(|| b / (y_p - c_u));
    (lower, upper)
}

/// The curves of Fig. 2 for an arch and friction.
pub fn domain_curves(arch: &Arch, friction: Friction) -> DomainCurves {
    let sym = SymmetricCircular::new(arch);
    let phi = friction.angle();
    let mut out = DomainCurves::default();
    let nan = f64::NAN;
    for theta in sample_angles(&sym) {
        let deg = theta.to_degrees();
        let (lo_e, hi_e) = rotational_bounds(&sym, theta, sym.k);
        let (lo_i, hi_i) = rotational_bounds(&sym, theta, 1.0);
        out.h_min_r_extrados.push((deg, lo_e.unwrap_or(nan)));
        out.h_max_r_extrados.push((deg, hi_e.unwrap_or(nan)));
        out.h_min_r_intrados.push((deg, lo_i.unwrap_or(nan)));
        out.h_max_r_intrados.push((deg, hi_i.unwrap_or(nan)));
        let [outward, inward] = sym.sliding_bounds(theta, phi);
        let max_s = match outward {
            SlidingBound::Upper(v) => v,
            _ => nan,
        };
        let min_s = match inward {
            SlidingBound::Lower(v) if theta > 0.0 || phi > 0.0 => v,
            _ => nan,
        };
        out.h_max_s.push((deg, max_s));
        out.h_min_s.push((deg, min_s));
    }
    out
}

/// K_c(μ) at the given friction values: NaN where the arch never stands (or always does).
pub fn critical_thickness_curve(arch: &Arch, mus: &[f64]) -> Samples {
    mus.iter()
        .map(|&mu| {
            let k = Friction::new(mu)
                .and_then(|f| symmetric::thickness(arch, f).found().map(|s| s.k))
                .unwrap_or(f64::NAN);
            (mu, k)
        })
        .collect()
}

/// μ_c(K) at the given thickness ratios: NaN where no friction lets the arch stand.
pub fn critical_friction_curve(arch: &Arch, ks: &[f64]) -> Samples {
    ks.iter()
        .map(|&k| {
            let c = symmetric::friction(&arch.with_k(k));
            let mu = match &c {
                symmetric::Critical::Found(s) => s.mu,
                symmetric::Critical::AlwaysStands => 0.0,
                symmetric::Critical::NeverStands => f64::NAN,
            };
            (k, mu)
        })
        .collect()
}

/// `n` values from `lo` to `hi` inclusive, with `extra` values inside the range merged in
/// (so that corners of a curve, e.g. bifurcations, are sampled exactly).
pub fn linspace_with(lo: f64, hi: f64, n: usize, extra: &[f64]) -> Vec<f64> {
    let mut v: Vec<f64> = (0..n)
        .map(|i| lo + (hi - lo) * i as f64 / (n.max(2) - 1) as f64)
        .collect();
    v.extend(extra.iter().copied().filter(|x| *x > lo && *x < hi));
    v.sort_by(f64::total_cmp);
    v.dedup_by(|a, b| merged(*a, *b));
    v
}

/// True when [`linspace_with`] takes two samples for one: within 1e-12 relative.
pub fn merged(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * (1.0 + b.abs())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fig2_bounds_give_the_domain_ends() {
        // H^r = [max H^{r,e}_min, min H^{r,i}_max] at K = 1.35 (paper §2.1).
        let arch = Arch::semicircular(1.35).unwrap();
        let f = Friction::new(0.4).unwrap();
        let c = domain_curves(&arch, f);
        let d = symmetric::domains(&arch, f);
        let max_lo = c
            .h_min_r_extrados
            .iter()
            .map(|p| p.1)
            .filter(|y| y.is_finite())
            .fold(f64::NEG_INFINITY, f64::max);
        let min_hi = c
            .h_max_r_intrados
            .iter()
            .map(|p| p.1)
            .filter(|y| y.is_finite())
            .fold(f64::INFINITY, f64::min);
        assert!((max_lo - d.rotational.interval.lo).abs() < 1e-4, "{max_lo}");
        assert!((min_hi - d.rotational.interval.hi).abs() < 1e-9, "{min_hi}");
        let s_hi = c.h_max_s.last().unwrap().1;
        assert!(
            (s_hi - 0.4).abs() < 1e-12,
            "at the springing H^s_max = μ W_half"
        );
    }
}
