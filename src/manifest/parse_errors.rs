//! The YAML parser's errors in the words of a manifest: the key at fault (found from the
//! position) and what is allowed, without the parser's own vocabulary.

/// Largest number of YAML nodes (keys, values, list items) the parser reads: a study manifest
/// has a few dozen; the grid's long value lists belong in `{from, to, steps}` ranges.
pub const MAX_NODES: usize = 250_000;

/// The parser's message rewritten for a person editing a manifest.
pub(super) fn friendly(message: &str) -> String {
    if let Some(rest) = message.strip_prefix("duplicate mapping key: ") {
        let key = rest.split(',').next().unwrap_or(rest).trim();
        return format!(
            "key `{key}` appears twice in the same mapping: keep one of them (a later one \
             would silently replace the earlier)"
        );
    }
    if message.starts_with("budget breached") {
        return format!(
            "the manifest has more than {MAX_NODES} YAML values, the limit of a study \
             manifest: give long grid axes as {{from, to, steps}} ranges"
        );
    }
    let integer = "expected a whole number (an integer such as 5, not 5.5 or text)";
    if matches!(
        message,
        "invalid i64" | "invalid u64" | "invalid u32" | "invalid i32"
    ) {
        return integer.to_string();
    }
    for (theirs, ours) in [
        (
            "expected sequence start",
            "expected a list such as [1.1, 1.2] (or `- item` lines)",
        ),
        (
            "expected mapping start",
            "expected a mapping of keys and values such as {from: 1.1, to: 1.5, steps: 10}",
        ),
        ("expected string scalar", "expected a text value"),
        ("invalid f64", "expected a number such as 1.35"),
        (
            "invalid floating point",
            "expected a finite number such as 1.35: `inf`, `nan` and numbers beyond ±1.8e308 \
             are not numbers here (only μ may be `inf`, in the grid and in scenes)",
        ),
        ("invalid bool", "expected true or false"),
    ] {
        if message == theirs {
            return ours.to_string();
        }
    }
    message
        .replace("floating point", "number")
        .replace("expected i64", "expected a whole number")
        .replace("expected u32", "expected a whole number ≥ 0")
        .replace("expected f64", "expected a number")
}

/// The key written on the manifest's line `line` at column `column` (1-based) when a key
/// starts there (an unknown key: `note` in `{k: 1.2, mu: 0.4, note: x}` at the column of
/// `note`); else the key before that column, e.g. `steps` for
/// `  k: {from: 1.1, to: 1.2, steps: 5.5}` at the column of 5.5; else the first key on that
/// line, or on the nearest line above that has one.
pub(super) fn key_at(text: &str, line: u64, column: u64) -> Option<String> {
    let lines: Vec<&str> = text.lines().collect();
    let index = usize::try_from(line).ok()?.checked_sub(1)?;
    let here = lines.get(index)?;
    let before = usize::try_from(column)
        .unwrap_or(usize::MAX)
        .saturating_sub(1);
    let from: String = here.chars().skip(before).collect();
    // A key may be quoted (a manifest written as JSON): `"colour": red`.
    let quote = from.chars().next().filter(|c| *c == '"' || *c == '\'');
    let unquoted = &from[quote.map_or(0, char::len_utf8)..];
    let word: String = unquoted
        .chars()
        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
        .collect();
    let after = &unquoted[word.len()..];
    // The position may also fall on the key's first letter, after its opening quote.
    let after = match quote {
        Some(q) => after.strip_prefix(q),
        None => Some(after.trim_start_matches(['"', '\''])),
    };
    if !word.is_empty() && after.is_some_and(|a| a.trim_start().starts_with(':')) {
        return Some(word);
    }
    let upto: String = here
        .chars()
        .take(usize::try_from(column).unwrap_or(usize::MAX))
        .collect();
    let key_before = |s: &str| -> Option<String> {
        let colon = s.rfind(':')?;
        let word: String = s[..colon]
            .trim_end()
            .trim_end_matches(['"', '\''])
            .chars()
            .rev()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
            .collect::<Vec<_>>()
            .into_iter()
            .rev()
            .collect();
        (!word.is_empty()).then_some(word)
    };
    key_before(&upto).or_else(|| lines[..=index].iter().rev().find_map(|l| key_before(l)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parser_words_are_replaced() {
        assert!(friendly("invalid i64").contains("whole number"));
        let d = friendly(
            "duplicate mapping key: name, set DuplicateKeyPolicy in Options if acceptable",
        );
        assert!(
            d.contains("`name` appears twice") && !d.contains("DuplicateKeyPolicy"),
            "{d}"
        );
        let b = friendly("budget breached: Nodes { nodes: 250001 }");
        assert!(b.contains("250000") && !b.contains("Nodes {"), "{b}");
        assert!(friendly("expected sequence start").contains("a list"));
        let n = friendly("invalid floating point");
        assert!(
            n.contains("finite number") && n.contains("only μ may be `inf`"),
            "{n}"
        );
    }

    #[test]
    fn the_key_is_found_from_the_position() {
        let t = "name: a\ngrid:\n  k: {from: 1.1, to: 1.2, steps: 5.5}\n  mu:\n    - x\n";
        assert_eq!(key_at(t, 3, 34).as_deref(), Some("steps"));
        assert_eq!(key_at(t, 1, 7).as_deref(), Some("name"));
        assert_eq!(key_at(t, 5, 7).as_deref(), Some("mu"));
        assert_eq!(key_at(t, 9, 1), None);
        // An unknown key inside a flow mapping is named, not the key before it.
        let f = "scenes: [{k: 1.2, mu: 0.4, note: x}]\n";
        assert_eq!(key_at(f, 1, 28).as_deref(), Some("note"));
        assert_eq!(key_at(f, 1, 23).as_deref(), Some("mu"));
        // A manifest written as JSON quotes its keys.
        let j = "{\"name\": \"x\", \"colour\": \"red\"}\n";
        assert_eq!(key_at(j, 1, 16).as_deref(), Some("colour"));
        assert_eq!(key_at(j, 1, 26).as_deref(), Some("colour"));
        let j2 = "{\n  \"name\": \"x\",\n  'colour': red\n}\n";
        assert_eq!(key_at(j2, 3, 3).as_deref(), Some("colour"));
    }
}
