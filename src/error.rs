//! Errors that mean bad usage or input (exit status 2), shared by every command the library
//! offers.

/// A bad option or argument value: names the option, the value and what is allowed.
#[derive(Debug, thiserror::Error)]
#[error("invalid value '{value}' for '{option}': {allowed}")]
pub struct UsageError {
    /// The option or argument as typed, e.g. `--k` or `RUN_DIR`.
    pub option: &'static str,
    /// The value given.
    pub value: String,
    /// What is allowed.
    pub allowed: String,
}

impl UsageError {
    /// A usage error for `option` given `value`, saying what is allowed.
    pub fn new(option: &'static str, value: impl ToString, allowed: impl ToString) -> Self {
        UsageError {
            option,
            value: value.to_string(),
            allowed: allowed.to_string(),
        }
    }
}
