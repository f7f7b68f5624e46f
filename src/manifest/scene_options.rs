//! The options of one scene as `archstudy solve` and the Python `archstudy.solve` take them,
//! checked once into a [`Scene`]: every rule of a single scene (K or t/R_c, μ, α, weight,
//! voussoirs, find, outline, joints, keystone, load, its position and λ) lives here, and an
//! error names the option by its keyword (`k`, `t_over_r`, `at_x`, ...), the value given and
//! what is allowed.

use super::{MAX_GENERAL_VOUSSOIRS, MAX_K, short_number};
use crate::analysis::forms::FormError;
use crate::model::{
    Arch, ArchForm, Discretisation, Friction, JointOrientation, Load, ModelError, Shape,
    WeightModel, k_from_t_over_r,
};
use crate::scene::{Find, Scene};

/// A bad value of one scene option: the option's keyword, the value and what is allowed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("invalid value '{value}' for '{option}': {allowed}")]
pub struct SceneOptionError {
    /// The option's keyword: `k`, `t_over_r`, `mu`, `half_angle`, `weight`, `voussoirs`,
    /// `find`, `shape`, `eccentricity`, `joints`, `keystone`, `load`, `at`, `at_x` or `lambda`.
    pub option: &'static str,
    /// The value given.
    pub value: String,
    /// What is allowed.
    pub allowed: String,
}

fn bad(option: &'static str, value: impl ToString, allowed: impl ToString) -> SceneOptionError {
    SceneOptionError {
        option,
        value: value.to_string(),
        allowed: allowed.to_string(),
    }
}

/// The options of one scene as typed by a user, before validation. Strings name the kinds as
/// the command line does (`--find load-factor` and `load_factor` alike).
#[derive(Debug, Clone, PartialEq)]
pub struct SceneOptions {
    /// Thickness ratio K = R/r (default 1.35 when neither K nor t/R_c is given).
    pub k: Option<f64>,
    /// Thickness over centreline radius t/R_c, instead of K.
    pub t_over_r: Option<f64>,
    /// Friction coefficient μ ≥ 0 (+∞ for infinite friction).
    pub mu: f64,
    /// Half-embrace angle α in degrees, in (0, 180).
    pub half_angle_deg: f64,
    /// Weight model: `annular` or `centreline`.
    pub weight: String,
    /// Number of voussoirs N ≥ 1 (`None`: the continuum).
    pub voussoirs: Option<i64>,
    /// What to compute: `state`, `thickness`, `friction`, `thrust`, `thresholds` or
    /// `load-factor`.
    pub find: String,
    /// Outline: `circular` or `pointed`.
    pub shape: String,
    /// Eccentricity e ∈ [0, 0.9999] of a pointed arch.
    pub eccentricity: Option<f64>,
    /// Joint planes: `radial` or `vertical`.
    pub joints: String,
    /// The crown inside one rigid block, the keystone.
    pub keystone: bool,
    /// Load case: `self-weight`, `horizontal` or `point`.
    pub load: String,
    /// Position of a point load, degrees from the crown.
    pub at_deg: Option<f64>,
    /// Position of a point load as x/L ∈ [0, 1].
    pub at_x: Option<f64>,
    /// Width of a point load spread over the extrados (a patch load), as a fraction of
    /// the extrados span; `None` for a concentrated load.
    pub width: Option<f64>,
    /// Load factor λ ≥ 0 of the live load (every find but `load_factor`).
    pub lambda: Option<f64>,
}

impl Default for SceneOptions {
    /// The defaults of `archstudy solve`: the state of the semicircle at K = 1.35, μ = ∞.
    fn default() -> Self {
        SceneOptions {
            k: None,
            t_over_r: None,
            mu: f64::INFINITY,
            half_angle_deg: 90.0,
            weight: "annular".into(),
            voussoirs: None,
            find: "state".into(),
            shape: "circular".into(),
            eccentricity: None,
            joints: "radial".into(),
            keystone: false,
            load: "self-weight".into(),
            at_deg: None,
            at_x: None,
            width: None,
            lambda: None,
        }
    }
}

