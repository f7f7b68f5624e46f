//! archstudy: limit analysis of masonry arches with finite Coulomb friction.
//!
//! The data flow is one-way: manifest → plan → analysis → engine → store → boundaries →
//! plots and report. The library does everything the `archstudy` binary does.

// `!(x > a)` is how validation rejects NaN together with out-of-range values.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod analysis;
pub mod app;
pub mod archive;
pub mod boundaries;
pub mod cli;
pub mod engine;
pub mod figdata;
pub mod manifest;
pub mod model;
pub mod output;
pub mod plan;
pub mod plot;
pub mod report;
pub mod runner;
pub mod scene;
pub mod store;
pub mod verify;
