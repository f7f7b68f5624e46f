//! End-to-end tests of the `archstudy` binary and the library's study pipeline, in one test
//! binary.

mod apex;
mod architecture;
mod archive;
mod boundaries;
mod common;
mod loads;
mod mechanisms;
mod report;
mod run;
mod solve;
