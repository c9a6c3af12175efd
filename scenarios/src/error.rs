//! The one error type of the crate: a bad scenario, located in its file.

use std::fmt;

/// Longest value text quoted in a message (characters); longer values are cut with `...`.
const MAX_VALUE_CHARS: usize = 60;

/// A scenario that cannot be used: which file, where in it, which field, the value found
/// and what is allowed.
///
/// Displayed as `thesis.toml:12:21: platform.leo.elements.eccentricity = 1.2: must be in
/// [0, 1)`; the line/column part is left out when the problem has no place in the text
/// (an unreadable file), the `= value` part when there is no value (a TOML syntax error,
/// which quotes the offending text in its message; a platform that fails to build), the
/// field too when none applies.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub struct ScenarioError {
    /// The scenario file as given (or `bundled:NAME`).
    pub file: String,
    /// 1-based line of the offending text.
    pub line: Option<usize>,
    /// 1-based column (in characters) of the offending text.
    pub column: Option<usize>,
    /// Dotted field path, e.g. `platform.leo.elements.eccentricity`, `antennas[1].name`;
    /// empty when no field applies (or, for a syntax error, none is known).
    pub field: String,
    /// The offending value as written (shortened when long); empty for TOML syntax errors.
    pub value: String,
    /// What is allowed, or what went wrong.
    pub allowed: String,
}

impl ScenarioError {
    /// An error at no particular place in the text of `file`.
    pub fn unlocated(
        file: &str,
        field: impl Into<String>,
        value: impl Into<String>,
        allowed: impl Into<String>,
    ) -> Self {
        Self {
            file: file.to_string(),
            line: None,
            column: None,
            field: field.into(),
            value: shorten(&value.into()),
            allowed: one_line(&allowed.into()),
        }
    }

    /// The same error placed at 1-based `(line, column)`.
    pub fn at(mut self, position: Option<(usize, usize)>) -> Self {
        if let Some((line, column)) = position {
            self.line = Some(line);
            self.column = Some(column);
        }
        self
    }
}

impl fmt::Display for ScenarioError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file)?;
        if let Some(line) = self.line {
            write!(f, ":{line}")?;
            if let Some(column) = self.column {
                write!(f, ":{column}")?;
            }
        }
        write!(f, ": ")?;
        if !self.field.is_empty() && !self.value.is_empty() {
            write!(f, "{} = {}: ", self.field, self.value)?;
        } else if !self.field.is_empty() {
            write!(f, "{}: ", self.field)?;
        } else if !self.value.is_empty() {
            write!(f, "`{}`: ", self.value)?;
        }
        write!(f, "{}", self.allowed)
    }
}

/// `text` on one line (line breaks become spaces) and at most [`MAX_VALUE_CHARS`] long.
pub(crate) fn shorten(text: &str) -> String {
    let flat = one_line(text.trim());
    if flat.chars().count() > MAX_VALUE_CHARS {
        let cut: String = flat.chars().take(MAX_VALUE_CHARS).collect();
        format!("{cut}...")
    } else {
        flat
    }
}

/// `text` with line breaks replaced by spaces.
fn one_line(text: &str) -> String {
    text.trim_end()
        .chars()
        .map(|c| if c == '\n' || c == '\r' { ' ' } else { c })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn display_matches_the_documented_format() {
        let e = ScenarioError::unlocated(
            "thesis.toml",
            "platform.leo.elements.eccentricity",
            "1.2",
            "must be in [0, 1)",
        )
        .at(Some((12, 21)));
        assert_eq!(
            e.to_string(),
            "thesis.toml:12:21: platform.leo.elements.eccentricity = 1.2: must be in [0, 1)"
        );
        let unreadable = ScenarioError::unlocated("x.toml", "", "", "cannot read file: denied");
        assert_eq!(unreadable.to_string(), "x.toml: cannot read file: denied");
        let syntax =
            ScenarioError::unlocated("x.toml", "", "= 3", "TOML syntax: bad").at(Some((2, 1)));
        assert_eq!(syntax.to_string(), "x.toml:2:1: `= 3`: TOML syntax: bad");
    }

    #[test]
    fn long_values_are_shortened_to_one_line() {
        let long = format!("[a]\n{}", "x".repeat(100));
        let s = shorten(&long);
        assert!(!s.contains('\n'));
        assert_eq!(s.chars().count(), MAX_VALUE_CHARS + 3);
        assert!(s.ends_with("..."));
    }
}
