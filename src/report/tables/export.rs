//! Every table of the reports as files a paper takes: CSV (the report's values as shown)
//! and a LaTeX booktabs table (numbers to six significant digits, symbols typeset, LaTeX
//! specials escaped), written to `tables/` of the run directory.

use super::super::view::ReportView;
use crate::plot::paper::{Shift, pieces};
use serde::Serialize;

/// Significant digits of the numbers of a LaTeX table.
pub const TEX_DIGITS: usize = 6;

/// One table of a report, as text cells.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportTable {
    /// File stem in tables/.
    pub stem: String,
    /// Title (the LaTeX caption).
    pub title: String,
    /// Column headers.
    pub headers: Vec<String>,
    /// Rows of cells, as the report shows them.
    pub rows: Vec<Vec<String>>,
}

/// A table's files, as linked from the reports.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct TableFiles {
    /// Title.
    pub title: String,
    /// Relative path of the CSV.
    pub csv: String,
    /// Relative path of the LaTeX table.
    pub tex: String,
}

impl ExportTable {
    fn new(stem: impl Into<String>, title: impl Into<String>, headers: &[&str]) -> Self {
        ExportTable {
            stem: stem.into(),
            title: title.into(),
            headers: headers.iter().map(|h| (*h).to_string()).collect(),
            rows: Vec::new(),
        }
    }

    fn row(mut self, cells: &[&String]) -> Self {
        self.rows.push(cells.iter().map(|c| (*c).clone()).collect());
        self
    }

    /// Its files in a run directory.
    pub fn files(&self) -> TableFiles {
        TableFiles {
            title: self.title.clone(),
            csv: format!("tables/{}.csv", self.stem),
            tex: format!("tables/{}.tex", self.stem),
        }
    }
}

/// Every non-empty table of a report, in the order the report shows them.
pub fn tables(v: &ReportView) -> Vec<ExportTable> {
    let mut out = Vec::new();
    let items = |stem: &str, title: &str, head: [&str; 2], items: &[super::Item]| {
        items
            .iter()
            .fold(ExportTable::new(stem, title, &head), |t, i| {
                t.row(&[&i.label, &i.value])
            })
    };
    out.push(items("study", "The arch and the model", ["", ""], &v.model));
    out.push(v.grid.iter().fold(
        ExportTable::new("grid", "Grid", &["parameter", "values", "first", "last"]),
        |t, a| t.row(&[&a.name, &a.count, &a.first, &a.last]),
    ));
    out.push(items("cases", "Cases", ["cases", "count"], &v.cases));
    out.push(v.key_results.iter().fold(
        ExportTable::new(
            "key-results",
            "Key results",
            &["quantity", "value", "paper", "difference", "stored in"],
        ),
        |t, r| t.row(&[&r.quantity, &r.value, &r.paper, &r.difference, &r.source]),
    ));
    for (i, t) in v.value_tables.iter().enumerate() {
        let mut e = ExportTable::new(format!("values-{}", i + 1), &t.title, &[]);
        e.headers.clone_from(&t.headers);
        e.rows.clone_from(&t.rows);
        out.push(e);
    }
    boundaries(v, &mut out);
    mechanisms(v, &mut out);
    speed(v, &mut out);
    out.push(items(
        "reproducibility",
        "Reproducibility",
        ["", ""],
        &v.reproducibility,
    ));
    out.push(items(
        "stages",
        "Stage timings",
        ["stage", "wall time"],
        &v.stages,
    ));
    out.push(items(
        "files",
        "Files of the run directory",
        ["file", "contents"],
        &v.files,
    ));
    out.retain(|t| !t.rows.is_empty());
    out
}

fn boundaries(v: &ReportView, out: &mut Vec<ExportTable>) {
    out.push(v.boundary_groups.iter().fold(
        ExportTable::new(
            "boundaries",
            "Boundary points by the regimes on either side",
            &[
                "regimes (low → high)",
                "along",
                "collapse curve",
                "mechanism",
                "points",
                "μ",
                "K",
            ],
        ),
        |t, g| {
            t.row(&[
                &g.regimes,
                &g.axis,
                &g.collapse,
                &g.mechanism,
                &g.points,
                &g.mu_range,
                &g.k_range,
            ])
        },
    ));
    out.push(v.collapse_points.iter().fold(
        ExportTable::new(
            "collapse-curve",
            "Collapse curve",
            &[
                "μ",
                "K",
                "t/R_c",
                "mechanism",
                "H/W_half",
                "hinges",
                "sliding joints",
            ],
        ),
        |t, p| {
            t.row(&[
                &p.mu,
                &p.k,
                &p.t_over_r,
                &p.mechanism,
                &p.thrust,
                &p.hinges,
                &p.sliding,
            ])
        },
    ));
}

