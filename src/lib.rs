//! archstudy: limit analysis of masonry arches with finite Coulomb friction.
//!
//! The data flow is one-way: manifest → plan → analysis → engine → store → boundaries →
//! figure data → plots → report → runner → app; docs/architecture.md gives every module
//! and what it owns. The library does everything the `archstudy` binary does; only `app`
//! sees the command line or prints.

#![warn(missing_docs)]
#![warn(clippy::unwrap_used, clippy::expect_used, clippy::too_many_lines)]
// `!(x > a)` is how validation rejects NaN together with out-of-range values.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod analysis;
pub mod app;
pub mod archive;
pub mod boundaries;
pub mod citation;
pub mod engine;
pub mod error;
pub mod explore;
pub mod figdata;
pub mod manifest;
pub mod merge;
pub mod model;
pub mod output;
pub mod plan;
pub mod plot;
pub mod progress;
pub mod provenance;
pub mod records;
pub mod report;
pub mod runner;
pub mod sampling;
pub mod scene;
pub mod shard;
pub mod slurm;
pub mod store;
pub mod verify;
