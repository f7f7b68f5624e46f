//! The uncertain parameters of a sampling study (`uncertain:` and `samples:`): which scene
//! parameters have a distribution instead of grid values, how they are sampled, and the
//! question the samples answer. The values of sample row `r` are computed from `r` alone, so
//! any slice of a plan (a chunk, a shard) holds the same samples whatever the thread count.

use super::types::LoadKind;
use crate::sampling::{Design, Distribution, Method, correlate, saltelli_point};
use crate::scene::Find;
use serde::Serialize;
use serde::ser::SerializeMap;

/// What a sampling study asks of its samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Question {
    /// The probability that the arch does not stand (at its given λ under a live load), and
    /// of each collapse mechanism.
    Probability,
    /// The distribution of the largest load factor λ_max of a live load.
    Fragility,
    /// First-order and total Sobol indices of the stability margin (self-weight) or of
    /// λ_max (live load).
    Sensitivity,
}

impl Question {
    /// All questions.
    pub const ALL: [Question; 3] = [
        Question::Probability,
        Question::Fragility,
        Question::Sensitivity,
    ];

    /// `probability`, `fragility` or `sensitivity`.
    pub fn as_str(self) -> &'static str {
        match self {
            Question::Probability => "probability",
            Question::Fragility => "fragility",
            Question::Sensitivity => "sensitivity",
        }
    }

    /// The question of a `find:` name, if it is one.
    pub fn parse(s: &str) -> Option<Self> {
        Question::ALL.into_iter().find(|q| q.as_str() == s)
    }

    /// The find each sample of a load case of `kind` is analysed with: the state at the
    /// given λ (probability), the largest load factor (fragility, and the sensitivity of a
    /// live load), the collapse thickness (the sensitivity of the self-weight margin, which
    /// compares the sample's thickness with the collapse thickness at its other values).
    pub fn scene_find(self, kind: LoadKind) -> Find {
        match (self, kind.is_live()) {
            (Question::Probability, _) => Find::State,
            (Question::Sensitivity, false) => Find::Thickness,
            (Question::Fragility | Question::Sensitivity, true) => Find::LoadFactor,
            // Refused by the validation: a fragility curve is of a live load.
            (Question::Fragility, false) => Find::LoadFactor,
        }
    }
}

impl std::fmt::Display for Question {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// A scene parameter that may be uncertain.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, PartialOrd, Ord)]
#[serde(rename_all = "snake_case")]
pub enum ParamName {
    /// Thickness ratio K = R/r.
    K,
    /// t/R_c (converted to K).
    TOverR,
    /// Friction coefficient μ.
    Mu,
    /// Half-embrace angle, degrees.
    HalfAngleDeg,
    /// Eccentricity of a pointed arch.
    Eccentricity,
    /// Voussoir count (a discrete distribution).
    Voussoirs,
    /// Position of a point load, degrees from the crown.
    AtDeg,
    /// Position of a point load, x/L.
    AtX,
    /// Load factor λ of the live load.
    Lambda,
}

impl ParamName {
    /// Every parameter, in the order the manifest's keys are read.
    pub const ALL: [ParamName; 9] = [
        ParamName::K,
        ParamName::TOverR,
        ParamName::Mu,
        ParamName::HalfAngleDeg,
        ParamName::Eccentricity,
        ParamName::Voussoirs,
        ParamName::AtDeg,
        ParamName::AtX,
        ParamName::Lambda,
    ];

    /// The manifest key (and the column of samples.parquet).
    pub fn as_str(self) -> &'static str {
        match self {
            ParamName::K => "k",
            ParamName::TOverR => "t_over_r",
            ParamName::Mu => "mu",
            ParamName::HalfAngleDeg => "half_angle_deg",
            ParamName::Eccentricity => "eccentricity",
            ParamName::Voussoirs => "voussoirs",
            ParamName::AtDeg => "at_deg",
            ParamName::AtX => "at_x",
            ParamName::Lambda => "lambda",
        }
    }

    /// The symbol in figures and tables.
    pub fn symbol(self) -> &'static str {
        match self {
            ParamName::K => "K",
            ParamName::TOverR => "t/R_c",
            ParamName::Mu => "μ",
            ParamName::HalfAngleDeg => "α (°)",
            ParamName::Eccentricity => "e",
            ParamName::Voussoirs => "N",
            ParamName::AtDeg => "load at (°)",
            ParamName::AtX => "load at x/L",
            ParamName::Lambda => "λ",
        }
    }
}