fn mechanisms(v: &ReportView, out: &mut Vec<ExportTable>) {
    for (i, s) in v.mechanisms.iter().enumerate() {
        out.push(s.rows.iter().fold(
            ExportTable::new(
                format!("mechanisms-{}", i + 1),
                &s.title,
                &[
                    "μ",
                    "K",
                    "mechanism",
                    "flow rule",
                    "dL^(a)",
                    "dL^(r,n)",
                    "dL^(r,t)",
                    "work residual",
                    "dilatancy at the sliding joints",
                ],
            ),
            |t, r| {
                t.row(&[
                    &r.mu,
                    &r.k,
                    &r.mechanism,
                    &r.flow_rule,
                    &r.work_loads,
                    &r.work_normal,
                    &r.work_friction,
                    &r.work_residual,
                    &r.dilatancy,
                ])
            },
        ));
    }
}

fn speed(v: &ReportView, out: &mut Vec<ExportTable>) {
    out.push(v.timing.iter().fold(
        ExportTable::new(
            "solve-times",
            "Solve time per case",
            &[
                "cases",
                "count",
                "median",
                "90th percentile",
                "largest",
                "sum",
            ],
        ),
        |t, r| t.row(&[&r.group, &r.cases, &r.median, &r.p90, &r.max, &r.total]),
    ));
    for (i, c) in v.convergence.iter().enumerate() {
        out.push(c.rows.iter().fold(
            ExportTable::new(
                format!("convergence-{}", i + 1),
                format!("Convergence of {}", c.quantity),
                &["N", "value", "abs. error", "solve time"],
            ),
            |t, r| t.row(&[&r.voussoirs, &r.value, &r.abs_error, &r.time]),
        ));
    }
    out.push(v.errors.iter().fold(
        ExportTable::new(
            "accuracy",
            "Error of the discrete arch against the continuum",
            &[
                "quantity",
                "N",
                "cases",
                "largest abs. error",
                "largest rel. error",
                "median time",
                "continuum median time",
            ],
        ),
        |t, e| {
            t.row(&[
                &e.quantity,
                &e.voussoirs,
                &e.cases,
                &e.max_abs_error,
                &e.max_rel_error,
                &e.median_time,
                &e.continuum_time,
            ])
        },
    ));
}

/// A cell as a number, when it is one (a minus sign or hyphen, digits, a decimal point, an
/// exponent).
pub fn number(cell: &str) -> Option<f64> {
    let t = cell.trim().replace('\u{2212}', "-");
    let plain = !t.is_empty()
        && t.chars()
            .all(|c| c.is_ascii_digit() || matches!(c, '-' | '+' | '.' | 'e' | 'E'))
        && t.chars().any(|c| c.is_ascii_digit());
    if !plain {
        return None;
    }
    t.parse::<f64>().ok().filter(|x| x.is_finite())
}

/// The first characters by which a spreadsheet takes a cell for a formula: a CSV cell that
/// starts with one of them (and is not a plain number) is written with a leading `'`, as
/// OWASP's advice on CSV injection has it, so that it stays text.
pub const FORMULA_PREFIXES: [char; 6] = ['=', '+', '-', '@', '\t', '\r'];

/// The CSV of a table (RFC 4180): the cells as the report shows them, minus signs as ASCII
/// hyphens in numbers so that every reader parses them; a text cell that a spreadsheet would
/// take for a formula neutralised ([`FORMULA_PREFIXES`]); control characters other than the
/// line breaks inside a quoted cell dropped.
pub fn csv(t: &ExportTable) -> String {
    let field = |s: &str| {
        let s = if number(s).is_some() {
            s.trim().replace('\u{2212}', "-")
        } else {
            let clean = plain(s);
            if clean.starts_with(FORMULA_PREFIXES) {
                format!("'{clean}")
            } else {
                clean
            }
        };
        if s.contains([',', '"', '\n', '\r']) {
            format!("\"{}\"", s.replace('"', "\"\""))
        } else {
            s
        }
    };
    let line = |cells: &[String]| cells.iter().map(|c| field(c)).collect::<Vec<_>>().join(",");
    let mut out = line(&t.headers);
    out.push_str("\r\n");
    for r in &t.rows {
        out.push_str(&line(r));
        out.push_str("\r\n");
    }
    out
}

