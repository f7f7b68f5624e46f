//! The `authors:` and `license:` rules: what a run's citation metadata says of the study.

use super::Ctx;
use crate::manifest::error::ManifestError;
use crate::manifest::raw::RawAuthor;
use crate::manifest::types::Author;
use serde_saphyr::Spanned;

/// Longest author name, affiliation or licence accepted, in characters.
const MAX_TEXT: usize = 300;

/// Authors: a non-empty name each, an ORCID iD in its printed form when given.
pub(super) fn validate_authors(
    raw: &[Spanned<RawAuthor>],
    cx: &Ctx,
) -> Result<Vec<Author>, ManifestError> {
    raw.iter()
        .enumerate()
        .map(|(i, a)| {
            let key = format!("authors[{i}]");
            let name = a.value.name.trim();
            if name.is_empty() || name.chars().count() > MAX_TEXT {
                return Err(cx.err(
                    Some(a.referenced),
                    &format!("{key}.name"),
                    format!("value {name:?} is not allowed: a name of 1 to {MAX_TEXT} characters"),
                ));
            }
            if let Some(o) = &a.value.orcid
                && !is_orcid(o)
            {
                return Err(cx.err(
                    Some(a.referenced),
                    &format!("{key}.orcid"),
                    format!(
                        "value {o:?} is not allowed: an ORCID iD is four groups of four digits, \
                         0000-0002-1825-0097 (the last may be X)"
                    ),
                ));
            }
            let affiliation = a.value.affiliation.as_deref().map(str::trim);
            if affiliation.is_some_and(|s| s.is_empty() || s.chars().count() > MAX_TEXT) {
                return Err(cx.err(
                    Some(a.referenced),
                    &format!("{key}.affiliation"),
                    format!("is not allowed: an affiliation of 1 to {MAX_TEXT} characters"),
                ));
            }
            Ok(Author {
                name: name.to_string(),
                orcid: a.value.orcid.clone(),
                affiliation: affiliation.map(str::to_string),
            })
        })
        .collect()
}

/// `dddd-dddd-dddd-dddX`, the last character a digit or `X`, with a valid ISO 7064 check.
fn is_orcid(s: &str) -> bool {
    let groups: Vec<&str> = s.split('-').collect();
    if groups.len() != 4 || groups.iter().any(|g| g.len() != 4) {
        return false;
    }
    let chars: Vec<char> = groups.concat().chars().collect();
    let (body, check) = chars.split_at(15);
    if !body.iter().all(char::is_ascii_digit) {
        return false;
    }
    let total = body
        .iter()
        .fold(0u32, |t, c| (t + c.to_digit(10).unwrap_or(0)) * 2);
    let digit = (12 - total % 11) % 11;
    let expected = if digit == 10 {
        'X'
    } else {
        char::from_digit(digit, 10).unwrap_or('?')
    };
    check == [expected]
}

/// A licence: an SPDX expression (identifiers joined by `AND`, `OR`, `WITH`, parentheses).
pub(super) fn validate_license(
    raw: Option<&Spanned<String>>,
    cx: &Ctx,
) -> Result<Option<String>, ManifestError> {
    let Some(l) = raw else { return Ok(None) };
    let text = l.value.trim();
    let ok = !text.is_empty()
        && text.chars().count() <= MAX_TEXT
        && text
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '.' | '-' | '+' | ' ' | '(' | ')'));
    if !ok {
        return Err(cx.err(
            Some(l.referenced),
            "license",
            format!(
                "value {text:?} is not allowed: an SPDX licence expression such as CC-BY-4.0 \
                 or MIT OR Apache-2.0"
            ),
        ));
    }
    Ok(Some(text.to_string()))
}

#[cfg(test)]
mod tests {
    use super::is_orcid;

    #[test]
    fn orcid_check_digits() {
        assert!(is_orcid("0000-0002-1825-0097"));
        assert!(is_orcid("0000-0002-1694-233X"));
        assert!(!is_orcid("0000-0002-1825-0098"));
        assert!(!is_orcid("0000-0002-1825"));
        assert!(!is_orcid("000a-0002-1825-0097"));
    }
}