/// One uncertain parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct UncertainParam {
    /// Which parameter.
    pub name: ParamName,
    /// Its distribution.
    pub distribution: Distribution,
}

impl Serialize for UncertainParam {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut m = s.serialize_map(None)?;
        m.serialize_entry("name", self.name.as_str())?;
        m.serialize_entry("distribution", self.distribution.name())?;
        match &self.distribution {
            Distribution::Normal { mean, sd } => {
                m.serialize_entry("mean", mean)?;
                m.serialize_entry("sd", sd)?;
            }
            Distribution::LogNormal { mu, sigma } => {
                m.serialize_entry("median", &mu.exp())?;
                m.serialize_entry("log_sd", sigma)?;
            }
            Distribution::Uniform { from, to } => {
                m.serialize_entry("from", from)?;
                m.serialize_entry("to", to)?;
            }
            Distribution::TruncatedNormal { mean, sd, from, to } => {
                m.serialize_entry("mean", mean)?;
                m.serialize_entry("sd", sd)?;
                m.serialize_entry("from", from)?;
                m.serialize_entry("to", to)?;
            }
            Distribution::Beta {
                alpha,
                beta,
                from,
                to,
            } => {
                m.serialize_entry("alpha", alpha)?;
                m.serialize_entry("beta", beta)?;
                m.serialize_entry("from", from)?;
                m.serialize_entry("to", to)?;
            }
            Distribution::Discrete { values, weights } => {
                m.serialize_entry("values", values)?;
                m.serialize_entry("weights", weights)?;
            }
        }
        m.serialize_entry("description", &self.distribution.describe())?;
        m.end()
    }
}

/// A correlation (of the normal scores, a Gaussian copula) between two uncertain parameters.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Correlation {
    /// Index of the first parameter in [`Sampling::params`].
    pub first: usize,
    /// Index of the second.
    pub second: usize,
    /// The correlation coefficient, in (−1, 1).
    pub value: f64,
}

/// A parameter of a distribution given as an axis: each grid point has its own distribution
/// (three scatters of μ, a thickness distribution about each nominal thickness).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DistributionAxis {
    /// Index of the uncertain parameter in [`Sampling::params`].
    pub param: usize,
    /// The distribution's parameter: `mean`, `sd`, `median`, `cov`, `from`, `to`, `alpha`
    /// or `beta`.
    pub field: &'static str,
    /// Its values, in the order they are run.
    pub values: Vec<f64>,
}

/// `d` with one of its parameters set to `v`, as the manifest would give it: a lognormal
/// keeps its other written parameter (σ of ln for `median`, the median for `cov`, the
/// standard deviation for `mean`, the mean for `sd`).
pub fn with_field(d: &Distribution, field: &str, v: f64) -> Distribution {
    use Distribution as D;
    match (d.clone(), field) {
        (D::Normal { sd, .. }, "mean") => D::Normal { mean: v, sd },
        (D::Normal { mean, .. }, "sd") => D::Normal { mean, sd: v },
        (D::LogNormal { sigma, .. }, "median") => D::LogNormal { mu: v.ln(), sigma },
        (D::LogNormal { mu, .. }, "cov") => D::LogNormal {
            mu,
            sigma: (1.0 + v * v).ln().sqrt(),
        },
        (D::LogNormal { .. }, "mean") => Distribution::lognormal_from_mean_sd(v, d.sd()),
        (D::LogNormal { .. }, "sd") => Distribution::lognormal_from_mean_sd(d.mean(), v),
        (D::Uniform { to, .. }, "from") => D::Uniform { from: v, to },
        (D::Uniform { from, .. }, "to") => D::Uniform { from, to: v },
        (D::TruncatedNormal { sd, from, to, .. }, "mean") => D::TruncatedNormal {
            mean: v,
            sd,
            from,
            to,
        },
        (D::TruncatedNormal { mean, from, to, .. }, "sd") => D::TruncatedNormal {
            mean,
            sd: v,
            from,
            to,
        },
        (D::TruncatedNormal { mean, sd, to, .. }, "from") => D::TruncatedNormal {
            mean,
            sd,
            from: v,
            to,
        },
        (D::TruncatedNormal { mean, sd, from, .. }, "to") => D::TruncatedNormal {
            mean,
            sd,
            from,
            to: v,
        },
        (D::Beta { beta, from, to, .. }, "alpha") => D::Beta {
            alpha: v,
            beta,
            from,
            to,
        },
        (
            D::Beta {
                alpha, from, to, ..
            },
            "beta",
        ) => D::Beta {
            alpha,
            beta: v,
            from,
            to,
        },
        (
            D::Beta {
                alpha, beta, to, ..
            },
            "from",
        ) => D::Beta {
            alpha,
            beta,
            from: v,
            to,
        },
        (
            D::Beta {
                alpha, beta, from, ..
            },
            "to",
        ) => D::Beta {
            alpha,
            beta,
            from,
            to: v,
        },
        (other, _) => other,
    }
}

