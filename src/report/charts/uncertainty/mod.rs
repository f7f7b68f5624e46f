//! The figures of a sampling study, from estimates.parquet, samples.parquet and the
//! collapse curves of curves.parquet: the samples over the (μ, K) plane, the probability of
//! each mechanism, the probability against a grid axis, the fragility curve, the Sobol
//! indices and what a sample size buys.

use super::{Chart, FigureSpec, LoadCaseFigure};
use crate::plot::palette;
use crate::plot::uncertainty::{Bar, BarGroup, BarsChart, SampleDot, SampleMap};
use crate::report::data::RunData;
use crate::store::EstimateRow;

mod curves;

use curves::{against_axis, convergence, fragility};

/// The estimates of one load case.
pub struct Estimates<'a> {
    rows: Vec<&'a EstimateRow>,
}

impl<'a> Estimates<'a> {
    /// The estimates of load case `lc`.
    pub fn of(data: &'a RunData, lc: &str) -> Self {
        Estimates {
            rows: data
                .estimates
                .iter()
                .filter(|r| r.load_case == lc)
                .collect(),
        }
    }

    /// The rows of a quantity at a point.
    pub fn get(&self, point: u64, quantity: &str) -> Vec<&'a EstimateRow> {
        self.rows
            .iter()
            .copied()
            .filter(|r| r.point == point && r.quantity == quantity)
            .collect()
    }

    /// The row of a quantity and parameter at a point.
    pub fn one(&self, point: u64, quantity: &str, parameter: &str) -> Option<&'a EstimateRow> {
        self.rows
            .iter()
            .copied()
            .find(|r| r.point == point && r.quantity == quantity && r.parameter == parameter)
    }

    /// The grid points, in order.
    pub fn points(&self) -> Vec<u64> {
        let mut p: Vec<u64> = self.rows.iter().map(|r| r.point).collect();
        p.sort_unstable();
        p.dedup();
        p
    }

    /// The grid values of a point, (axis, value), in grid order.
    pub fn grid(&self, point: u64) -> Vec<(String, f64)> {
        self.get(point, "grid")
            .into_iter()
            .map(|r| (r.parameter.clone(), r.value))
            .collect()
    }

    /// A point's grid values in words (`K = 1.2, μ = 0.4`), empty without grid axes.
    pub fn label(&self, point: u64) -> String {
        self.grid(point)
            .iter()
            .map(|(a, v)| value_words(a, *v))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The point a one-point figure shows: the one whose probability of not standing is
    /// nearest ½ (at 0 or 1 there is nothing to read), the first one when none has one.
    pub fn informative_point(&self) -> Option<u64> {
        let points = self.points();
        let p = |q: u64| self.one(q, "probability", "").map(|r| r.value);
        points
            .iter()
            .copied()
            .filter(|&q| p(q).is_some())
            .min_by(|&a, &b| {
                let d = |q| (p(q).unwrap_or(0.0) - 0.5).abs();
                d(a).total_cmp(&d(b))
            })
            .or_else(|| points.first().copied())
    }
}

/// The symbol of a grid axis or uncertain parameter, with its unit.
pub fn symbol(name: &str) -> &'static str {
    match name {
        "k" => "K",
        "t_over_r" => "t/R_c",
        "mu" => "μ",
        "half_angle_deg" => "α (°)",
        "eccentricity" => "e",
        "voussoirs" => "N",
        "at_deg" => "θ (°)",
        "at_x" => "x/L",
        "lambda" => "λ",
        _ => "value",
    }
}

/// An axis in words, for an axis title.
pub fn axis_words(name: &str) -> String {
    if let Some((param, field)) = name.split_once('.') {
        return format!("{field} of the distribution of {}", symbol(param));
    }
    let words = match name {
        "k" => "thickness ratio K = R/r",
        "t_over_r" => "thickness t/R_c",
        "mu" => "friction coefficient μ",
        "half_angle_deg" => "half-angle α (°)",
        "voussoirs" => "voussoirs N",
        "at_deg" => "load position θ (° from the crown)",
        "at_x" => "load position x/L",
        _ => "value",
    };
    words.to_string()
}

/// A grid value in words: `K = 1.2`, `θ = 22.5°`, `sd of μ = 0.05` (an axis of a
/// distribution's parameter).
pub fn value_words(name: &str, v: f64) -> String {
    let v = crate::report::format::given(v);
    if let Some((param, field)) = name.split_once('.') {
        return format!("{field} of {} = {v}", symbol(param));
    }
    match name {
        "half_angle_deg" => format!("α = {v}°"),
        "at_deg" => format!("θ = {v}°"),
        other => format!("{} = {v}", symbol(other)),
    }
}

/// A mechanism name in words, `none` being both domains empty.
pub fn mechanism_words(m: &str) -> &str {
    if m == "none" { "Hʳ and Hˢ empty" } else { m }
}

