//! The validated manifest: the types the planner, the runner and the reports read.

use crate::model::{
    ArchForm, Discretisation, JointOrientation, Load, Shape, WeightModel, t_over_r_from_k,
};
use crate::scene::Find;
use serde::Serialize;

/// The kind of a load case.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LoadKind {
    /// Self-weight only (symmetric).
    SelfWeight,
    /// Self-weight and a horizontal body force λ·(weight) toward +x.
    Horizontal,
    /// Self-weight and a vertical point load λ·W_total on the extrados at `at_deg`.
    Point,
}

impl LoadKind {
    /// The manifest name.
    pub fn as_str(self) -> &'static str {
        match self {
            LoadKind::SelfWeight => "self_weight",
            LoadKind::Horizontal => "horizontal",
            LoadKind::Point => "point",
        }
    }

    /// True when the load case has a live part scaled by λ.
    pub fn is_live(self) -> bool {
        self != LoadKind::SelfWeight
    }
}

/// A named load case.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LoadCase {
    /// Unique name.
    pub name: String,
    /// Kind.
    pub kind: LoadKind,
    /// Position of a point load, degrees from the crown (`None` when the grid has an
    /// `at_deg` axis, and for other kinds).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub at_deg: Option<f64>,
    /// Position of a point load as x/L (`None` when given in degrees or by a grid axis, and
    /// for other kinds).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub at_x: Option<f64>,
    /// Width of a point load spread over the extrados (a patch load), as a fraction of the
    /// extrados span L; `None` for a concentrated point load and for other kinds.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub width: Option<f64>,
    /// The given load factor λ of the live part (state, thickness and friction studies).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda: Option<f64>,
    /// What the cases of this load case compute: the load case's own `find`, or the study's
    /// (in a sampling study, what each sample is analysed with).
    pub find: Find,
    /// The load case of a sampling study: its cases span every grid axis and the sample
    /// rows, whatever its find.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub sampled: bool,
}

impl LoadCase {
    /// The load of this case, with the position of a point load from the grid's `at_deg`
    /// or `at_x` axis when it gives it.
    pub fn load(&self, axis_at_deg: Option<f64>, axis_at_x: Option<f64>) -> Load {
        match self.kind {
            LoadKind::SelfWeight => Load::SelfWeight,
            LoadKind::Horizontal => Load::Horizontal,
            LoadKind::Point => match self.at_x.or(axis_at_x) {
                Some(at_x) if self.at_deg.or(axis_at_deg).is_none() => Load::PointX {
                    at_x,
                    width: self.width.unwrap_or(0.0),
                },
                _ => Load::Point {
                    at_deg: self.at_deg.or(axis_at_deg).unwrap_or(0.0),
                    width: self.width.unwrap_or(0.0),
                },
            },
        }
    }

    /// True when the cases of this load case span the grid axis `axis`: every axis but the
    /// ones its find finds itself (K for `thickness`, μ for `friction`, both for
    /// `thresholds`).
    pub fn spans(&self, axis: AxisName) -> bool {
        if self.sampled {
            return true;
        }
        match axis {
            AxisName::K | AxisName::TOverR => self.find.needs_k(),
            AxisName::Mu => self.find.needs_mu(),
            AxisName::HalfAngleDeg
            | AxisName::Eccentricity
            | AxisName::Joints
            | AxisName::Voussoirs
            | AxisName::AtDeg
            | AxisName::AtX => true,
        }
    }
}

/// The arch options common to every case (each may be overridden by a grid axis).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ArchOptions {
    /// `circular` or `pointed`.
    pub shape: &'static str,
    /// Eccentricity e of a pointed arch.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub eccentricity: Option<f64>,
    /// Half-embrace angle α in degrees.
    pub half_angle_deg: f64,
    /// `radial` or `vertical`.
    pub joints: &'static str,
    /// The crown inside one rigid block (`ArchForm::keystone`).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub keystone: bool,
    /// Weight model.
    pub weight: WeightModel,
    /// Continuum or voussoirs.
    #[serde(serialize_with = "ser_disc")]
    pub voussoirs: Discretisation,
}

impl ArchOptions {
    /// The outline and joint planes.
    pub fn form(&self) -> ArchForm {
        ArchForm {
            shape: match self.eccentricity {
                Some(eccentricity) if self.shape == "pointed" => Shape::Pointed { eccentricity },
                _ => Shape::Circular,
            },
            joints: JointOrientation::parse(self.joints).unwrap_or_default(),
            keystone: self.keystone,
        }
    }
}

fn ser_disc<S: serde::Serializer>(d: &Discretisation, s: S) -> Result<S::Ok, S::Error> {
    match d {
        Discretisation::Continuum => s.serialize_str("continuum"),
        Discretisation::Voussoirs(n) => s.serialize_u32(*n),
    }
}

