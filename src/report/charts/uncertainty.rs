//! The figures of a sampling study, from estimates.parquet, samples.parquet and the
//! collapse curves of curves.parquet: the samples over the (μ, K) plane, the probability of
//! each mechanism, the probability against a grid axis, the fragility curve, the Sobol
//! indices and what a sample size buys.

use super::{Chart, FigureSpec, LoadCaseFigure};
use crate::plot::palette;
use crate::plot::uncertainty::{
    Bar, BarGroup, BarsChart, Curve, CurvePanel, CurvesChart, SampleDot, SampleMap,
};
use crate::report::data::RunData;
use crate::store::EstimateRow;

/// Most grid points drawn as separate curves of one panel.
const MAX_CURVES: usize = 8;

/// A fragility figure's λ axis is logarithmic when its values span more than this ratio.
const LOG_SPREAD: f64 = 50.0;

/// A fragility figure's λ axis ends at this many times the largest finite median.
const CAP_MEDIANS: f64 = 20.0;

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
pub fn axis_words(name: &str) -> &'static str {
    match name {
        "k" => "thickness ratio K = R/r",
        "t_over_r" => "thickness t/R_c",
        "mu" => "friction coefficient μ",
        "half_angle_deg" => "half-angle α (°)",
        "voussoirs" => "voussoirs N",
        "at_deg" => "load position θ (° from the crown)",
        "at_x" => "load position x/L",
        _ => "value",
    }
}