/// Text without control characters (but tab and line breaks) and without the invisible
/// characters that reorder or hide text (bidirectional controls, zero-width characters).
pub fn plain(s: &str) -> String {
    s.chars()
        .filter(|&c| (!c.is_control() || matches!(c, '\t' | '\n' | '\r')) && !is_invisible(c))
        .collect()
}

/// Bidirectional controls and zero-width characters: shown by no reader as what they do.
pub fn is_invisible(c: char) -> bool {
    matches!(c,
        '\u{200B}'..='\u{200F}' | '\u{202A}'..='\u{202E}' | '\u{2060}'..='\u{2069}'
        | '\u{FEFF}' | '\u{061C}')
}

/// A number to `digits` significant digits, as LaTeX math: `1.23457`, `$-0.5$`,
/// `$1.5 \times 10^{-9}$`.
pub fn tex_number(x: f64, digits: usize) -> String {
    if x == 0.0 {
        return "0".into();
    }
    let e = x.abs().log10().floor() as i32;
    let body = if (digits as i32..9).contains(&e) {
        let q = 10f64.powi(e + 1 - digits as i32);
        format!("{:.0}", (x / q).round() * q)
    } else if (-4..9).contains(&e) {
        let decimals = usize::try_from((digits as i32 - 1 - e).max(0)).unwrap_or(0);
        let s = format!("{x:.decimals$}");
        let s = if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        };
        if s == "-0" { "0".to_string() } else { s }
    } else {
        let m = x / 10f64.powi(e);
        let m = format!("{m:.*}", digits.saturating_sub(1));
        let m = m.trim_end_matches('0').trim_end_matches('.');
        format!("{m} \\times 10^{{{e}}}")
    };
    if body.starts_with('-') || body.contains("\\times") {
        format!("${body}$")
    } else {
        body
    }
}

/// Text as LaTeX: specials escaped, Greek letters and K_c, H^r, t/R_c as math.
pub fn tex_text(s: &str) -> String {
    let p = pieces(s);
    let mut out = String::new();
    for (i, (kind, text)) in p.iter().enumerate() {
        let scripted = p.get(i + 1).is_some_and(|(k, _)| *k != Shift::Base);
        match kind {
            Shift::Base if scripted => {
                // The last character is the base of the following script.
                let mut chars: Vec<char> = text.chars().collect();
                let base = chars.pop().unwrap_or(' ');
                out.push_str(&escape(&chars.into_iter().collect::<String>()));
                out.push('$');
                out.push_str(&math_char(base));
            }
            Shift::Base => out.push_str(&escape(text)),
            Shift::Sub | Shift::Sup => {
                let mark = if *kind == Shift::Sub { '_' } else { '^' };
                let body: String = text.chars().map(math_char).collect();
                let body = if text.chars().count() > 1 && text.chars().all(char::is_alphabetic) {
                    format!("\\mathrm{{{body}}}")
                } else {
                    body
                };
                out.push_str(&format!("{mark}{{{body}}}$"));
            }
        }
    }
    out
}

/// A character inside math mode: letters, digits and plain punctuation as they are, Greek
/// letters as commands, every other character set as escaped text in an `\mbox` (a LaTeX
/// special, in a sub- or superscript too, is never active).
fn math_char(c: char) -> String {
    greek(c).map_or_else(
        || match c {
            '\u{2212}' => "-".into(),
            c if c.is_ascii_alphanumeric() || "+-.,:;'()/=*<>! ".contains(c) => c.to_string(),
            c => format!("\\mbox{{{}}}", escape(&c.to_string())),
        },
        |g| format!("{g} "),
    )
}

/// Unicode superscript and subscript characters, which pdflatex does not know, as LaTeX
/// math: `Hʳ` is `H$^{r}$`.
fn script_char(c: char) -> Option<String> {
    const SUP: [(char, char); 18] = [
        ('ʳ', 'r'),
        ('ˢ', 's'),
        ('ⁿ', 'n'),
        ('ᵗ', 't'),
        ('ᵃ', 'a'),
        ('ᶜ', 'c'),
        ('ⁱ', 'i'),
        ('⁰', '0'),
        ('¹', '1'),
        ('²', '2'),
        ('³', '3'),
        ('⁴', '4'),
        ('⁵', '5'),
        ('⁶', '6'),
        ('⁷', '7'),
        ('⁸', '8'),
        ('⁹', '9'),
        ('⁻', '-'),
    ];
    const SUB: [(char, char); 12] = [
        ('₀', '0'),
        ('₁', '1'),
        ('₂', '2'),
        ('₃', '3'),
        ('₄', '4'),
        ('₅', '5'),
        ('₆', '6'),
        ('₇', '7'),
        ('₈', '8'),
        ('₉', '9'),
        ('ᵣ', 'r'),
        ('ₛ', 's'),
    ];
    if let Some((_, b)) = SUP.iter().find(|(u, _)| *u == c) {
        return Some(format!("$^{{{b}}}$"));
    }
    SUB.iter()
        .find(|(u, _)| *u == c)
        .map(|(_, b)| format!("$_{{{b}}}$"))
}

