//! The integration test binary: every end-to-end and CLI test, one module per area.

mod archive;
