//! The error of a manifest that cannot be read or is not valid: the file, the line and
//! column, the key at fault and what is wrong, on one line.

use std::path::PathBuf;

/// A manifest that could not be read or is not valid.
#[derive(Debug, thiserror::Error)]
#[error("{}", self.render())]
pub struct ManifestError {
    /// The manifest file.
    pub path: PathBuf,
    /// 1-based line and column, when known.
    pub position: Option<(u64, u64)>,
    /// The key at fault (dotted path), when known.
    pub key: Option<String>,
    /// What is wrong, with the value given and what is allowed.
    pub message: String,
}

impl ManifestError {
    /// The value given and what is allowed, as the message words them ("value V is not
    /// allowed: A", "V is not allowed: A", "unknown field `V`, expected A"); a message
    /// worded otherwise (a missing key, a file that cannot be read) names no value, and all
    /// of it says what is allowed. Quotes around a string value are dropped.
    pub fn value_and_allowed(&self) -> (Option<String>, String) {
        let m = self.message.as_str();
        if let Some(rest) = m.strip_prefix("unknown field `")
            && let Some((field, allowed)) = rest.split_once("`, expected ")
        {
            return (Some(field.to_string()), allowed.to_string());
        }
        if let Some((given, after)) = m.split_once(" is not allowed")
            && let Some((_, allowed)) = after.split_once(": ")
        {
            let given = given.strip_prefix("value ").unwrap_or(given);
            let given = given
                .strip_prefix('"')
                .and_then(|g| g.strip_suffix('"'))
                .unwrap_or(given);
            return (Some(given.to_string()), allowed.to_string());
        }
        (None, m.to_string())
    }

    fn render(&self) -> String {
        let mut s = self.path.display().to_string();
        if let Some((l, c)) = self.position {
            s.push_str(&format!(":{l}:{c}"));
        }
        s.push_str(": ");
        if let Some(k) = &self.key {
            s.push_str(&format!("key `{k}`: "));
        }
        s.push_str(&self.message);
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn error(message: &str) -> ManifestError {
        ManifestError {
            path: "m.yaml".into(),
            position: Some((2, 7)),
            key: Some("find".into()),
            message: message.into(),
        }
    }

    #[test]
    fn the_value_given_and_what_is_allowed_come_apart() {
        let (v, a) =
            error("value \"nope\" is not allowed: use state or thickness").value_and_allowed();
        assert_eq!(
            (v.as_deref(), a.as_str()),
            (Some("nope"), "use state or thickness")
        );
        let (v, a) = error("value -3 is not allowed: steps must be an integer in [1, 100000]")
            .value_and_allowed();
        assert_eq!(
            (v.as_deref(), a.as_str()),
            (Some("-3"), "steps must be an integer in [1, 100000]")
        );
        let (v, a) = error("value \"vertical\" is not allowed with a half-angle of 120°: vertical joints need α ≤ 90°")
            .value_and_allowed();
        assert_eq!(
            (v.as_deref(), a.as_str()),
            (Some("vertical"), "vertical joints need α ≤ 90°")
        );
        let (v, a) =
            error("unknown field `colour`, expected one of name, title").value_and_allowed();
        assert_eq!(
            (v.as_deref(), a.as_str()),
            (Some("colour"), "one of name, title")
        );
        let (v, a) =
            error("a pointed arch needs `eccentricity: e` with 0 ≤ e < 1").value_and_allowed();
        assert_eq!(
            (v, a.as_str()),
            (
                None,
                "a pointed arch needs `eccentricity: e` with 0 ≤ e < 1"
            )
        );
    }
}