/// A grid value in words: `K = 1.2`, `θ = 22.5°`.
pub fn value_words(name: &str, v: f64) -> String {
    let v = crate::report::format::given(v);
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

/// The probability (with its band, and the exact value dashed) against the innermost grid
/// axis, one curve per value of the others.
fn against_axis(e: &Estimates, lc: &LoadCaseFigure, quantity: &str) -> Option<FigureSpec> {
    let points = e.points();
    if points.len() < 2 {
        return None;
    }
    let axis = e.grid(points[0]).last()?.0.clone();
    let mut lines: Vec<(String, Vec<u64>)> = Vec::new();
    for &p in &points {
        let g = e.grid(p);
        let others: Vec<String> = g[..g.len() - 1]
            .iter()
            .map(|(a, v)| format!("{a} = {}", crate::report::format::given(*v)))
            .collect();
        let key = others.join(", ");
        match lines.iter_mut().find(|(k, _)| *k == key) {
            Some((_, v)) => v.push(p),
            None => lines.push((key, vec![p])),
        }
    }
    let colors = [
        palette::BLUE,
        palette::RED,
        palette::GREEN,
        palette::PURPLE,
        palette::ORANGE,
        palette::SKY,
        palette::INK,
        palette::GREY,
    ];
    let mut curves = Vec::new();
    for ((key, pts), color) in lines.iter().take(MAX_CURVES).zip(colors) {
        let x_of = |p: u64| e.grid(p).last().map_or(f64::NAN, |g| g.1);
        let mut pts_xy = Vec::new();
        let mut band = Vec::new();
        let mut exact = Vec::new();
        for &p in pts {
            let x = x_of(p);
            if let Some(r) = e.one(p, quantity, "") {
                pts_xy.push((x, r.value));
                band.push((x, r.lo.unwrap_or(r.value), r.hi.unwrap_or(r.value)));
            }
            if let Some(r) = e
                .one(p, "exact_probability", "")
                .filter(|r| r.value.is_finite())
            {
                exact.push((x, r.value));
            }
        }
        let label = if key.is_empty() {
            "sampled".to_string()
        } else {
            key.clone()
        };
        curves.push(Curve {
            label,
            points: pts_xy,
            band,
            color,
            dashed: false,
            dots: true,
            line: true,
        });
        if !exact.is_empty() {
            curves.push(Curve {
                label: if key.is_empty() {
                    "exact".into()
                } else {
                    format!("{key}, exact")
                },
                points: exact,
                band: Vec::new(),
                color: if lines.len() == 1 {
                    palette::INK
                } else {
                    color
                },
                dashed: false,
                dots: true,
                line: false,
            });
        }
    }
    Some(FigureSpec {
        stem: format!(
            "probability-against-{}{}",
            axis.replace('_', "-"),
            lc.stem_suffix
        ),
        title: format!("Probability of collapse against {axis}{}", lc.title_suffix),
        caption: format!(
            "The sampled probability that the arch does not stand at each value of the grid axis \
             {axis} (dots, joined), with its 95 % Wilson band; dashed, the exact probability where \
             the mechanics gives it. Every point is estimated from the same samples of the \
             uncertain parameters (common random numbers), so the curve is smooth where the \
             estimates share their error."
        ),
        chart: Chart::Curves(CurvesChart {
            title: format!("P(collapse) against {axis}{}", lc.title_suffix),
            panels: vec![CurvePanel {
                title: String::new(),
                x_desc: axis_words(&axis).into(),
                y_desc: "probability of collapse".into(),
                curves,
                log: (false, false),
                y_range: None,
            }],
        }),
    })
}

fn fragility(e: &Estimates, lc: &LoadCaseFigure) -> Option<FigureSpec> {
    let points = e.points();
    let colors = [
        palette::BLUE,
        palette::RED,
        palette::GREEN,
        palette::PURPLE,
        palette::ORANGE,
        palette::SKY,
        palette::INK,
        palette::GREY,
    ];
    let mut curves: Vec<Curve> = Vec::new();
    for (&p, color) in points.iter().take(MAX_CURVES).zip(colors) {
        let rows = e.get(p, "fragility_cdf");
        if rows.is_empty() {
            continue;
        }
        let label = e.label(p);
        curves.push(Curve {
            label: if label.is_empty() {
                "P(λ_max ≤ λ)".into()
            } else {
                label
            },
            points: rows
                .iter()
                .map(|r| (r.x.unwrap_or(f64::NAN), r.value))
                .collect(),
            band: rows
                .iter()
                .map(|r| {
                    (
                        r.x.unwrap_or(f64::NAN),
                        r.lo.unwrap_or(r.value),
                        r.hi.unwrap_or(r.value),
                    )
                })
                .collect(),
            color,
            dashed: false,
            dots: false,
            line: true,
        });
    }
    if curves.is_empty() {
        return None;
    }
    // λ_max spread over decades (a load near a springing) is read on a logarithmic axis.
    let xs: Vec<f64> = curves
        .iter()
        .flat_map(|c| c.points.iter().map(|p| p.0))
        .filter(|x| x.is_finite() && *x > 0.0)
        .collect();
    let (lo, hi) = xs
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
    let log_x = hi / lo > LOG_SPREAD;
    // A few samples near an unbounded capacity would stretch the axis over decades: it ends
    // at CAP_MEDIANS times the largest finite median, each curve level beyond it.
    let cap = points
        .iter()
        .take(MAX_CURVES)
        .filter_map(|&p| e.one(p, "quantile", "0.5").map(|r| r.value))
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold(0.0f64, f64::max)
        * CAP_MEDIANS;
    for c in &mut curves {
        if log_x {
            c.points.retain(|p| p.0 > 0.0);
            c.band.retain(|b| b.0 > 0.0);
        }
        if cap > 0.0 {
            let last = c.points.iter().rev().find(|p| p.0 <= cap).copied();
            let last_band = c.band.iter().rev().find(|b| b.0 <= cap).copied();
            c.points.retain(|p| p.0 <= cap);
            c.band.retain(|b| b.0 <= cap);
            if let (Some((_, y)), Some((_, lo, hi))) = (last, last_band) {
                c.points.push((cap, y));
                c.band.push((cap, lo, hi));
            }
        }
    }
    let unbounded: Vec<String> = points
        .iter()
        .take(MAX_CURVES)
        .filter_map(|&p| {
            e.one(p, "unbounded", "").map(|r| {
                let at = e.label(p);
                let at = if at.is_empty() {
                    String::new()
                } else {
                    format!(" at {at}")
                };
                format!("{}{at}", crate::report::format::sig(r.value, 3))
            })
        })
        .collect();
    let unbounded = if unbounded.is_empty() {
        String::new()
    } else {
        format!(
            " A curve that stays below 1 has samples whose λ_max is unbounded (every λ stands): \
             a share of {}.",
            unbounded.join(", ")
        )
    };
    let at = e.label(points[0]);
    let at = if at.is_empty() || points.len() == 1 {
        String::new()
    } else {
        format!(" at {at}")
    };
    let q: Vec<String> = ["0.05", "0.5", "0.95"]
        .iter()
        .filter_map(|l| {
            e.one(points[0], "quantile", l).map(|r| {
                format!(
                    "{} % quantile{at} {}",
                    (l.parse::<f64>().unwrap_or(0.0) * 100.0).round(),
                    crate::report::format::sig(r.value, 4)
                )
            })
        })
        .collect();
    let capped = if cap > 0.0 && hi > cap {
        format!(
            " The λ axis ends at {} ({CAP_MEDIANS} times the largest median); a curve goes on \
             beyond it to its larger values.",
            crate::report::format::sig(cap, 3)
        )
    } else {
        String::new()
    };
    Some(FigureSpec {
        stem: format!("fragility{}", lc.stem_suffix),
        title: format!("Fragility curve{}", lc.title_suffix),
        caption: format!(
            "The fragility curve: the probability that the largest load factor λ_max of the live \
             load is at most λ, from the samples' λ_max (the static limit, the largest λ at which \
             an admissible state exists), with the 95 % Dvoretzky–Kiefer–Wolfowitz band (shaded). \
             An arch that does not stand under its own weight counts as λ_max = 0. {}.{unbounded}{capped} The key results give every curve's quantiles.",
            q.join(", ")
        ),
        chart: Chart::Curves(CurvesChart {
            title: format!("Fragility{}", lc.title_suffix),
            panels: vec![CurvePanel {
                title: String::new(),
                x_desc: "load factor λ".into(),
                y_desc: "P(λ_max ≤ λ)".into(),
                curves,
                log: (log_x, false),
                y_range: Some((0.0, 1.0)),
            }],
        }),
    })
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

fn convergence(e: &Estimates, lc: &LoadCaseFigure, method: &str) -> Option<FigureSpec> {
    let point = e
        .points()
        .into_iter()
        .find(|&p| !e.get(p, "convergence").is_empty())?;
    let rows = e.get(point, "convergence");
    if rows.is_empty() {
        return None;
    }
    let series = |name: &str| -> Vec<(f64, f64)> {
        rows.iter()
            .filter(|r| r.parameter == name)
            .map(|r| (r.x.unwrap_or(f64::NAN), r.value))
            .collect()
    };
    let (sobol, random, run) = (series("sobol"), series("random"), series("this run"));
    let slope = |m: &str| {
        e.one(point, "convergence_slope", m)
            .map_or("—".to_string(), |r| format!("{:.2}", r.value))
    };
    let mut curves = vec![
        Curve {
            label: format!("Sobol (scrambled), slope {}", slope("sobol")),
            points: sobol.clone(),
            band: Vec::new(),
            color: palette::GREEN,
            dashed: false,
            dots: true,
            line: true,
        },
        Curve {
            label: format!("random, slope {}", slope("random")),
            points: random.clone(),
            band: Vec::new(),
            color: palette::ORANGE,
            dashed: false,
            dots: true,
            line: true,
        },
    ];
    if !run.is_empty() {
        curves.push(Curve {
            label: format!("this run ({method})"),
            points: run,
            band: Vec::new(),
            color: palette::INK,
            dashed: false,
            dots: true,
            line: true,
        });
    }
    // Reference slopes through the first point of each method.
    for (pts, power, color, name) in [
        (&random, -0.5, palette::ORANGE, "n^(-1/2)"),
        (&sobol, -1.0, palette::GREEN, "n^(-1)"),
    ] {
        if let (Some(&(n0, e0)), Some(&(n1, _))) = (pts.first(), pts.last()) {
            curves.push(Curve {
                label: name.into(),
                points: vec![(n0, e0), (n1, e0 * (n1 / n0).powf(power))],
                band: Vec::new(),
                color,
                dashed: true,
                dots: false,
                line: true,
            });
        }
    }
    Some(FigureSpec {
        stem: format!("convergence{}", lc.stem_suffix),
        title: format!(
            "Error of the sampled probability against n{}",
            lc.title_suffix
        ),
        caption: "The error of the sampled probability of collapse against the exact value, \
                  against the number of samples n: the root-mean-square error over independent \
                  replicates for scrambled Sobol points and for random sampling, and the absolute \
                  error of this run's own estimate at each power of two. Dashed: the slopes n^(-1) \
                  and n^(-1/2) through the first point of each method. The legend gives the \
                  least-squares slope of each method. Random sampling falls as n^(-1/2); scrambled \
                  Sobol points reach n^(-1) for smooth integrands only: whether an arch stands is \
                  a step function of its parameters, for which the error of a scrambled net \
                  falls as n^(-1/2-1/(2d)), n^(-3/4) for d = 2 uncertain parameters."
            .into(),
        chart: Chart::Curves(CurvesChart {
            title: format!("Convergence{}", lc.title_suffix),
            panels: vec![CurvePanel {
                title: String::new(),
                x_desc: "samples n".into(),
                y_desc: "error of P(collapse)".into(),
                curves,
                log: (true, true),
                y_range: None,
            }],
        }),
    })
}
