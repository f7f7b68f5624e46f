//! End-to-end tests of the `archstudy` binary and the library's study pipeline, in one test
//! binary.

mod architecture;
mod archive;
mod boundaries;
mod citation;
mod common;
mod hardening;
mod loads;
mod report;
mod report_arches;
mod report_regime_map;
mod run;
mod solve;