/// Default number of samples.
pub const DEFAULT_SAMPLES: u64 = 4096;
/// Default number of bootstrap resamples of the Sobol indices.
pub const DEFAULT_BOOTSTRAP: u64 = 200;

/// The uncertain parameters of a study and how they are sampled.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Sampling {
    /// What the samples answer.
    pub question: Question,
    /// The uncertain parameters, in [`ParamName::ALL`] order.
    pub params: Vec<UncertainParam>,
    /// A correlation between two of them.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub correlation: Option<Correlation>,
    /// Number of samples (base samples of the sensitivity design).
    pub n: u64,
    /// `sobol`, `lhs` or `random`.
    #[serde(serialize_with = "ser_method")]
    pub method: Method,
    /// Seed of the scramble, the permutations or the random numbers.
    pub seed: u64,
    /// Bootstrap resamples of the Sobol indices' intervals.
    pub bootstrap: u64,
    /// Parameters of distributions given as axes, outermost first: the grid points of the
    /// study run over them inside its grid axes.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub axes: Vec<DistributionAxis>,
}

fn ser_method<S: serde::Serializer>(m: &Method, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(m.as_str())
}

impl Sampling {
    /// Sample rows at each grid point: n, or n·(d + 2) for the sensitivity design (A, B and
    /// A with each column from B).
    pub fn rows(&self) -> u64 {
        match self.question {
            Question::Sensitivity => self.n * (self.params.len() as u64 + 2),
            _ => self.n,
        }
    }

    /// The design the rows are drawn from.
    pub fn design(&self) -> Design {
        let d = self.params.len();
        let dims = if self.question == Question::Sensitivity {
            2 * d
        } else {
            d
        };
        Design::new(self.method, self.seed, self.n, dims)
    }

    /// The uncertain values of sample row `row` (< [`Sampling::rows`]), in `params` order.
    pub fn values(&self, design: &Design, row: u64) -> Vec<f64> {
        let d = self.params.len();
        let mut u = vec![0.0; d];
        if self.question == Question::Sensitivity {
            saltelli_point(design, d, row, &mut u);
        } else {
            design.point(row, &mut u);
        }
        if let Some(c) = self.correlation {
            let (a, b) = correlate(u[c.first], u[c.second], c.value);
            (u[c.first], u[c.second]) = (a, b);
        }
        self.params
            .iter()
            .zip(&u)
            .map(|(p, &u)| p.distribution.quantile(u))
            .collect()
    }

    /// The sampling at one position of its distribution axes (`at[i]` indexes
    /// `axes[i].values`): every distribution set, no axes left.
    pub fn at(&self, at: &[usize]) -> Sampling {
        let mut s = Sampling {
            axes: Vec::new(),
            ..self.clone()
        };
        for (a, &i) in self.axes.iter().zip(at) {
            let p = &mut s.params[a.param];
            p.distribution = with_field(&p.distribution, a.field, a.values[i]);
        }
        s
    }

    /// The name of a distribution axis, `mu.sd`.
    pub fn axis_name(&self, a: &DistributionAxis) -> String {
        format!("{}.{}", self.params[a.param].name.as_str(), a.field)
    }

    /// The positions of the distribution axes at index `point` of their own odometer (the
    /// last axis fastest); a grid point's index modulo [`Sampling::axis_points`].
    pub fn axis_position(&self, point: u64) -> Vec<usize> {
        let mut rest = point;
        let mut at = vec![0; self.axes.len()];
        for (i, a) in self.axes.iter().enumerate().rev() {
            let n = a.values.len() as u64;
            at[i] = (rest % n) as usize;
            rest /= n;
        }
        at
    }

    /// The number of positions of the distribution axes.
    pub fn axis_points(&self) -> u64 {
        self.axes.iter().map(|a| a.values.len() as u64).product()
    }

    /// The uncertain parameter `name`, if it is one.
    pub fn param(&self, name: ParamName) -> Option<&UncertainParam> {
        self.params.iter().find(|p| p.name == name)
    }

    /// The index of parameter `name` among the uncertain ones.
    pub fn index_of(&self, name: ParamName) -> Option<usize> {
        self.params.iter().position(|p| p.name == name)
    }
}
