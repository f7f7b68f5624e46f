//! Paper-ready output: the PDF, SVG and PNG of a figure carry the same text at the column
//! width, no text prints below 7 pt, the fonts of the PDF are embedded, and every table of
//! the report is also a CSV and a LaTeX table holding the report's values.

use crate::common::{archstudy, assert_usage_error, manifest, run_study, scratch};
use std::process::Command;

const STUDY: &str = "\
name: paper
title: Semicircular arch for print
arch: {voussoirs: continuum}
grid:
  k: {from: 1.05, to: 1.5, steps: 7}
  mu: {from: 0.2, to: 0.8, steps: 7}
find: state
scenes:
  - {k: 1.35, mu: 0.4}
figures: {width: single}
";

/// The value of attribute `name` in the tag starting at `tag`.
fn attr<'a>(tag: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let end = tag.find('>')?;
    let i = tag[..end].find(&key)? + key.len();
    let j = tag[i..].find('"')? + i;
    Some(&tag[i..j])
}

/// The text of every `<text>` element of an SVG, tags (tspans) removed, entities decoded.
fn svg_labels(svg: &str) -> Vec<String> {
    let mut out = Vec::new();
    for part in svg.split("<text").skip(1) {
        let body = &part[part.find('>').unwrap() + 1..part.find("</text>").unwrap()];
        let mut text = String::new();
        let mut in_tag = false;
        for c in body.chars() {
            match c {
                '<' => in_tag = true,
                '>' => in_tag = false,
                c if !in_tag => text.push(c),
                _ => {}
            }
        }
        let text = text
            .replace("&lt;", "<")
            .replace("&gt;", ">")
            .replace("&quot;", "\"")
            .replace("&apos;", "'")
            .replace("&amp;", "&");
        if !text.trim().is_empty() {
            out.push(text.trim().to_string());
        }
    }
    out
}

/// The printed width of an SVG in points and its width in user units.
fn svg_widths(svg: &str) -> (f64, f64) {
    let root = &svg[svg.find("<svg").unwrap()..];
    let w = attr(root, "width").unwrap();
    let inches: f64 = w
        .strip_suffix("in")
        .expect("width in inches")
        .parse()
        .unwrap();
    let vb: Vec<f64> = attr(root, "viewBox")
        .unwrap()
        .split_whitespace()
        .map(|x| x.parse().unwrap())
        .collect();
    (72.0 * inches, vb[2])
}

/// Every font size of an SVG (text and tspans), in user units, with whether it is a tspan.
fn font_sizes(svg: &str) -> Vec<(f64, bool)> {
    let mut out = Vec::new();
    for (tag, is_span) in [("<text", false), ("<tspan", true)] {
        for part in svg.split(tag).skip(1) {
            if let Some(s) = attr(part, "font-size") {
                out.push((s.parse::<f64>().unwrap(), is_span));
            }
        }
    }
    out
}

fn tool(name: &str) -> bool {
    Command::new(name).arg("-v").output().is_ok()
}

/// The MediaBox width of the first page of a PDF, read from the file itself.
fn pdf_page_width(pdf: &[u8]) -> f64 {
    let text = String::from_utf8_lossy(pdf);
    let i = text.find("/MediaBox [").unwrap() + "/MediaBox [".len();
    let nums: Vec<f64> = text[i..i + text[i..].find(']').unwrap()]
        .split_whitespace()
        .map(|x| x.parse().unwrap())
        .collect();
    nums[2] - nums[0]
}

