//! A survey of the non-associative gap over random scenes of every form, joint kind, load and
//! critical find: the share of finds with a gap by form and load, the widest gaps, and the
//! time the search for the first complete solution adds to each find. Its output is recorded
//! in docs/gap-survey.md.
//!
//! `cargo run --release --example gap_survey -- [SCENES] [SEED] [CSV]` (default 1000 scenes,
//! seed 1); with CSV, each find's scene, status, static limit and collapse value are written
//! there too, one row per find, so that two builds can be compared scene by scene.

use archstudy::analysis::forms::ArchModel;
use archstudy::analysis::gap::{self, GapStatus, Settings};
use archstudy::analysis::windows::WindowSettings;
use archstudy::model::{
    Arch, ArchForm, Discretisation, Friction, JointOrientation, Load, Shape, WeightModel,
};
use archstudy::scene::{self, Find, Scene, Solution};
use std::collections::BTreeMap;
use std::io::Write;
use std::time::Instant;

/// A small pseudo-random generator: the same scenes on every machine.
struct Draw(u64);

impl Draw {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
    fn pick<T: Copy>(&mut self, items: &[T]) -> T {
        items[((self.next() * items.len() as f64) as usize).min(items.len() - 1)]
    }
}

fn draw_scene(d: &mut Draw) -> Option<Scene> {
    let find = d.pick(&[Find::LoadFactor, Find::Friction, Find::Thickness]);
    let pointed = d.next() < 0.3;
    let vertical = d.next() < 0.3;
    let joints = if d.next() < 0.35 {
        Discretisation::Continuum
    } else {
        Discretisation::Voussoirs(3 + (d.next() * 14.0) as u32)
    };
    let half = d.range(30.0, if pointed { 80.0 } else { 90.0 });
    let load = match (find, d.pick(&[0, 1, 2])) {
        (Find::LoadFactor, 0) | (_, 1) => Load::Horizontal,
        (_, 2) | (Find::LoadFactor, _) => Load::point(d.range(-0.9 * half, 0.9 * half)),
        _ => Load::SelfWeight,
    };
    let lambda = match load {
        Load::SelfWeight => 0.0,
        _ if find == Find::LoadFactor => 0.0,
        Load::Horizontal => d.range(0.0, 0.15),
        _ => d.range(0.0, 0.3),
    };
    let form = ArchForm {
        shape: if pointed {
            Shape::Pointed {
                eccentricity: d.range(0.1, 0.5),
            }
        } else {
            Shape::Circular
        },
        joints: if vertical {
            JointOrientation::Vertical
        } else {
            JointOrientation::Radial
        },
        keystone: false,
    };
    Some(Scene {
        arch: Arch::new(d.range(1.1, 1.8), half, WeightModel::Annular, joints).ok()?,
        friction: Friction::new(d.range(0.3, 1.5))?,
        find,
        form,
        load,
        lambda,
    })
}

/// Time of the search for the first complete solution alone, µs.
fn gap_time(scene: &Scene, s: &Solution) -> Option<f64> {
    let settings = Settings::DEFAULT;
    let model = |k: f64| ArchModel::new(scene.arch.with_k(k), scene.form, scene.load).ok();
    let start = Instant::now();
    match scene.find {
        Find::LoadFactor => {
            gap::first_complete_load_factor(
                &model(scene.arch.k)?,
                scene.friction.angle(),
                &settings,
            );
        }
        Find::Friction => {
            gap::first_complete_friction(
                &model(scene.arch.k)?,
                scene.lambda,
                s.mu_crit?,
                &settings,
            );
        }
        Find::Thickness => {
            let k_c = s.k_crit?;
            let cap = scene
                .form
                .max_k_with_load(scene.arch.half_angle, scene.load);
            let top = s
                .k_windows_scanned_to
                .unwrap_or_else(|| WindowSettings::DEFAULT.upper_end(Some(k_c), cap));
            gap::first_complete_thickness(
                &model,
                scene.friction.angle(),
                scene.lambda,
                k_c,
                top,
                &settings,
            );
        }
        _ => return None,
    }
    Some(start.elapsed().as_secs_f64() * 1e6)
}

/// The static limit of a find: λ_max (∞ when unbounded), K_c or μ_c.
fn static_limit(s: &Solution) -> f64 {
    s.load_factor
        .or(s.k_crit)
        .or(s.mu_crit)
        .unwrap_or(f64::INFINITY)
}

fn class(scene: &Scene) -> String {
    let shape = match scene.form.shape {
        Shape::Circular => "circular",
        Shape::Pointed { .. } => "pointed",
    };
    let joints = match scene.form.joints {
        JointOrientation::Radial => "radial",
        JointOrientation::Vertical => "vertical",
    };
    let n = match scene.arch.joints {
        Discretisation::Continuum => "continuum",
        Discretisation::Voussoirs(_) => "voussoirs",
    };
    format!("{shape}, {joints} joints, {n}, {}", scene.load.as_str())
}

