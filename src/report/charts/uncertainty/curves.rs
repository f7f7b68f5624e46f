//! The curve figures of a sampling study: the probability against a grid axis, the
//! fragility curves, and the error of the sampled probability against n.

use super::{Estimates, axis_words, value_words};
use crate::plot::palette;
use crate::plot::uncertainty::{Curve, CurvePanel, CurvesChart};
use crate::report::charts::{Chart, FigureSpec, LoadCaseFigure};

/// Most grid points drawn as separate curves of one panel.
const MAX_CURVES: usize = 8;

/// A fragility figure's λ axis is logarithmic when its values span more than this ratio.
const LOG_SPREAD: f64 = 50.0;

/// A fragility figure's λ axis ends at this many times the largest finite median.
const CAP_MEDIANS: f64 = 20.0;

/// The colours of the curves of one panel, in order.
const COLORS: [plotters::style::RGBColor; 8] = [
    palette::BLUE,
    palette::RED,
    palette::GREEN,
    palette::PURPLE,
    palette::ORANGE,
    palette::SKY,
    palette::INK,
    palette::GREY,
];

/// The probability (with its band, and the exact value dashed) against the innermost grid
/// axis, one curve per value of the others.
pub(super) fn against_axis(
    e: &Estimates,
    lc: &LoadCaseFigure,
    quantity: &str,
) -> Option<FigureSpec> {
    let points = e.points();
    if points.len() < 2 {
        return None;
    }
    // The abscissa is the axis with the most values (the innermost of those tied); one line
    // per value of the others.
    let names: Vec<String> = e.grid(points[0]).into_iter().map(|g| g.0).collect();
    let count = |i: usize| {
        let mut v: Vec<u64> = points
            .iter()
            .filter_map(|&p| e.grid(p).get(i).map(|g| g.1.to_bits()))
            .collect();
        v.sort_unstable();
        v.dedup();
        v.len()
    };
    let x_index = (0..names.len()).max_by_key(|&i| (count(i), i))?;
    let axis = names[x_index].clone();
    let lines = lines_of(e, &points, x_index);
    let mut curves = Vec::new();
    for ((key, pts), color) in lines.iter().take(MAX_CURVES).zip(COLORS) {
        let x_of = |p: u64| e.grid(p).get(x_index).map_or(f64::NAN, |g| g.1);
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
                x_desc: axis_words(&axis),
                y_desc: "probability of collapse".into(),
                curves,
                log: (false, false),
                y_range: None,
            }],
        }),
    })
}

/// The points of each line of an against-axis figure: one line per value of the axes other
/// than the innermost, labelled by them.
fn lines_of(e: &Estimates, points: &[u64], x_index: usize) -> Vec<(String, Vec<u64>)> {
    let mut lines: Vec<(String, Vec<u64>)> = Vec::new();
    for &p in points {
        let g = e.grid(p);
        let others: Vec<String> = (g.iter().enumerate())
            .filter(|(i, _)| *i != x_index)
            .map(|(_, (a, v))| value_words(a, *v))
            .collect();
        let key = others.join(", ");
        match lines.iter_mut().find(|(k, _)| *k == key) {
            Some((_, v)) => v.push(p),
            None => lines.push((key, vec![p])),
        }
    }
    lines
}

pub(super) fn fragility(e: &Estimates, lc: &LoadCaseFigure) -> Option<FigureSpec> {
    let points = e.points();
    let mut curves = fragility_curves(e, &points);
    if curves.is_empty() {
        return None;
    }
    let (log_x, cap, hi) = fit_axis(&mut curves, e, &points);
    let (q, unbounded, capped) = caption_parts(e, &points, cap, hi);
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

/// One curve per grid point (at most MAX_CURVES): the empirical CDF with its band.
fn fragility_curves(e: &Estimates, points: &[u64]) -> Vec<Curve> {
    let mut curves: Vec<Curve> = Vec::new();
    for (&p, color) in points.iter().take(MAX_CURVES).zip(COLORS) {
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
    curves
}

/// A logarithmic λ axis where the values span decades, and the axis ended at CAP_MEDIANS
/// times the largest finite median (a few samples near an unbounded capacity would
/// stretch it over decades), each curve held level to the end: (log axis, cap, largest λ).
fn fit_axis(curves: &mut [Curve], e: &Estimates, points: &[u64]) -> (bool, f64, f64) {
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
    for c in curves.iter_mut() {
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
    (log_x, cap, hi)
}

/// The caption's quantiles, unbounded shares and axis note.
fn caption_parts(
    e: &Estimates,
    points: &[u64],
    cap: f64,
    hi: f64,
) -> (Vec<String>, String, String) {
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
    (q, unbounded, capped)
}

pub(super) fn convergence(e: &Estimates, lc: &LoadCaseFigure, method: &str) -> Option<FigureSpec> {
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