#[test]
fn paper_figures_are_the_same_text_at_the_column_width() {
    let d = scratch("paper-figures");
    let run = run_study(&d, "paper.yaml", STUDY);
    let plots = run.join("plots");
    let mut stems = Vec::new();
    for e in std::fs::read_dir(&plots).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x == "svg") {
            stems.push(p.file_stem().unwrap().to_string_lossy().into_owned());
        }
    }
    stems.sort();
    assert!(stems.len() >= 3, "{stems:?}");
    assert!(
        stems.iter().any(|s| s.starts_with("mechanisms-")),
        "no mechanism figure: {stems:?}"
    );
    for stem in &stems {
        let svg = std::fs::read_to_string(plots.join(format!("{stem}.svg"))).unwrap();
        let pdf = std::fs::read(plots.join(format!("{stem}.pdf"))).unwrap();
        let png = std::fs::read(plots.join(format!("{stem}.png"))).unwrap();
        // The page, the SVG and the PNG are 3.5 in wide (one column).
        let (print_pt, user) = svg_widths(&svg);
        assert!((print_pt - 252.0).abs() < 0.01, "{stem}: {print_pt} pt");
        assert!((pdf_page_width(&pdf) - 252.0).abs() < 0.01, "{stem}.pdf");
        let reader = png::Decoder::new(std::io::Cursor::new(&png))
            .read_info()
            .unwrap();
        assert_eq!(reader.info().width, 1050, "{stem}.png is 3.5 in at 300 dpi");
        // A figure of four panels (the mechanisms at a bifurcation) is no taller than 1.3
        // times the column width (4.55 in): stacked in one column it was 6.9 in tall.
        let tall = f64::from(reader.info().height) / 1050.0;
        if stem.starts_with("mechanisms-") {
            assert!(
                tall <= 1.3 + 1e-3,
                "{stem}.png is {tall:.3} times as tall as wide"
            );
        }
        // Text is 8–9 pt on the baseline, scripts no smaller than 7 pt.
        let pt = print_pt / user;
        let sizes = font_sizes(&svg);
        assert!(!sizes.is_empty(), "{stem}: no text");
        for (s, span) in sizes {
            let printed = s * pt;
            assert!(printed >= 7.0 - 1e-9, "{stem}: text of {printed:.2} pt");
            if !span {
                assert!(
                    (8.0 - 1e-6..=9.0 + 1e-6).contains(&printed),
                    "{stem}: text of {printed:.2} pt"
                );
            }
        }
        // No title: the report's caption carries it.
        assert!(
            !svg.contains("Semicircular arch for print"),
            "{stem}.svg has a title"
        );
        // Every font of the PDF is embedded.
        let text = String::from_utf8_lossy(&pdf);
        let fonts = text.matches("/FontDescriptor").count();
        assert!(fonts > 0, "{stem}.pdf has no font");
        assert_eq!(
            text.matches("/FontFile2").count(),
            text.matches("/Type /FontDescriptor").count(),
            "{stem}.pdf: a font is not embedded"
        );
        // The PNG is the SVG rasterised.
        assert!(
            archstudy::plot::paper::svg_to_png(&svg).unwrap() == png,
            "{stem}.png is not its SVG"
        );
        // The PDF carries the SVG's labels, in its font.
        if tool("pdftotext") {
            let out = Command::new("pdftotext")
                .args(["-raw", "-enc", "UTF-8"])
                .arg(plots.join(format!("{stem}.pdf")))
                .arg("-")
                .output()
                .unwrap();
            let pdf_text: String = String::from_utf8_lossy(&out.stdout)
                .chars()
                .filter(|c| !c.is_whitespace())
                .collect();
            for label in svg_labels(&svg) {
                let l: String = label.chars().filter(|c| !c.is_whitespace()).collect();
                assert!(
                    pdf_text.contains(&l),
                    "{stem}.pdf lacks {label:?}: {pdf_text}"
                );
            }
        } else {
            eprintln!("pdftotext is not installed (poppler-utils): PDF text not compared");
        }
    }
    // Symbols are typeset, not typed.
    let map = std::fs::read_to_string(plots.join("regime-map.svg")).unwrap();
    assert!(
        !map.contains("K_c") && !map.contains("t/R_c"),
        "typed symbols"
    );
    assert!(map.contains("font-family=\"DejaVu Sans, sans-serif\""));
    assert!(
        !map.contains(">-0.0") && !map.contains(">-0<"),
        "negative zero"
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// The rows of the Markdown table that follows `heading` in a report.
fn md_table(md: &str, heading: &str) -> Vec<Vec<String>> {
    let at = md.find(heading).unwrap();
    md[at..]
        .lines()
        .skip_while(|l| !l.starts_with('|'))
        .take_while(|l| l.starts_with('|'))
        .filter(|l| !l.starts_with("|---") && !l.starts_with("|--"))
        .map(|l| {
            l.trim_matches('|')
                .split(" | ")
                .map(|c| c.trim().trim_matches('`').to_string())
                .collect()
        })
        .collect()
}

/// A CSV line split at commas outside quotes.
fn csv_fields(line: &str) -> Vec<String> {
    let mut out = vec![String::new()];
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '"' if quoted && chars.peek() == Some(&'"') => {
                out.last_mut().unwrap().push('"');
                chars.next();
            }
            '"' => quoted = !quoted,
            ',' if !quoted => out.push(String::new()),
            c => out.last_mut().unwrap().push(c),
        }
    }
    out
}

