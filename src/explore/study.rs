//! The study of a window of (K, μ) around one scene: the manifest the explorer's regime map
//! runs (in memory) and the one "save as study" downloads, one text for both, so that a
//! downloaded study reproduces the map that was on the page.

use super::query::{MAP_PARAMETERS, Query, QueryError};
use crate::manifest::{MAX_K, SceneOptions};
use crate::model::Load;
use crate::report::format::given;
use crate::scene::Scene;
use std::fmt::Write as _;

/// The most grid points of a regime map of a circular arch with radial joints under
/// self-weight (the separable route: about a millisecond per K line).
pub const MAX_MAP_POINTS: u64 = 2500;
/// The most grid points of a regime map of any other scene (the general route: a linear
/// programme per point).
pub const MAX_GENERAL_MAP_POINTS: u64 = 441;
/// The narrowest window of a map along K or μ: below it the grid's values are not distinct
/// enough to draw.
pub const MIN_MAP_SPAN: f64 = 1e-4;
/// The largest μ of a map window (beyond it friction no longer changes the regimes; μ = ∞
/// is the scene's own control).
pub const MAX_MAP_MU: f64 = 1000.0;
/// The most steps along either axis of a map.
pub const MAX_MAP_STEPS: i64 = 201;

/// The window of a regime map: K and μ ranges and their steps.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct MapWindow {
    /// K from, to.
    pub k: (f64, f64),
    /// Steps along K.
    pub k_steps: u64,
    /// μ from, to (finite).
    pub mu: (f64, f64),
    /// Steps along μ.
    pub mu_steps: u64,
}

impl MapWindow {
    /// The window a query gives, around `scene` where it gives none: K ± 0.15 and μ ± 0.25
    /// (μ from 0.1 to 1 at infinite friction), 31 steps each (17 on the general route).
    pub fn of_query(q: &Query, scene: &Scene) -> Result<Self, QueryError> {
        let separable = scene.load == Load::SelfWeight && scene.form.is_circular_radial();
        let cap = if separable {
            MAX_MAP_POINTS
        } else {
            MAX_GENERAL_MAP_POINTS
        };
        let k = scene.arch.k;
        let mu = scene.friction.mu();
        let (mu_lo, mu_hi) = if mu.is_finite() {
            ((mu - 0.25).max(0.0), mu + 0.25)
        } else {
            (0.1, 1.0)
        };
        let steps = if separable { 31 } else { 17 };
        // Window ends to 4 decimals: a downloaded study reads as typed.
        let round = |x: f64| (x * 1e4).round() / 1e4;
        let w = MapWindow {
            k: (
                q.number("k_from", false)?
                    .unwrap_or(round((k - 0.15).max(1.02))),
                q.number("k_to", false)?
                    .unwrap_or(round((k + 0.15).min(MAX_K))),
            ),
            k_steps: count(q, "k_steps", steps)?,
            mu: (
                q.number("mu_from", false)?.unwrap_or(round(mu_lo)),
                q.number("mu_to", false)?.unwrap_or(round(mu_hi)),
            ),
            mu_steps: count(q, "mu_steps", steps)?,
        };
        let k_ok = w.k.0 > 1.0 && w.k.1 - w.k.0 >= MIN_MAP_SPAN && w.k.1 <= MAX_K;
        if !k_ok {
            return Err(window_error(
                q,
                ("k", k),
                w.k,
                format!("1 < k_from < k_to ≤ {MAX_K}"),
            ));
        }
        let mu_ok = w.mu.0 >= 0.0 && w.mu.1 - w.mu.0 >= MIN_MAP_SPAN && w.mu.1 <= MAX_MAP_MU;
        if !mu_ok {
            let allowed = format!("0 ≤ mu_from < mu_to ≤ {MAX_MAP_MU}");
            return Err(window_error(q, ("mu", mu), w.mu, allowed));
        }
        if w.k_steps * w.mu_steps > cap {
            return Err(QueryError::new(
                "k_steps",
                &format!("{} × mu_steps {}", w.k_steps, w.mu_steps),
                format!(
                    "a map of at most {cap} points for this arch and load (run a study for \
                     more: \"save as study\")"
                ),
            ));
        }
        Ok(w)
    }

    /// The window as query pairs.
    pub fn query(&self) -> String {
        let v = [
            self.k.0.to_string(),
            self.k.1.to_string(),
            self.k_steps.to_string(),
            self.mu.0.to_string(),
            self.mu.1.to_string(),
            self.mu_steps.to_string(),
        ];
        MAP_PARAMETERS
            .iter()
            .zip(v)
            .map(|(n, v)| format!("{n}={v}"))
            .collect::<Vec<_>>()
            .join("&")
    }
}

