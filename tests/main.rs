//! End-to-end tests of the `archstudy` binary and the library's study pipeline, in one test
//! binary.

mod apex;
mod architecture;
mod archive;
mod boundaries;
mod citation;
mod common;
mod damaged;
mod disk_full;
mod hardening;
mod keystone;
mod loads;
mod mechanisms;
mod paper;
mod report;
mod report_arches;
mod report_regime_map;
mod report_states;
mod run;
mod shard;
mod solve;
mod span_positions;
mod symmetric_boundaries;
mod symmetric_lines;