#[derive(Default)]
struct Tally {
    finds: usize,
    gaps: usize,
    none: usize,
    static_us: Vec<f64>,
    gap_us: Vec<f64>,
    /// Each find's added time over its own static time.
    ratio: Vec<f64>,
}

fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// One table of tallies, a row per group.
fn print_tallies<'a>(head: &str, rows: impl Iterator<Item = (String, &'a mut Tally)>) {
    println!(
        "| {head} | finds | with a gap | no complete solution | median µs today | median µs added | median added/today |"
    );
    println!("|---|---|---|---|---|---|---|");
    for (name, t) in rows {
        println!(
            "| {name} | {} | {} ({:.0} %) | {} | {:.0} | {:.0} | {:.1} |",
            t.finds,
            t.gaps,
            100.0 * t.gaps as f64 / t.finds as f64,
            t.none,
            median(&mut t.static_us),
            median(&mut t.gap_us),
            median(&mut t.ratio)
        );
    }
}

fn main() {
    let mut args = std::env::args().skip(1);
    let n: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(1000);
    let seed: u64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(1);
    let mut csv = args.next().map(|path| {
        let mut out = std::io::BufWriter::new(std::fs::File::create(&path).expect("a CSV file"));
        writeln!(
            out,
            "find,form_and_load,k,mu,half_angle_deg,lambda,voussoirs,status,static_limit,collapse,\
             eccentricity,collapse_work_loads,at_deg"
        )
        .expect("writable");
        out
    });
    let mut d = Draw(seed);
    let mut by_class: BTreeMap<String, Tally> = BTreeMap::new();
    let mut by_find: BTreeMap<&str, Tally> = BTreeMap::new();
    let mut widest: Vec<(f64, String)> = Vec::new();
    let mut drawn = 0;
    let mut with_limit = 0;
    while drawn < n {
        let Some(scene) = draw_scene(&mut d) else {
            continue;
        };
        drawn += 1;
        let s = scene::solve(&scene);
        let Some(status) = s.gap else {
            continue;
        };
        with_limit += 1;
        if let Some(out) = csv.as_mut() {
            writeln!(
                out,
                "{},\"{}\",{:?},{:?},{:?},{:?},{},{},{:?},{:?},{:?},{:?},{}",
                scene.find.as_str(),
                class(&scene),
                scene.arch.k,
                scene.friction.mu(),
                scene.arch.half_angle_deg(),
                scene.lambda,
                s.voussoirs.map_or(String::new(), |v| v.to_string()),
                status.as_str(),
                static_limit(&s),
                s.collapse_value.unwrap_or(f64::NAN),
                scene.form.shape.eccentricity(),
                s.collapse_work_loads.unwrap_or(f64::NAN),
                scene
                    .load
                    .at_deg()
                    .map_or(String::new(), |a| format!("{a:?}")),
            )
            .expect("writable");
        }
        let t_gap = gap_time(&scene, &s).unwrap_or(0.0);
        for t in [
            by_class.entry(class(&scene)).or_default(),
            by_find.entry(scene.find.as_str()).or_default(),
        ] {
            t.finds += 1;
            t.gaps += usize::from(status == GapStatus::Gap);
            t.none += usize::from(status == GapStatus::NoCompleteSolution);
            let today = (s.solve_time_us - t_gap).max(0.0);
            t.static_us.push(today);
            t.gap_us.push(t_gap);
            if today > 0.0 {
                t.ratio.push(t_gap / today);
            }
        }
        if status == GapStatus::Gap {
            let limit = static_limit(&s);
            let v = s.collapse_value.unwrap_or(f64::NAN);
            let rel = (v - limit).abs() / limit.abs();
            widest.push((
                if rel.is_finite() { rel } else { f64::INFINITY },
                format!(
                    "| {} | {} | K = {:.4}, μ = {:.4}, α = {:.2}°, λ = {:.4} | {} | {:.6} | {:.6} | {} |",
                    scene.find.as_str(),
                    class(&scene),
                    scene.arch.k,
                    scene.friction.mu(),
                    scene.arch.half_angle_deg(),
                    scene.lambda,
                    s.voussoirs.map_or("—".to_string(), |v| v.to_string()),
                    limit,
                    v,
                    s.collapse_mechanism.map_or("—", |m| m.as_str()),
                ),
            ));
        }
    }
    println!("{n} scenes drawn with seed {seed}; {with_limit} have a static limit.\n");
    print_tallies("find", by_find.iter_mut().map(|(k, t)| (k.to_string(), t)));
    println!();
    print_tallies(
        "form and load",
        by_class.iter_mut().map(|(k, t)| (k.clone(), t)),
    );
    widest.sort_by(|a, b| b.0.total_cmp(&a.0));
    println!("\nThe widest gaps (relative to the static limit):\n");
    println!("| find | form and load | scene | voussoirs | static limit | collapse | mechanism |");
    println!("|---|---|---|---|---|---|---|");
    for (_, line) in widest.iter().take(12) {
        println!("{line}");
    }
}