impl SceneOptions {
    /// The validated scene, or the first option at fault.
    pub fn scene(&self) -> Result<Scene, SceneOptionError> {
        let find = Find::parse(&self.find).ok_or_else(|| {
            bad(
                "find",
                &self.find,
                "one of state, thickness, friction, thrust, thresholds, load-factor",
            )
        })?;
        self.unknowns_left_out(find)?;
        let k = self.k()?;
        let friction = Friction::new(self.mu)
            .ok_or_else(|| bad("mu", self.mu, "μ must be a number ≥ 0 or inf"))?;
        let weight = WeightModel::parse(&self.weight)
            .ok_or_else(|| bad("weight", &self.weight, "annular or centreline"))?;
        let joints = match self.voussoirs {
            None => Discretisation::Continuum,
            Some(n) if n >= 1 && n <= i64::from(u32::MAX) => Discretisation::Voussoirs(n as u32),
            Some(n) => return Err(bad("voussoirs", n, "N must be an integer ≥ 1")),
        };
        let arch = Arch::new(k, self.half_angle_deg, weight, joints).map_err(|e| match e {
            ModelError::HalfAngle(a) => bad(
                "half_angle",
                a,
                "α must lie strictly between 0 and 180 degrees",
            ),
            other if self.t_over_r.is_some() => bad(
                "t_over_r",
                self.t_over_r.unwrap_or_default(),
                other.to_string(),
            ),
            other => bad("k", k, other.to_string()),
        })?;
        let form = self.form()?;
        let load = self.load()?;
        if matches!(find, Find::Thrust | Find::Thresholds)
            && !(load == Load::SelfWeight && form.is_circular_radial())
        {
            return Err(bad(
                "find",
                &self.find,
                format!(
                    "{find} is defined for self-weight on a circular arch with radial joints only"
                ),
            ));
        }
        let lambda = self.lambda(find, load)?;
        if find == Find::LoadFactor && load == Load::SelfWeight {
            return Err(bad(
                "find",
                &self.find,
                "load-factor needs a live load: give --load horizontal or --load point --at DEG",
            ));
        }
        check_general_voussoirs(joints, load, &form)?;
        let scene = Scene {
            arch,
            friction,
            find,
            form,
            load,
            lambda,
        };
        scene.check().map_err(|e| form_error(e, self.t_over_r))?;
        Ok(scene)
    }

    /// Refuses a K or μ given to a find that computes it (K of `thickness`, μ of
    /// `friction`, both of `thresholds`): the value would be left out without a word. μ = ∞,
    /// the default, counts as not given.
    fn unknowns_left_out(&self, find: Find) -> Result<(), SceneOptionError> {
        if !find.needs_k() {
            let given = [("k", self.k), ("t_over_r", self.t_over_r)];
            if let Some((option, Some(v))) = given.into_iter().find(|(_, v)| v.is_some()) {
                return Err(bad(
                    option,
                    short_number(v),
                    format!("the {find} find computes K: give neither K nor t/R_c"),
                ));
            }
        }
        if !find.needs_mu() && self.mu.is_finite() {
            return Err(bad(
                "mu",
                short_number(self.mu),
                format!("the {find} find computes μ: give no μ"),
            ));
        }
        Ok(())
    }

    /// K from `k` or `t_over_r`, within (1, MAX_K].
    fn k(&self) -> Result<f64, SceneOptionError> {
        Ok(match (self.k, self.t_over_r) {
            (Some(_), Some(_)) => {
                return Err(bad(
                    "t_over_r",
                    self.t_over_r.unwrap_or_default(),
                    "give either --k or --t-over-r, not both",
                ));
            }
            (Some(k), None) => {
                if !(k > 1.0 && k <= MAX_K) {
                    return Err(bad(
                        "k",
                        short_number(k),
                        format!(
                            "K = R/r must be a number greater than 1 and at most {MAX_K}: beyond \
                             it the solver's answers are not reliable and no masonry arch is \
                             that thick (README, Limits)"
                        ),
                    ));
                }
                k
            }
            (None, Some(x)) => {
                let x_max = 2.0 * (MAX_K - 1.0) / (MAX_K + 1.0);
                if !(x > 0.0 && x <= x_max && k_from_t_over_r(x) > 1.0) {
                    return Err(bad(
                        "t_over_r",
                        short_number(x),
                        format!(
                            "t/R_c must be a number in (0, {x_max:.4}] (K = R/r in (1, {MAX_K}]), \
                             large enough that K differs from 1 (t/R_c ≥ 1e-15)"
                        ),
                    ));
                }
                k_from_t_over_r(x)
            }
            (None, None) => 1.35,
        })
    }

    fn form(&self) -> Result<ArchForm, SceneOptionError> {
        let joints = JointOrientation::parse(&self.joints)
            .ok_or_else(|| bad("joints", &self.joints, "radial or vertical"))?;
        let shape = match (self.shape.as_str(), self.eccentricity) {
            ("circular", None) => Shape::Circular,
            ("circular", Some(e)) => {
                return Err(bad(
                    "eccentricity",
                    e,
                    "only a pointed arch has an eccentricity: add --shape pointed",
                ));
            }
            ("pointed", Some(e)) if crate::analysis::forms::eccentricity_allowed(e) => {
                Shape::Pointed { eccentricity: e }
            }
            ("pointed", Some(e)) => {
                return Err(bad(
                    "eccentricity",
                    e,
                    format!(
                        "e must lie in {} (beyond, the critical thickness t/R_c ≈ 0.175 (1 − e) \
                         is below what the margins resolve)",
                        crate::analysis::forms::ECCENTRICITY_RANGE
                    ),
                ));
            }
            ("pointed", None) => {
                return Err(bad(
                    "shape",
                    "pointed",
                    "a pointed arch needs --eccentricity E (0 ≤ E < 1; 0.5 is the equilateral arch)",
                ));
            }
            (other, _) => return Err(bad("shape", other, "circular or pointed")),
        };
        Ok(ArchForm {
            shape,
            joints,
            keystone: self.keystone,
        })
    }