/// Every figure of a sampling study's load case.
pub fn figures(data: &RunData, lc: &LoadCaseFigure) -> Vec<FigureSpec> {
    let Some(s) = &data.manifest.sampling else {
        return Vec::new();
    };
    let e = Estimates::of(data, lc.name);
    let mut out = Vec::new();
    out.extend(sample_map(data, lc));
    match s.question.as_str() {
        "probability" => {
            out.extend(mechanism_bars(
                &e,
                lc,
                "mechanism",
                "Probability of collapse by mechanism",
            ));
            out.extend(against_axis(&e, lc, "probability"));
            out.extend(convergence(&e, lc, &s.method));
        }
        "fragility" => {
            out.extend(fragility(&e, lc));
            out.extend(mechanism_bars(
                &e,
                lc,
                "limit_mechanism",
                "Mechanism at λ_max",
            ));
        }
        _ if live(data, lc) => {
            out.extend(sobol_bars(data, &e, lc));
            out.extend(mechanism_bars(
                &e,
                lc,
                "limit_mechanism",
                "Mechanism at λ_max",
            ));
        }
        _ => {
            out.extend(sobol_bars(data, &e, lc));
            out.extend(mechanism_bars(
                &e,
                lc,
                "mechanism",
                "Probability of collapse by mechanism",
            ));
        }
    }
    out
}

/// True when the load case has a live load (its samples find λ_max).
fn live(data: &RunData, lc: &LoadCaseFigure) -> bool {
    data.manifest
        .load_cases
        .iter()
        .find(|l| l.name == lc.name)
        .is_some_and(|l| l.kind != "self_weight")
}

fn sample_map(data: &RunData, lc: &LoadCaseFigure) -> Option<FigureSpec> {
    let dots: Vec<SampleDot> = (data.samples.iter())
        .filter(|s| s.load_case == lc.name)
        .map(|s| SampleDot {
            mu: s.mu,
            k: s.k,
            outcome: s.outcome.clone(),
        })
        .collect();
    if dots.is_empty() {
        return None;
    }
    let limit = data
        .manifest
        .sampling
        .as_ref()
        .is_some_and(|s| s.question != "probability" && live(data, lc));
    let figure = crate::figdata::sampled::samples_figure(lc.name);
    let curves: Vec<(String, Vec<(f64, f64)>)> = ["rotational", "mixed", "sliding"]
        .into_iter()
        .map(|m| (m.to_string(), data.curve(&figure, &format!("k_crit:{m}"))))
        .filter(|(_, pts)| pts.iter().any(|p| p.1.is_finite()))
        .collect();
    let mu_min = data
        .curve(&figure, crate::figdata::sampled::MU_MIN_SERIES)
        .first()
        .map(|p| p.0);
    let n = dots.len();
    let points = Estimates::of(data, lc.name).points();
    let at = match points.first() {
        Some(&p) if points.len() > 1 => format!(" at {}", Estimates::of(data, lc.name).label(p)),
        _ => String::new(),
    };
    let others: Vec<&str> = (data.manifest.sampling.iter())
        .flat_map(|s| &s.params)
        .map(|p| p.name.as_str())
        .filter(|p| !matches!(*p, "k" | "t_over_r" | "mu"))
        .collect();
    let other = if others.is_empty() {
        String::new()
    } else {
        format!(
            " The samples also vary {}, which this projection onto (μ, K) does not show.",
            others
                .iter()
                .map(|p| symbol(p))
                .collect::<Vec<_>>()
                .join(", ")
        )
    };
    let curve_text = if curves.is_empty() {
        String::new()
    } else {
        " The line is the collapse thickness K_c(μ) of the study's arch, coloured by the \
         mechanism at collapse: a sample below it does not stand."
            .to_string()
    };
    let curve_text = match mu_min {
        Some(m) if !curves.is_empty() => format!(
            "{curve_text} Left of the dashed line μ_min = {} no thickness stands.",
            crate::report::format::sig(m, 4)
        ),
        _ => curve_text,
    };
    Some(FigureSpec {
        stem: format!("samples{}", lc.stem_suffix),
        title: format!("Samples over the (μ, K) plane{}", lc.title_suffix),
        caption: if limit {
            let black = if dots.iter().any(|d| d.outcome == "none") {
                " (black: the arch does not stand under its own weight, λ_max = 0)"
            } else {
                ""
            };
            let line = if curves.is_empty() {
                ""
            } else {
                " The line, where it falls in the plotted range, is the collapse thickness under \
                 self-weight alone, K_c(μ), below which λ_max is 0."
            };
            format!(
                "The first {n} samples of (μ, K){at}, in the colour of the mechanism that sets \
                 their largest load factor λ_max{black}.{line}{other}"
            )
        } else {
            format!(
                "The first {n} samples of (μ, K){at}, grey where the arch stands and in the colour \
                 of its collapse mechanism where it does not.{curve_text}{other}"
            )
        },
        chart: Chart::SampleMap(SampleMap {
            title: format!("Samples{}", lc.title_suffix),
            dots,
            curves,
            mu_min,
            by_limit: limit,
            y_desc: "thickness ratio K = R/r".into(),
        }),
    })
}