/// A map window that cannot be drawn along `axis` (`k` or `mu`, with the scene's value):
/// named by its `_from` when the query gave the window, else by the scene's value, around
/// which the window was taken.
fn window_error(
    q: &Query,
    (axis, scene_value): (&str, f64),
    (from, to): (f64, f64),
    allowed: String,
) -> QueryError {
    let (from_name, to_name) = (format!("{axis}_from"), format!("{axis}_to"));
    let allowed = format!("a map window {allowed}, at least {MIN_MAP_SPAN} wide");
    if q.get(&from_name).is_some() || q.get(&to_name).is_some() {
        QueryError::new(&from_name, &format!("{from} ({to_name} {to})"), allowed)
    } else {
        QueryError::new(axis, &scene_value.to_string(), allowed)
    }
}

fn count(q: &Query, name: &str, default: u64) -> Result<u64, QueryError> {
    match q.integer(name)? {
        None => Ok(default),
        Some(n) if (2..=MAX_MAP_STEPS).contains(&n) => Ok(n as u64),
        Some(n) => Err(QueryError::new(
            name,
            &n.to_string(),
            format!("an integer from 2 to {MAX_MAP_STEPS}"),
        )),
    }
}

/// A number as the manifest takes it (`inf` for infinity).
fn num(x: f64) -> String {
    if x.is_infinite() {
        "inf".into()
    } else {
        x.to_string()
    }
}

/// The manifest of a `state` study over `window` on the arch and load of `options` (checked
/// into `scene`), with the scene itself as the study's drawn scene.
pub fn manifest_text(options: &SceneOptions, scene: &Scene, window: &MapWindow) -> String {
    let k = scene.arch.k;
    let mu = scene.friction.mu();
    let mut t = String::new();
    let _ = writeln!(
        t,
        "# A K × μ study around the scene K = {}, μ = {} (archstudy explore).",
        num(k),
        num(mu)
    );
    let _ = writeln!(t, "name: explore-around-scene");
    let _ = writeln!(
        t,
        "title: Regimes around K = {}, μ = {}",
        given(k),
        if mu.is_finite() {
            given(mu)
        } else {
            "∞".into()
        }
    );
    let _ = writeln!(t, "arch:");
    let _ = writeln!(t, "  shape: {}", options.shape);
    if let Some(e) = options.eccentricity {
        let _ = writeln!(t, "  eccentricity: {}", num(e));
    }
    let _ = writeln!(t, "  half_angle_deg: {}", num(options.half_angle_deg));
    let _ = writeln!(t, "  joints: {}", options.joints);
    if options.keystone {
        let _ = writeln!(t, "  keystone: true");
    }
    let _ = writeln!(t, "  weight: {}", options.weight);
    let _ = writeln!(
        t,
        "  voussoirs: {}",
        options
            .voussoirs
            .map_or("continuum".to_string(), |n| n.to_string())
    );
    let _ = writeln!(t, "grid:");
    let _ = writeln!(
        t,
        "  k: {{from: {}, to: {}, steps: {}}}",
        num(window.k.0),
        num(window.k.1),
        window.k_steps
    );
    let _ = writeln!(
        t,
        "  mu: {{from: {}, to: {}, steps: {}}}",
        num(window.mu.0),
        num(window.mu.1),
        window.mu_steps
    );
    let _ = writeln!(t, "load_cases:");
    let lambda = scene.lambda;
    let _ = match scene.load {
        Load::SelfWeight => writeln!(t, "  - {{name: gravity, kind: self_weight}}"),
        Load::Horizontal => writeln!(
            t,
            "  - {{name: horizontal, kind: horizontal, lambda: {}}}",
            num(lambda)
        ),
        Load::Point { .. } | Load::PointX { .. } => {
            let at = match (options.at_x, options.at_deg) {
                (Some(x), _) => format!("at_x: {}", num(x)),
                (None, Some(a)) => format!("at_deg: {}", num(a)),
                (None, None) => String::new(),
            };
            writeln!(
                t,
                "  - {{name: point, kind: point, {at}, lambda: {}}}",
                num(lambda)
            )
        }
    };
    let _ = writeln!(t, "find: state");
    let _ = writeln!(t, "scenes:");
    let _ = writeln!(t, "  - {{k: {}, mu: {}}}", num(k), num(mu));
    t
}
