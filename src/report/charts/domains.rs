//! Figure 2: the thrust domains Hʳ and Hˢ of a scene against the joint angle.

use super::{Chart, FigureSpec, mu_text, safe};
use crate::figdata;
use crate::plot::domains::{BoundCurve, BoundFamily, DomainsChart};
use crate::report::data::RunData;
use crate::report::format::{given, short};
use crate::store::StateRow;

/// The thrust-domains figure of a scene, from the curves stored for it.
pub fn figure(data: &RunData, s: &StateRow) -> FigureSpec {
    let fig = figdata::domains_figure(&s.state_id);
    figure_of(s, super::arch_axis::axes(data), |series| {
        data.curve(&fig, series)
    })
}

/// The thrust-domains figure of a scene whose Fig. 2 curves `c` gives by series name
/// (`h_min_r_extrados`, …, `h_max_s`, as curves.parquet names them), in a study whose arch
/// axes are `varied`.
pub fn figure_of(
    s: &StateRow,
    varied: super::arch_axis::ArchAxes,
    c: impl Fn(&str) -> Vec<(f64, f64)>,
) -> FigureSpec {
    let curve = |label: &str, series: &str, family, upper| BoundCurve {
        label: label.into(),
        points: c(series),
        family,
        upper,
    };
    let curves = vec![
        curve(
            "min, eq. 2a, thrust at crown extrados",
            "h_min_r_extrados",
            BoundFamily::CrownExtrados,
            false,
        ),
        curve(
            "max, eq. 2b, thrust at crown extrados",
            "h_max_r_extrados",
            BoundFamily::CrownExtrados,
            true,
        ),
        curve(
            "min, eq. 2a, thrust at crown intrados",
            "h_min_r_intrados",
            BoundFamily::CrownIntrados,
            false,
        ),
        curve(
            "max, eq. 2b, thrust at crown intrados",
            "h_max_r_intrados",
            BoundFamily::CrownIntrados,
            true,
        ),
        curve(
            "min, eq. 4a (sliding)",
            "h_min_s",
            BoundFamily::Sliding,
            false,
        ),
        curve(
            "max, eq. 4b (sliding)",
            "h_max_s",
            BoundFamily::Sliding,
            true,
        ),
    ];
    let interval = |lo: Option<f64>, hi: Option<f64>, exists: bool| {
        exists.then(|| (lo.unwrap_or(f64::NEG_INFINITY), hi.unwrap_or(f64::INFINITY)))
    };
    let regime = s.regime.as_deref().unwrap_or("");
    let r_exists = !matches!(regime, "rotational" | "none");
    let s_exists = !matches!(regime, "sliding" | "none");
    let arch = super::state::arch_text(s, varied);
    let on = if arch.is_empty() {
        String::new()
    } else {
        format!(" ({arch})")
    };
    let title = format!(
        "Domains Hʳ and Hˢ, K = {}, μ = {}{on}",
        given(s.scene_k),
        mu_text(s.scene_mu)
    );
    FigureSpec {
        stem: format!("domains-{}", safe(&s.state_id)),
        title: format!(
            "Thrust domains of scene K = {}, μ = {}{on}",
            given(s.scene_k),
            mu_text(s.scene_mu)
        ),
        caption: format!(
            "The paper's Fig. 2 for K = {} (t/R_c = {}) and μ = {}: against the joint angle θ, the crown thrust H/W_half at which the line of thrust through the crown extrados or intrados touches the intrados (eq. 2a, lower bounds) or the extrados (eq. 2b, upper bounds) of joint θ, and the sliding bounds of eqs. 4a/4b. Bands: Hʳ (rotational), Hˢ (sliding) and their intersection, the thrusts of admissible states. Regime: {}.",
            given(s.scene_k),
            short(crate::model::t_over_r_from_k(s.scene_k)),
            mu_text(s.scene_mu),
            if regime.is_empty() { "—" } else { regime }
        ),
        chart: Chart::Domains(DomainsChart {
            title,
            alpha_deg: s.half_angle_deg,
            curves,
            h_r: interval(s.thrust_r_min, s.thrust_r_max, r_exists),
            h_s: interval(s.thrust_s_min, s.thrust_s_max, s_exists),
            discrete: s.voussoirs.is_some(),
            marks: Vec::new(),
        }),
    }
}