fn mechanism_bars(
    e: &Estimates,
    lc: &LoadCaseFigure,
    quantity: &str,
    title: &str,
) -> Option<FigureSpec> {
    let point = e.informative_point()?;
    let mut groups = Vec::new();
    if quantity == "mechanism" {
        let total = e.one(point, "probability", "")?;
        groups.push(BarGroup {
            label: "does not stand".into(),
            bars: vec![bar("", total, palette::INK)],
        });
        if let Some(x) = e
            .one(point, "exact_probability", "")
            .filter(|x| x.value.is_finite())
        {
            groups.push(BarGroup {
                label: "does not stand, exact".into(),
                bars: vec![bar("", x, palette::GREEN)],
            });
        }
    }
    for m in ["rotational", "mixed", "sliding", "none"] {
        let Some(r) = e.one(point, quantity, m) else {
            continue;
        };
        if r.value == 0.0 && m == "none" {
            continue;
        }
        groups.push(BarGroup {
            label: mechanism_words(m).to_string(),
            bars: vec![bar("", r, palette::mechanism(m))],
        });
    }
    let top = groups
        .iter()
        .flat_map(|g| &g.bars)
        .map(|b| {
            if b.interval.1.is_finite() {
                b.interval.1
            } else {
                b.value
            }
        })
        .fold(0.0f64, f64::max);
    let at = e.label(point);
    let at = if at.is_empty() {
        String::new()
    } else {
        format!(" at {at}")
    };
    let what = if quantity == "mechanism" {
        "the probability that the arch does not stand, and that it fails by each mechanism"
    } else {
        "the share of samples whose largest load factor λ_max is reached by each mechanism"
    };
    Some(FigureSpec {
        stem: format!("{}{}", quantity.replace('_', "-"), lc.stem_suffix),
        title: format!("{title}{}", lc.title_suffix),
        caption: format!(
            "Bars: {what}{at}, with 95 % Wilson intervals (whiskers). {}",
            if quantity == "mechanism" {
                "The green bar, where shown, is the exact probability by quadrature over μ of the \
                 thickness outside the windows in which the arch stands."
            } else {
                ""
            }
        ),
        chart: Chart::Bars(BarsChart {
            title: format!("{title}{}", lc.title_suffix),
            x_desc: if quantity == "mechanism" {
                "probability".into()
            } else {
                "share of samples".into()
            },
            groups,
            x_range: (0.0, (top * 1.25).clamp(1e-3, 1.0)),
        }),
    })
}

fn bar(series: &str, r: &EstimateRow, color: plotters::style::RGBColor) -> Bar {
    Bar {
        series: series.into(),
        value: r.value,
        interval: (r.lo.unwrap_or(f64::NAN), r.hi.unwrap_or(f64::NAN)),
        color,
    }
}

fn sobol_bars(data: &RunData, e: &Estimates, lc: &LoadCaseFigure) -> Option<FigureSpec> {
    let s = data.manifest.sampling.as_ref()?;
    let point = *e.points().first()?;
    let mut groups = Vec::new();
    for p in &s.params {
        let (Some(f), Some(t)) = (
            e.one(point, "first_order", &p.name),
            e.one(point, "total", &p.name),
        ) else {
            continue;
        };
        groups.push(BarGroup {
            label: symbol(&p.name).to_string(),
            bars: vec![
                bar("first order S_i", f, palette::BLUE),
                bar("total S_Ti", t, palette::ORANGE),
            ],
        });
    }
    if groups.is_empty() {
        return None;
    }
    let output = if live(data, lc) {
        "the largest load factor λ_max"
    } else {
        "the stability margin t/t_c − 1 (t_c the collapse thickness at the sample's other values; −1 where no thickness stands)"
    };
    let top = groups
        .iter()
        .flat_map(|g| &g.bars)
        .map(|b| b.interval.1.max(b.value))
        .filter(|v| v.is_finite())
        .fold(1.0f64, f64::max);
    Some(FigureSpec {
        stem: format!("sobol-indices{}", lc.stem_suffix),
        title: format!("Sobol indices{}", lc.title_suffix),
        caption: format!(
            "First-order (Saltelli 2010) and total (Jansen 1999) Sobol indices of {output} to each \
             uncertain parameter, from {} base samples (n (d + 2) analyses), with 95 % bootstrap \
             intervals ({} resamples). The first-order index is the share of the variance a \
             parameter explains alone; the total index adds its interactions.",
            s.n, s.bootstrap
        ),
        chart: Chart::Bars(BarsChart {
            title: format!("Sobol indices{}", lc.title_suffix),
            x_desc: "index".into(),
            groups,
            x_range: (0.0_f64.min(-0.02), top.min(1.2)),
        }),
    })
}