    /// The load, a point load spread over the width given.
    fn load(&self) -> Result<Load, SceneOptionError> {
        let load = self.concentrated_load()?;
        let Some(w) = self.width else {
            return Ok(load);
        };
        if !load.is_live() || load == Load::Horizontal {
            return Err(bad(
                "width",
                w,
                "--width spreads a point load over the extrados: add --load point",
            ));
        }
        if !(0.0..=1.0).contains(&w) {
            return Err(bad(
                "width",
                w,
                "a fraction of the extrados span in [0, 1] (0: a concentrated load)",
            ));
        }
        Ok(match load {
            Load::Point { at_deg, .. } => Load::Point { at_deg, width: w },
            Load::PointX { at_x, .. } => Load::PointX { at_x, width: w },
            other => other,
        })
    }

    fn concentrated_load(&self) -> Result<Load, SceneOptionError> {
        if let Some(x) = self.at_x {
            return match (self.load.as_str(), self.at_deg) {
                (_, Some(a)) => Err(bad(
                    "at",
                    a,
                    "give the position once: --at DEG or --at-x X/L, not both",
                )),
                ("point", None) if (0.0..=1.0).contains(&x) => Ok(Load::point_x(x)),
                ("point", None) => Err(bad(
                    "at_x",
                    x,
                    "x/L must lie in [0, 1] (0 and 1 the extrados springings, 0.5 the crown)",
                )),
                (_, None) => Err(bad(
                    "at_x",
                    x,
                    "--at-x is the position of a point load: add --load point",
                )),
            };
        }
        let load = match (self.load.as_str(), self.at_deg) {
            ("self-weight" | "self_weight", None) => Load::SelfWeight,
            ("horizontal", None) => Load::Horizontal,
            ("point", Some(a)) if a.is_finite() => Load::point(a),
            ("point", Some(a)) => return Err(bad("at", a, "a finite angle in degrees")),
            ("point", None) => {
                return Err(bad(
                    "load",
                    "point",
                    "a point load needs its position: add --at DEG (degrees from the crown) or --at-x X/L",
                ));
            }
            (_, Some(a)) => {
                return Err(bad(
                    "at",
                    a,
                    "--at is the position of a point load: add --load point",
                ));
            }
            (other, None) => {
                return Err(bad("load", other, "self-weight, horizontal or point"));
            }
        };
        Ok(load)
    }

    fn lambda(&self, find: Find, load: Load) -> Result<f64, SceneOptionError> {
        match (self.lambda, load.is_live(), find) {
            (None, false, _) | (None, true, Find::LoadFactor) => Ok(0.0),
            (Some(l), _, Find::LoadFactor) => Err(bad(
                "lambda",
                l,
                "load-factor finds λ itself: remove --lambda",
            )),
            (Some(l), false, _) => Err(bad(
                "lambda",
                l,
                "self-weight has no live part to scale: add --load horizontal or --load point",
            )),
            (Some(l), true, _) if l >= 0.0 && l.is_finite() => Ok(l),
            (Some(l), true, _) => Err(bad("lambda", l, "λ must be a finite number ≥ 0")),
            (None, true, _) => Err(bad(
                "load",
                &self.load,
                format!(
                    "a live load needs its load factor for --find {}: add --lambda L (or use --find load-factor)",
                    find
                ),
            )),
        }
    }
}

/// The general solver's voussoir limit (live loads, pointed arches, vertical joints).
fn check_general_voussoirs(
    joints: Discretisation,
    load: Load,
    form: &ArchForm,
) -> Result<(), SceneOptionError> {
    if let Discretisation::Voussoirs(n) = joints
        && n > MAX_GENERAL_VOUSSOIRS
        && (load.is_live() || !form.is_circular_radial())
    {
        Err(bad(
            "voussoirs",
            n,
            format!(
                "a live load, a pointed outline or vertical joints are analysed by the \
                 general solver, which answers promptly up to {MAX_GENERAL_VOUSSOIRS} \
                 voussoirs: use at most {MAX_GENERAL_VOUSSOIRS}, or omit --voussoirs for \
                 the continuum"
            ),
        ))
    } else {
        Ok(())
    }
}