fn greek(c: char) -> Option<&'static str> {
    Some(match c {
        'α' => "\\alpha",
        'β' => "\\beta",
        'γ' => "\\gamma",
        'δ' => "\\delta",
        'ε' => "\\varepsilon",
        'θ' => "\\theta",
        'λ' => "\\lambda",
        'μ' => "\\mu",
        'π' => "\\pi",
        'σ' => "\\sigma",
        'τ' => "\\tau",
        'φ' => "\\varphi",
        'Φ' => "\\Phi",
        'Δ' => "\\Delta",
        _ => return None,
    })
}

/// Text-mode LaTeX of plain text: specials escaped, Greek letters and math symbols in math.
fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 8);
    for c in s.chars() {
        if let Some(g) = greek(c) {
            out.push_str(&format!("${g}$"));
            continue;
        }
        match c {
            c if c.is_control() || is_invisible(c) => {}
            '\\' => out.push_str("\\textbackslash{}"),
            '<' => out.push_str("\\textless{}"),
            '>' => out.push_str("\\textgreater{}"),
            '|' => out.push_str("\\textbar{}"),
            '&' | '%' | '$' | '#' | '_' | '{' | '}' => {
                out.push('\\');
                out.push(c);
            }
            '~' => out.push_str("\\textasciitilde{}"),
            '^' => out.push_str("\\textasciicircum{}"),
            '\u{2212}' => out.push_str("$-$"),
            '→' => out.push_str("$\\to$"),
            '≤' => out.push_str("$\\leq$"),
            '≥' => out.push_str("$\\geq$"),
            '×' => out.push_str("$\\times$"),
            '·' => out.push_str("$\\cdot$"),
            '±' => out.push_str("$\\pm$"),
            '≈' => out.push_str("$\\approx$"),
            '∞' => out.push_str("$\\infty$"),
            '°' => out.push_str("\\textdegree{}"),
            c => match script_char(c) {
                Some(m) => out.push_str(&m),
                None => out.push(c),
            },
        }
    }
    out
}

/// A cell as LaTeX: a number to [`TEX_DIGITS`] significant digits, `inf` as ∞, text
/// escaped.
fn tex_cell(cell: &str) -> String {
    match number(cell) {
        Some(x) => tex_number(x, TEX_DIGITS),
        None if cell.trim() == "inf" => "$\\infty$".into(),
        None => tex_text(cell),
    }
}

