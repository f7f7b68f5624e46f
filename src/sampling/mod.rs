//! Uncertain parameters: distributions, sampling designs and the estimators of probabilities,
//! fragility curves and Sobol indices.

pub mod design;
pub mod distribution;
pub mod estimate;
mod gauss;
pub mod quadrature;
pub mod sobol_indices;
mod truncated_normal;

pub use design::{Design, MAX_DIMS, Method, correlate, saltelli_point, saltelli_rows};
pub use distribution::Distribution;
pub use estimate::{Interval, Z95, ecdf_band, quantile_interval, wilson};
pub use quadrature::{Quadrature, QuadratureError, integrate};
pub use sobol_indices::{Indices, indices};
