//! Draws the ten one-degree-of-freedom mechanism families of the paper (Figs. 3–5) for a
//! semicircular arch, and the collapse mechanisms of the reference states (Figs. 6, 7), as PNG.
//!
//! `cargo run --example mechanism_families -- [OUT_DIR] [K]` (default `target/mechanisms`,
//! K = 1.25).

use anyhow::{Context, Result};
use archstudy::analysis::circular::CircularArch;
use archstudy::analysis::kinematics::{self, collapse_mechanism, drawing};
use archstudy::analysis::symmetric::{friction, sliding_threshold, thickness};
use archstudy::model::{Arch, Discretisation, Friction, WeightModel};
use archstudy::plot::mechanisms::{MechanismFigure, render_mechanism};
use std::path::PathBuf;

fn main() -> Result<()> {
    let mut args = std::env::args().skip(1);
    let out = PathBuf::from(args.next().unwrap_or_else(|| "target/mechanisms".into()));
    let k: f64 = match args.next() {
        Some(s) => s
            .parse()
            .with_context(|| format!("K = {s} is not a number"))?,
        None => 1.25,
    };
    std::fs::create_dir_all(&out).with_context(|| format!("creating {}", out.display()))?;
    let arch = Arch::semicircular(k)?;
    let geom = CircularArch::new(arch);
    for f in kinematics::families(&geom)? {
        let Some(field) = f.modes.fields.first() else {
            eprintln!("{}: no mechanism ({:?})", f.template.id, f.modes.status);
            continue;
        };
        let fig = MechanismFigure {
            title: format!(
                "Fig. {}: {} ({})",
                f.template.figure, f.template.id, f.template.kind
            ),
            subtitle: format!(
                "{}; K = {k}, dof {}, {}",
                f.template.description,
                f.modes.dof,
                f.modes.status.as_str()
            ),
            drawing: drawing(&geom, field, 0.08),
            window: None,
        };
        let path = out.join(format!("{}.png", f.template.id));
        render_mechanism(&path, (800, 520), &fig)?;
        println!("{}", path.display());
    }
    let base = Arch::semicircular(1.5)?;
    let n16 = Arch::new(
        1.5,
        90.0,
        WeightModel::Annular,
        Discretisation::Voussoirs(16),
    )?;
    let states = [
        (
            "collapse-rotational-n16",
            thickness(&n16, Friction::INFINITE),
        ),
        ("collapse-rotational", thickness(&base, Friction::INFINITE)),
        (
            "collapse-mixed-mu-0.35",
            thickness(&base, Friction::new(0.35).unwrap_or(Friction::INFINITE)),
        ),
        (
            "bifurcation-rotational-mixed",
            friction(&Arch::semicircular(1.113581813339)?),
        ),
        (
            "bifurcation-mixed-sliding",
            thickness(
                &base,
                Friction::new(0.309215444330).unwrap_or(Friction::INFINITE),
            ),
        ),
        (
            "collapse-sliding-mu-min",
            sliding_threshold(&Arch::semicircular(1.3)?),
        ),
    ];
    for (name, c) in states {
        let Some(s) = c.found() else { continue };
        let from = if name.ends_with("n16") { n16 } else { base };
        let at = if s.k.is_finite() {
            from.with_k(s.k)
        } else {
            Arch::semicircular(1.3)?
        };
        let geom = CircularArch::new(at);
        let m = collapse_mechanism(&at, s);
        let fields = m.field.iter().chain(&m.alternatives);
        for (i, field) in fields.enumerate() {
            let kind = field.kind().map_or("none", |k| k.as_str());
            let fig = MechanismFigure {
                title: format!("{name}: {kind} mechanism"),
                subtitle: format!(
                    "K = {:.6}, μ = {:.6}, dof {}, work residual {:.1e}",
                    at.k,
                    s.mu,
                    m.mechanism_dof,
                    m.work.map_or(f64::NAN, |w| w.work_residual)
                ),
                drawing: drawing(&geom, field, 0.08),
                window: None,
            };
            let path = out.join(format!("{name}-{i}-{kind}.png"));
            render_mechanism(&path, (800, 520), &fig)?;
            println!("{}", path.display());
        }
    }
    Ok(())
}