/// The LaTeX of a table: a `table` float with a booktabs `tabular` (needs
/// `\usepackage{booktabs}`), numeric columns right-aligned, the title as caption and
/// `tab:STEM` as label.
pub fn latex(t: &ExportTable) -> String {
    let cols = t
        .headers
        .len()
        .max(t.rows.iter().map(Vec::len).max().unwrap_or(0));
    let numeric = |j: usize| {
        t.rows.iter().all(|r| {
            r.get(j)
                .is_none_or(|c| number(c).is_some() || matches!(c.trim(), "" | "—" | "inf"))
        })
    };
    let spec: String = (0..cols)
        .map(|j| if numeric(j) { 'r' } else { 'l' })
        .collect();
    let mut out = String::new();
    out.push_str("% Written by archstudy; needs \\usepackage{booktabs}.\n");
    out.push_str("\\begin{table}\n\\centering\n");
    out.push_str(&format!("\\caption{{{}}}\n", tex_text(&t.title)));
    out.push_str(&format!("\\label{{tab:{}}}\n", t.stem));
    out.push_str(&format!("\\begin{{tabular}}{{{spec}}}\n\\toprule\n"));
    let line = |cells: Vec<String>| format!("{} \\\\\n", cells.join(" & "));
    out.push_str(&line(t.headers.iter().map(|h| tex_text(h)).collect()));
    out.push_str("\\midrule\n");
    for r in &t.rows {
        out.push_str(&line(r.iter().map(|c| tex_cell(c)).collect()));
    }
    out.push_str("\\bottomrule\n\\end{tabular}\n\\end{table}\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table() -> ExportTable {
        let s = |x: &str| x.to_string();
        ExportTable {
            stem: "t".into(),
            title: s("K_c & μ_min at 50%"),
            headers: vec![s("μ"), s("K_c"), s("H^r"), s("note")],
            rows: vec![vec![
                s("0.395265252140"),
                s("\u{2212}0.5"),
                s("1.5e-9"),
                s("a, \"b\" #1"),
            ]],
        }
    }

    #[test]
    fn csv_quotes_and_keeps_the_values() {
        let c = csv(&table());
        assert_eq!(
            c,
            "μ,K_c,H^r,note\r\n0.395265252140,-0.5,1.5e-9,\"a, \"\"b\"\" #1\"\r\n"
        );
    }

    #[test]
    fn latex_escapes_typesets_and_rounds() {
        let l = latex(&table());
        assert!(
            l.contains("\\caption{$K_{c}$ \\& $\\mu _{\\mathrm{min}}$ at 50\\%}"),
            "{l}"
        );
        assert!(l.contains("$\\mu$ & $K_{c}$ & $H^{r}$ & note \\\\"), "{l}");
        assert!(
            l.contains("0.395265 & $-0.5$ & $1.5 \\times 10^{-9}$ & a, \"b\" \\#1 \\\\"),
            "{l}"
        );
        assert!(l.contains("\\begin{tabular}{rrrl}"), "{l}");
        assert_eq!(tex_number(1.113581813339, 6), "1.11358");
        assert_eq!(tex_number(-0.0, 6), "0");
        assert_eq!(tex_number(12345678.0, 6), "12345700");
        assert_eq!(tex_text("t/R_c"), "t/$R_{c}$");
    }

    /// A path or title with `^(\input /etc/passwd )` (a superscript of LaTeX specials) and
    /// every special character, in text and in sub- and superscripts, is inert LaTeX.
    #[test]
    fn latex_specials_are_inert_in_every_mode() {
        let t = tex_text("/tmp/x^(\\input /etc/passwd )_{$#&%~}");
        assert!(!t.contains("\\input"), "{t}");
        assert!(t.contains("textbackslash{}"), "{t}");
        for bad in ["^{(\\i", "{$", "#&"] {
            assert!(!t.contains(bad), "{bad}: {t}");
        }
        let raw = "a\\b{c}$d#e&f%g_h~i^j<k>l|m";
        let t = tex_text(&format!("K_{raw} {raw}"));
        // No unescaped special: every `\` starts a command this module writes.
        for (i, c) in t.char_indices() {
            if matches!(c, '#' | '&' | '%' | '~') {
                assert!(t[..i].ends_with('\\'), "{c} at {i}: {t}");
            }
        }
        assert!(!t.contains("\\b"), "{t}");
        // Hʳ, Hˢ (characters pdflatex rejects) as math; control and bidi characters dropped.
        assert_eq!(tex_text("Hʳ, Hˢ"), "H$^{r}$, H$^{s}$");
        assert_eq!(tex_text("a\u{202E}b\u{7}c\u{1b}d"), "abcd");
    }

    /// A text cell that a spreadsheet takes for a formula gets a leading `'`; plain numbers,
    /// negative ones included, stay numbers.
    #[test]
    fn csv_formulas_are_neutralised_and_numbers_kept() {
        let s = |x: &str| x.to_string();
        let t = ExportTable {
            stem: "t".into(),
            title: s("t"),
            headers: vec![s("a")],
            rows: [
                "=HYPERLINK(\"http://x\",\"y\")",
                "+1+2",
                "-x",
                "@SUM(A1)",
                "\tcmd",
                "\rcmd",
                "-0.5",
                "\u{2212}2",
                "+3",
                "1e-9",
                "a\u{202E}b",
            ]
            .iter()
            .map(|c| vec![s(c)])
            .collect(),
        };
        let lines: Vec<String> = csv(&t).split("\r\n").map(str::to_string).collect();
        assert_eq!(lines[1], "\"'=HYPERLINK(\"\"http://x\"\",\"\"y\"\")\"");
        assert_eq!(lines[2], "'+1+2");
        assert_eq!(lines[3], "'-x");
        assert_eq!(lines[4], "'@SUM(A1)");
        assert_eq!(lines[5], "'\tcmd");
        assert!(lines[6].starts_with("\"'\rcmd"), "{lines:?}");
        assert_eq!(lines[7], "-0.5");
        assert_eq!(lines[8], "-2");
        assert_eq!(lines[9], "+3");
        assert_eq!(lines[10], "1e-9");
        assert_eq!(lines[11], "ab");
    }
}