#[test]
fn the_csv_and_latex_of_a_table_hold_the_reports_values() {
    let d = scratch("paper-tables");
    let run = run_study(&d, "paper.yaml", STUDY);
    let md = std::fs::read_to_string(run.join("report.md")).unwrap();
    let html = std::fs::read_to_string(run.join("report.html")).unwrap();
    for link in ["tables/key-results.csv", "tables/key-results.tex"] {
        assert!(md.contains(&format!("({link})")), "report.md lacks {link}");
        // minijinja escapes `/` in HTML as `&#x2f;`, which a browser reads as `/`.
        let href = format!("href=\"{}\"", link.replace('/', "&#x2f;"));
        assert!(html.contains(&href), "report.html lacks {link}");
    }
    let report = md_table(&md, "## Key results");
    let csv = std::fs::read_to_string(run.join("tables/key-results.csv")).unwrap();
    let csv: Vec<Vec<String>> = csv.lines().map(csv_fields).collect();
    assert_eq!(csv.len(), report.len(), "{csv:?}\n{report:?}");
    assert!(csv.len() >= 4, "{csv:?}");
    for (c, r) in csv.iter().zip(&report) {
        let r: Vec<String> = r.iter().map(|x| x.replace('\u{2212}', "-")).collect();
        assert_eq!(c, &r);
    }
    // The LaTeX table: the same rows, numbers to six significant digits.
    let tex = std::fs::read_to_string(run.join("tables/key-results.tex")).unwrap();
    assert!(tex.contains("\\toprule") && tex.contains("\\bottomrule"));
    let body: Vec<&str> = tex
        .lines()
        .skip_while(|l| *l != "\\midrule")
        .skip(1)
        .take_while(|l| *l != "\\bottomrule")
        .collect();
    assert_eq!(body.len(), report.len() - 1);
    let mut numbers = 0;
    for (line, r) in body.iter().zip(&report[1..]) {
        let cells: Vec<&str> = line.trim_end_matches(" \\\\").split(" & ").collect();
        // Numbers only: angles with their faces are text in both.
        let Ok(value) = r[1].replace('\u{2212}', "-").parse::<f64>() else {
            continue;
        };
        numbers += 1;
        let tex_value: f64 = cells[1].trim_matches('$').parse().unwrap();
        assert!(
            (tex_value - value).abs() <= 5e-6 * value.abs(),
            "{}: {tex_value} against {value}",
            r[0]
        );
    }
    assert!(numbers >= 4, "{numbers} numeric rows");
    // Symbols in the quantities are typeset: K_c as $K_{c}$.
    assert!(tex.contains("$K_{c}$"), "{tex}");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn the_figure_width_is_a_checked_manifest_option_and_a_run_option() {
    let d = scratch("paper-width");
    let bad = manifest(
        &d,
        "bad.yaml",
        "name: w\ngrid:\n  k: {values: [1.2]}\n  mu: {values: [0.4]}\nfigures: {width: triple}\n",
    );
    let o = archstudy(&["check", bad.to_str().unwrap()]);
    assert_usage_error(
        &o,
        &["bad.yaml", "figures.width", "triple", "single or double"],
    );
    let unknown = manifest(
        &d,
        "unknown.yaml",
        "name: w\ngrid:\n  k: {values: [1.2]}\n  mu: {values: [0.4]}\nfigures: {height: 3}\n",
    );
    let o = archstudy(&["check", unknown.to_str().unwrap()]);
    assert_usage_error(&o, &["unknown.yaml", "height"]);
    let good = manifest(
        &d,
        "good.yaml",
        "name: w\ngrid:\n  k: {values: [1.2, 1.3]}\n  mu: {values: [0.4, 0.5]}\n",
    );
    let o = archstudy(&[
        "run",
        good.to_str().unwrap(),
        "--figure-width",
        "wide",
        "--quiet",
    ]);
    assert_usage_error(&o, &["--figure-width", "wide"]);
    let out = d.join("out");
    let o = archstudy(&[
        "run",
        good.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--figure-width",
        "single",
        "--quiet",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let pdf = std::fs::read(out.join("w/plots/regime-map.pdf")).unwrap();
    assert!((pdf_page_width(&pdf) - 252.0).abs() < 0.01);
    // Without the option: the default, two columns (7.2 in).
    let o = archstudy(&[
        "run",
        good.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(o.status.success());
    let pdf = std::fs::read(out.join("w/plots/regime-map.pdf")).unwrap();
    assert!((pdf_page_width(&pdf) - 518.4).abs() < 0.01);
    let _ = std::fs::remove_dir_all(&d);
}