/// Which parameter a grid axis spans.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum AxisName {
    /// Thickness ratio K.
    K,
    /// t/R_c (converted to K).
    TOverR,
    /// Friction coefficient.
    Mu,
    /// Half-embrace angle in degrees.
    HalfAngleDeg,
    /// Eccentricity of a pointed arch (0: the semicircle's outline).
    Eccentricity,
    /// Joint planes, coded [`JOINTS_RADIAL`] and [`JOINTS_VERTICAL`].
    Joints,
    /// Voussoir count.
    Voussoirs,
    /// Position of a point load, degrees from the crown (an influence line).
    AtDeg,
    /// Position of a point load as x/L (an influence line over the span).
    AtX,
}

impl AxisName {
    /// Every axis.
    pub const ALL: [AxisName; 9] = [
        AxisName::K,
        AxisName::TOverR,
        AxisName::Mu,
        AxisName::HalfAngleDeg,
        AxisName::Eccentricity,
        AxisName::Joints,
        AxisName::Voussoirs,
        AxisName::AtDeg,
        AxisName::AtX,
    ];

    /// The axis of a manifest key ([`AxisName::as_str`]), as run.json stores it.
    pub fn from_key(key: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|a| a.as_str() == key)
    }

    /// True for the axes that change the arch itself: half-angle, eccentricity, joints and
    /// voussoirs.
    pub fn is_arch(self) -> bool {
        matches!(
            self,
            AxisName::HalfAngleDeg
                | AxisName::Eccentricity
                | AxisName::Joints
                | AxisName::Voussoirs
        )
    }

    /// True for the axes of a point load's position, `at_deg` and `at_x`.
    pub fn is_position(self) -> bool {
        matches!(self, AxisName::AtDeg | AxisName::AtX)
    }

    /// True for the axes each of whose values makes a group of cases of its own, in which
    /// boundaries and bifurcations are located along K and μ: the arch axes and the positions
    /// (the boundaries' grid keys its groups by the values of these axes).
    pub fn splits_groups(self) -> bool {
        self.is_arch() || self.is_position()
    }

    /// The manifest key.
    pub fn as_str(self) -> &'static str {
        match self {
            AxisName::K => "k",
            AxisName::TOverR => "t_over_r",
            AxisName::Mu => "mu",
            AxisName::HalfAngleDeg => "half_angle_deg",
            AxisName::Eccentricity => "eccentricity",
            AxisName::Joints => "joints",
            AxisName::Voussoirs => "voussoirs",
            AxisName::AtDeg => "at_deg",
            AxisName::AtX => "at_x",
        }
    }
}

/// The value of a `joints` axis that stands for radial joints.
pub const JOINTS_RADIAL: f64 = 0.0;
/// The value of a `joints` axis that stands for vertical joints.
pub const JOINTS_VERTICAL: f64 = 1.0;

/// The joint planes a value of a `joints` axis stands for.
pub fn joints_of_axis_value(v: f64) -> crate::model::JointOrientation {
    if v == JOINTS_VERTICAL {
        crate::model::JointOrientation::Vertical
    } else {
        crate::model::JointOrientation::Radial
    }
}

/// The value of a `joints` axis that stands for `j`.
pub fn axis_value_of_joints(j: crate::model::JointOrientation) -> f64 {
    match j {
        crate::model::JointOrientation::Radial => JOINTS_RADIAL,
        crate::model::JointOrientation::Vertical => JOINTS_VERTICAL,
    }
}

/// Every form of an arch and its grid axes ([`Manifest::forms`]).
pub fn study_forms(arch: &ArchOptions, grid: &[GridAxis]) -> Vec<crate::model::ArchForm> {
    use crate::model::{ArchForm, JointOrientation, Shape};
    let values = |n: AxisName| grid.iter().find(|a| a.name == n).map(|a| a.values.clone());
    let base = arch.form();
    let shapes: Vec<Shape> = values(AxisName::Eccentricity).map_or_else(
        || vec![base.shape],
        |v| {
            v.iter()
                .map(|&e| Shape::Pointed { eccentricity: e })
                .collect()
        },
    );
    let joints: Vec<JointOrientation> = values(AxisName::Joints).map_or_else(
        || vec![base.joints],
        |v| v.iter().map(|&j| joints_of_axis_value(j)).collect(),
    );
    shapes
        .iter()
        .flat_map(|&shape| {
            joints.iter().map(move |&joints| ArchForm {
                shape,
                joints,
                ..base
            })
        })
        .collect()
}

/// A validated grid axis: its values in the order they are run.
#[derive(Debug, Clone, PartialEq)]
pub struct GridAxis {
    /// The parameter.
    pub name: AxisName,
    /// Values (μ may be infinite).
    pub values: Vec<f64>,
}

/// A `joints` axis is written with its names (`radial`, `vertical`), every other axis with
/// its numbers.
impl Serialize for GridAxis {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let mut st = s.serialize_struct("GridAxis", 2)?;
        st.serialize_field("name", &self.name)?;
        if self.name == AxisName::Joints {
            let names: Vec<&str> = (self.values.iter())
                .map(|&v| joints_of_axis_value(v).as_str())
                .collect();
            st.serialize_field("values", &names)?;
        } else {
            st.serialize_field("values", &self.values)?;
        }
        st.end()
    }
}