/// The option at fault when the form does not exist; a thickness given as t/R_c is named
/// as given, with its own bound.
fn form_error(e: FormError, t_over_r: Option<f64>) -> SceneOptionError {
    match e {
        FormError::Eccentricity(v) => bad("eccentricity", v, e.to_string()),
        FormError::PointedTooThick {
            eccentricity,
            half_angle_deg,
            max_k,
            ..
        } if t_over_r.is_some() => bad(
            "t_over_r",
            short_number(t_over_r.unwrap_or_default()),
            format!(
                "a pointed arch with eccentricity {eccentricity} and half-angle \
                 {half_angle_deg}° exists only for t/R_c < {:.4} (K < {max_k:.4}); t/R_c = {} is \
                 too thick",
                crate::model::t_over_r_from_k(max_k),
                short_number(t_over_r.unwrap_or_default()),
            ),
        ),
        FormError::PointedTooThick { k, .. } | FormError::NotThick(k) => bad("k", k, e.to_string()),
        FormError::VerticalBeyondQuadrant(a) => bad("half_angle", a, e.to_string()),
        FormError::LoadOutside { at_deg, .. }
        | FormError::LoadInsideKeystone { at_deg, .. }
        | FormError::LoadOffExtrados { at_deg, .. } => bad("at", at_deg, e.to_string()),
        FormError::NoKeystone(_) => bad("keystone", "on", e.to_string()),
        FormError::LoadOffSpan { at_x, .. } | FormError::XInsideKeystone { at_x, .. } => {
            bad("at_x", at_x, e.to_string())
        }
        FormError::PatchOffSpan { width, .. } => bad("width", width, e.to_string()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_defaults_are_the_semicircle_state_at_k_1_35_and_infinite_friction() {
        let s = SceneOptions::default().scene().unwrap();
        assert_eq!(s.find, Find::State);
        assert_eq!(s.arch.k, 1.35);
        assert!(s.friction.is_infinite());
        assert_eq!(s.load, Load::SelfWeight);
    }

    #[test]
    fn a_value_given_for_what_the_find_computes_is_refused_not_left_out() {
        let refused = |o: SceneOptions| o.scene().unwrap_err();
        let e = refused(SceneOptions {
            k: Some(1.3),
            find: "thickness".into(),
            ..SceneOptions::default()
        });
        assert_eq!((e.option, e.value.as_str()), ("k", "1.3"));
        assert!(e.allowed.contains("computes K"), "{e}");
        let e = refused(SceneOptions {
            t_over_r: Some(0.1),
            find: "thresholds".into(),
            ..SceneOptions::default()
        });
        assert_eq!(e.option, "t_over_r");
        let e = refused(SceneOptions {
            mu: 0.4,
            find: "friction".into(),
            ..SceneOptions::default()
        });
        assert_eq!((e.option, e.value.as_str()), ("mu", "0.4"));
        assert!(e.allowed.contains("computes μ"), "{e}");
        // μ = ∞ is the default: a friction find with it, and a thickness find with a μ, stand.
        let ok = SceneOptions {
            find: "friction".into(),
            ..SceneOptions::default()
        };
        assert_eq!(ok.scene().unwrap().find, Find::Friction);
        let ok = SceneOptions {
            mu: 0.4,
            find: "thickness".into(),
            ..SceneOptions::default()
        };
        assert_eq!(ok.scene().unwrap().find, Find::Thickness);
    }

    #[test]
    fn an_error_names_the_keyword_the_value_and_what_is_allowed() {
        let o = SceneOptions {
            k: Some(0.9),
            ..SceneOptions::default()
        };
        let e = o.scene().unwrap_err();
        assert_eq!((e.option, e.value.as_str()), ("k", "0.9"));
        assert!(e.allowed.contains("greater than 1"), "{e}");
        let o = SceneOptions {
            load: "point".into(),
            at_x: Some(1.5),
            lambda: Some(0.1),
            ..SceneOptions::default()
        };
        assert_eq!(o.scene().unwrap_err().option, "at_x");
        let o = SceneOptions {
            mu: -0.1,
            ..SceneOptions::default()
        };
        assert_eq!(o.scene().unwrap_err().option, "mu");
        // A thickness given as t/R_c is named as given, not as the K it becomes.
        let o = SceneOptions {
            t_over_r: Some(0.9),
            shape: "pointed".into(),
            eccentricity: Some(0.9),
            ..SceneOptions::default()
        };
        let e = o.scene().unwrap_err();
        assert_eq!((e.option, e.value.as_str()), ("t_over_r", "0.9"));
        // K < 1 + 2/9 there: t/R_c = 2(K − 1)/(K + 1) < 0.2.
        assert!(e.allowed.contains("t/R_c < 0.2000 (K < 1.2222)"), "{e}");
    }
}
