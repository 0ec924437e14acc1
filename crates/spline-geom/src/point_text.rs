//! The tokens of a line of a point file, shared by the exchange format's point files and the
//! airfoil reader: numbers separated by whitespace or commas, each possibly in parentheses.

/// The non-empty tokens of a line, split at whitespace and commas.
pub(crate) fn tokens(line: &str) -> Vec<&str> {
    line.split(|c: char| c.is_whitespace() || c == ',')
        .filter(|t| !t.is_empty())
        .collect()
}

/// The numbers of the tokens (`(1.5` and `2)` read as 1.5 and 2 only when both
/// parentheses are there: `(1.5)`), or `None` if one is not a number.
pub(crate) fn numbers(tokens: &[&str]) -> Option<Vec<f64>> {
    tokens
        .iter()
        .map(|t| {
            let t = t
                .strip_prefix('(')
                .and_then(|t| t.strip_suffix(')'))
                .unwrap_or(t);
            t.parse::<f64>().ok()
        })
        .collect()
}