/// A scene (K, μ) the report draws.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SceneSpec {
    /// K = R/r.
    pub k: f64,
    /// μ (may be infinite).
    pub mu: f64,
}

/// An author of a study, cited in the run's metadata.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Author {
    /// Name as it should be cited.
    pub name: String,
    /// ORCID iD, `0000-0000-0000-0000` (the last character may be `X`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub orcid: Option<String>,
    /// Affiliation.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub affiliation: Option<String>,
}

/// A validated study manifest.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Manifest {
    /// Study name ([A-Za-z0-9_-]+), names the run directory.
    pub name: String,
    /// Title for reports.
    pub title: Option<String>,
    /// Description for reports.
    pub description: Option<String>,
    /// Authors of the study, for the citation metadata of its runs.
    pub authors: Vec<Author>,
    /// Licence of the study's results, an SPDX expression (e.g. `CC-BY-4.0`).
    pub license: Option<String>,
    /// Arch options.
    pub arch: ArchOptions,
    /// Grid axes, in plan order (outermost first).
    pub grid: Vec<GridAxis>,
    /// Load cases.
    pub load_cases: Vec<LoadCase>,
    /// What each case computes, unless its load case names its own find
    /// ([`LoadCase::find`]).
    pub find: Find,
    /// Scenes to draw.
    pub scenes: Vec<SceneSpec>,
    /// Tolerance for locating boundaries, in K and μ.
    pub boundary_tolerance: f64,
    /// The column width the paper figures (PDF, SVG, PNG in plots/) are drawn for.
    pub figure_width: FigureWidth,
    /// The uncertain parameters of a sampling study (`find: probability`, `fragility` or
    /// `sensitivity`): every grid point is analysed at each of their sample rows.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sampling: Option<super::uncertain::Sampling>,
}

/// The printed width of the paper figures: one column or the full page of a two-column
/// journal.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum FigureWidth {
    /// One column: 3.5 in (88.9 mm).
    Single,
    /// Both columns: 7.2 in (182.9 mm).
    #[default]
    Double,
}

impl FigureWidth {
    /// The values a manifest or the command line may give.
    pub const NAMES: &'static str = "single or double";

    /// The width of a name (`single`, `double`).
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "single" => Some(FigureWidth::Single),
            "double" => Some(FigureWidth::Double),
            _ => None,
        }
    }

    /// The name.
    pub fn as_str(self) -> &'static str {
        match self {
            FigureWidth::Single => "single",
            FigureWidth::Double => "double",
        }
    }

    /// The printed width in inches.
    pub fn inches(self) -> f64 {
        match self {
            FigureWidth::Single => 3.5,
            FigureWidth::Double => 7.2,
        }
    }

    /// The printed width in PostScript points (1/72 in).
    pub fn points(self) -> f64 {
        72.0 * self.inches()
    }
}

/// Default tolerance for boundary location.
pub const DEFAULT_BOUNDARY_TOLERANCE: f64 = 1e-9;

impl Manifest {
    /// The K values of the grid (converted from t/R_c when given so), if any.
    pub fn k_values(&self) -> Option<Vec<f64>> {
        self.grid.iter().find_map(|a| match a.name {
            AxisName::K => Some(a.values.clone()),
            AxisName::TOverR => Some(
                a.values
                    .iter()
                    .map(|&x| crate::model::k_from_t_over_r(x))
                    .collect(),
            ),
            _ => None,
        })
    }

    /// True when a grid axis varies the arch's form (`eccentricity` or `joints`): each case's
    /// form is then its own, and [`ArchOptions::form`] is not every case's.
    pub fn forms_vary(&self) -> bool {
        self.grid
            .iter()
            .any(|a| matches!(a.name, AxisName::Eccentricity | AxisName::Joints))
    }

    /// Every form of the study: the arch's, or one per value of its `eccentricity` and
    /// `joints` axes (the arch's keystone kept), eccentricities outermost.
    pub fn forms(&self) -> Vec<crate::model::ArchForm> {
        study_forms(&self.arch, &self.grid)
    }

    /// t/R_c for a K value.
    pub fn t_over_r(k: f64) -> f64 {
        t_over_r_from_k(k)
    }
}

#[cfg(test)]
mod tests {
    use super::AxisName;

    #[test]
    fn every_axis_reads_back_from_its_key_as_run_json_stores_it() {
        for a in AxisName::ALL {
            assert_eq!(AxisName::from_key(a.as_str()), Some(a));
            // run.json stores the serde name, which the report reads back with `from_key`.
            assert_eq!(serde_json::to_value(a).unwrap(), a.as_str());
        }
        assert_eq!(AxisName::from_key("half_angle"), None);
        let groups: Vec<&str> = (AxisName::ALL.into_iter())
            .filter(|a| a.splits_groups())
            .map(AxisName::as_str)
            .collect();
        assert_eq!(
            groups,
            [
                "half_angle_deg",
                "eccentricity",
                "joints",
                "voussoirs",
                "at_deg",
                "at_x"
            ]
        );
    }
}
