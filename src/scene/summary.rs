//! The readable summary that `archstudy solve` prints without `--json`.

use super::solution::Outcome;
use super::{Find, Solution};
use crate::analysis::gap::GapStatus;
use crate::analysis::{Hinge, SlidingJoint};
use crate::model::WeightModel;
use std::fmt::Write;

/// A value with ten decimals, or `none`.
fn opt(x: Option<f64>) -> String {
    x.map_or("none".to_string(), |v| format!("{v:.10}"))
}

fn hinge_list(h: &[Hinge]) -> String {
    h.iter()
        .map(|h| format!("{:.4}° {}", h.angle_deg, h.face.as_str()))
        .collect::<Vec<_>>()
        .join(", ")
}

fn sliding_list(s: &[SlidingJoint]) -> String {
    s.iter()
        .map(|s| format!("{:.4}° {}", s.angle_deg, s.sense.as_str()))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A short readable summary of a solution (the output of `archstudy solve` without `--json`).
pub fn summary(s: &Solution) -> String {
    let mut o = String::new();
    arch_lines(&mut o, s);
    if s.find == Find::State {
        state_lines(&mut o, s);
    } else {
        if let Some(line) = s.outcome.and_then(|outcome| outcome_line(s.find, outcome)) {
            let _ = writeln!(o, "{line}");
        }
        if s.find == Find::Thresholds {
            threshold_lines(&mut o, s);
        }
        critical_lines(&mut o, s);
        window_lines(&mut o, s);
        mechanism_lines(&mut o, s);
        gap_lines(&mut o, s);
        if s.find == Find::Thrust {
            thrust_lines(&mut o, s);
        }
    }
    let _ = writeln!(o, "solve time: {:.1} µs", s.solve_time_us);
    o
}

/// The arch, its thickness and friction; the form and load when they are not the paper's.
fn arch_lines(o: &mut String, s: &Solution) {
    let mu = if s.mu_infinite {
        "inf".to_string()
    } else {
        opt(s.mu)
    };
    let n = s
        .voussoirs
        .map_or("continuum".to_string(), |n| format!("{n} voussoirs"));
    let weight = match s.weight {
        WeightModel::Annular => "annular",
        WeightModel::Centreline => "centreline",
    };
    let _ = writeln!(
        o,
        "arch: half-angle {}°, {weight} weight, {n}; K = {}, t/R_c = {}, μ = {mu}",
        s.half_angle_deg,
        opt(s.k),
        opt(s.t_over_r),
    );
    if s.shape != "circular" || s.joints != "radial" || s.load != "self_weight" {
        let mut form = s.shape.to_string();
        if let Some(e) = s.eccentricity {
            form.push_str(&format!(" (e = {e})"));
        }
        let mut load = match (s.at_deg, s.at_x) {
            // An x/L position's angle is computed: shown to 1e-6°, beside the x/L given.
            (Some(a), Some(x)) => {
                format!("self-weight and a point load at x/L = {x} ({a:.6}°)")
            }
            (Some(a), None) => format!("self-weight and a point load at {a}°"),
            (None, _) if s.load == "horizontal" => "self-weight and a horizontal load".to_string(),
            (None, _) => "self-weight".to_string(),
        };
        if let Some(l) = s.lambda {
            load.push_str(&format!(", λ = {l}"));
        }
        let _ = writeln!(o, "form: {form}, {} joints; load: {load}", s.joints);
    }
}

/// The regime and both thrust domains.
fn state_lines(o: &mut String, s: &Solution) {
    let regime = s.regime.map_or("?", |r| r.as_str());
    let _ = writeln!(o, "regime: {regime}");
    let _ = writeln!(
        o,
        "H^r/W_half: [{}, {}]",
        opt(s.thrust_r_min),
        opt(s.thrust_r_max)
    );
    let _ = writeln!(
        o,
        "H^s/W_half: [{}, {}]",
        opt(s.thrust_s_min),
        opt(s.thrust_s_max)
    );
}

/// What an outcome other than a found value means for this find.
fn outcome_line(find: Find, outcome: Outcome) -> Option<String> {
    let line = match (find, outcome) {
        (Find::Thickness, Outcome::NeverStands) => {
            "no collapse thickness: the arch cannot stand at this μ for any K"
        }
        (Find::Thickness, Outcome::AlwaysStands) => {
            "no collapse thickness: the arch stands for every K > 1"
        }
        (Find::Friction, Outcome::NeverStands) => {
            "no critical friction: the arch cannot stand at this K for any μ"
        }
        (Find::Friction, Outcome::AlwaysStands) => {
            "critical friction 0: the arch stands without friction"
        }
        (Find::LoadFactor, Outcome::Unbounded) => {
            "load factor unbounded: the arch carries every multiple of the live load"
        }
        (Find::LoadFactor, Outcome::NeverStands) => {
            "no load factor: the arch cannot stand under this load"
        }
        (_, Outcome::Invalid) => "no answer: the form does not exist for these inputs",
        (_, Outcome::Unsupported) => {
            "no answer: this find is defined for self-weight on a circular arch with radial joints only"
        }
        (_, Outcome::Unconfirmed) => {
            "no answer: the route's answer for the whole range was contradicted by the state \
             find at an end of that range"
        }
        (_, Outcome::Failed | Outcome::NotConverged) => {
            return Some(format!(
                "no answer: the analysis {}",
                outcome.as_str().replace('_', " ")
            ));
        }
        _ => return None,
    };
    Some(line.to_string())
}

/// The four thresholds of the arch under self-weight.
fn threshold_lines(o: &mut String, s: &Solution) {
    let _ = writeln!(o, "K_c (μ = ∞) = {}", opt(s.k_c_rotational));
    let _ = writeln!(
        o,
        "μ at the rotational/mixed bifurcation = {}",
        opt(s.mu_rotational_mixed)
    );
    let _ = writeln!(o, "μ_min = {}", opt(s.mu_min));
    let _ = writeln!(
        o,
        "K at the mixed/sliding bifurcation = {}",
        opt(s.k_mixed_sliding)
    );
}

/// The critical value found, with its crown thrust and shear.
fn critical_lines(o: &mut String, s: &Solution) {
    if let Some(k) = s.k_crit {
        let _ = writeln!(
            o,
            "K_c = {k:.12} ≈ {k:.4}  (t/R_c = {:.12})",
            s.t_over_r_crit.unwrap_or(f64::NAN)
        );
    }
    if let Some(m) = s.mu_crit {
        let _ = writeln!(o, "μ_c = {m:.12} ≈ {m:.3}");
    }
    if let Some(l) = s.load_factor {
        let _ = writeln!(
            o,
            "λ_max = {l:.12} ≈ {l:.4} (multiples of the total weight)"
        );
    }
    if let Some(m) = s.mechanism {
        let _ = writeln!(o, "mechanism: {m}");
    }
    if let Some(h) = s.thrust_over_half_weight {
        let _ = writeln!(o, "H/W_half = {h:.12} ≈ {h:.3}");
    }
    if let Some(v) = s.crown_shear
        && v != 0.0
    {
        let _ = writeln!(o, "V/W_half at the crown = {v:.12}");
    }
}

/// The windows of K of a thickness find, and whether a thicker arch fails again.
fn window_lines(o: &mut String, s: &Solution) {
    let Some(to) = s.k_windows_scanned_to else {
        return;
    };
    let res = s.k_windows_resolution.unwrap_or(f64::NAN);
    let list = s
        .k_windows
        .iter()
        .map(|(a, b)| match b {
            Some(b) => format!("[{a:.7}, {b:.7}]"),
            None => format!("[{a:.7}, end of the scan)"),
        })
        .collect::<Vec<_>>()
        .join(", ");
    if s.k_windows.is_empty() {
        let _ = writeln!(
            o,
            "stands for no K in (1, {to:.7}] (scanned at steps of {res})"
        );
        return;
    }
    let _ = writeln!(
        o,
        "stands for K in {list} (scanned to K = {to:.7} at steps of {res})"
    );
    if s.fails_again() {
        let _ = writeln!(
            o,
            "a thicker arch than K_c fails again: the arch does not stand for every K above K_c"
        );
    }
}

/// Hinges, sliding joints and the work equation of the collapse mechanism.
fn mechanism_lines(o: &mut String, s: &Solution) {
    if !s.hinges.is_empty() {
        let _ = writeln!(o, "hinges: {}", hinge_list(&s.hinges));
    }
    if !s.sliding_joints.is_empty() {
        let _ = writeln!(o, "sliding joints: {}", sliding_list(&s.sliding_joints));
    }
    if let (Some(dof), Some(a), Some(f), Some(r)) = (
        s.mechanism_dof,
        s.work_loads,
        s.work_friction,
        s.work_residual,
    ) {
        let _ = writeln!(
            o,
            "work equation: dL(a) = {a:.6e}, dL(r,t) = {f:.6e}, residual {r:.1e} \
             (mechanism dof {dof})"
        );
    }
    if let Some(v) = s.critical_apex_shared {
        let _ = writeln!(
            o,
            "apex load: the value above puts it on the right half (least favourable split); \
             shared freely between the halves (most favourable split): {v:.12}"
        );
    }
    if s.mechanism_admissible == Some(false) {
        let _ = writeln!(
            o,
            "no mechanism of this pattern obeys every flow rule (normality at the hinges, \
             slip in the sense of friction): the state is a limit of the static problem \
             without a non-associative collapse mechanism"
        );
    }
}

/// The first complete solution along the find's path: the other end of the gap.
fn gap_lines(o: &mut String, s: &Solution) {
    let Some(status) = s.gap else {
        return;
    };
    let (name, path) = match s.find {
        Find::LoadFactor => ("λ", "increasing λ"),
        Find::Thickness => ("K", "decreasing K"),
        _ => ("μ", "decreasing μ"),
    };
    let to = opt(s.gap_searched_to);
    match status {
        GapStatus::NoGap => {
            let _ = writeln!(
                o,
                "collapse: no gap: the static limit is the first complete solution along \
                 {path} (a mechanism obeying the flow rules starts there and nowhere before)"
            );
        }
        GapStatus::Gap => {
            let v = s.collapse_value.unwrap_or(f64::NAN);
            let w = s.gap_width.unwrap_or(f64::NAN);
            let _ = writeln!(
                o,
                "collapse: {name} = {v:.12} ≈ {v:.4}, the first complete solution along {path}; \
                 the static limit lies {w:.6} beyond it. Between the two the outcome depends on \
                 contact stiffness and initial stress, which rigid-block statics cannot settle"
            );
        }
        GapStatus::NoCompleteSolution => {
            let from = if s.find == Find::LoadFactor {
                format!("from λ = 0 up to the static limit or λ = {to}")
            } else {
                format!("from {name} = {to} to the static limit")
            };
            let _ = writeln!(
                o,
                "collapse: no complete solution along {path} ({from}): no admissible state \
                 there admits a mechanism obeying the flow rules"
            );
            return;
        }
        GapStatus::Failed => {
            let _ = writeln!(
                o,
                "collapse: the search did not finish (more vertices, polytopes or walked \
                 joints than it may take)"
            );
            return;
        }
    }
    if let Some(m) = s.collapse_mechanism {
        let mut parts = vec![format!("collapse mechanism: {m}")];
        if !s.collapse_hinges.is_empty() {
            parts.push(format!("hinges {}", hinge_list(&s.collapse_hinges)));
        }
        if !s.collapse_sliding_joints.is_empty() {
            parts.push(format!(
                "sliding {}",
                sliding_list(&s.collapse_sliding_joints)
            ));
        }
        if !s.collapse_lifted_joints.is_empty() {
            let l: Vec<String> = s
                .collapse_lifted_joints
                .iter()
                .map(|a| format!("{a:.4}°"))
                .collect();
            parts.push(format!("lifting off at {}", l.join(", ")));
        }
        let _ = writeln!(o, "{}", parts.join("; "));
    }
    if let (Some(a), Some(f), Some(r)) = (
        s.collapse_work_loads,
        s.collapse_work_friction,
        s.collapse_work_residual,
    ) {
        // The breach is measured on the search's own mechanisms; the static limit's (taken
        // when the search met none) is checked by the static route.
        let breach = s.collapse_flow_violation.map_or(String::new(), |v| {
            format!("; largest breach of a flow rule {v:.1e}")
        });
        let _ = writeln!(
            o,
            "its work equation: dL(a) = {a:.6e}, dL(r,t) = {f:.6e}, residual {r:.1e}{breach}"
        );
    }
    if let Some(l) = s.collapse_on_loading {
        let at = if l == 0.0 {
            "under its own weight alone (λ = 0)".to_string()
        } else {
            format!("at λ = {l:.6}")
        };
        let _ = writeln!(
            o,
            "on the way up: with the live load rising from zero, the arch at the collapse value \
             would already start to move {at}, below this scene's λ = {}",
            s.lambda.unwrap_or(f64::NAN)
        );
    }
}

/// The minimum and maximum thrust states.
fn thrust_lines(o: &mut String, s: &Solution) {
    if s.outcome == Some(Outcome::NeverStands) {
        let _ = writeln!(o, "no admissible state: the arch cannot stand");
        return;
    }
    let _ = writeln!(
        o,
        "H_min/W_half = {}  hinges: {}",
        opt(s.thrust_min),
        hinge_list(&s.hinges_min)
    );
    if !s.sliding_joints_min.is_empty() {
        let _ = writeln!(o, "  sliding: {}", sliding_list(&s.sliding_joints_min));
    }
    let _ = writeln!(
        o,
        "H_max/W_half = {}  hinges: {}",
        opt(s.thrust_max),
        hinge_list(&s.hinges_max)
    );
    if !s.sliding_joints_max.is_empty() {
        let _ = writeln!(o, "  sliding: {}", sliding_list(&s.sliding_joints_max));
    }
}
