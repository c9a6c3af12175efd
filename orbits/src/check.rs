//! Configuration checks shared by every domain crate: one invalid field, its path, its
//! value and what is allowed. `scenarios` prefixes the path and adds file/line/column.

/// One invalid configuration value.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{field} = {value}: {allowed}")]
pub struct Invalid {
    /// Dotted field path relative to the table the check ran on, e.g. `forces.mass_kg`.
    pub field: String,
    /// The offending value as the user wrote it (or as parsed).
    pub value: String,
    /// What is allowed, phrased for the user, e.g. "must be > 0".
    pub allowed: String,
}

impl Invalid {
    /// A new invalid-field report.
    pub fn new(
        field: impl Into<String>,
        value: impl std::fmt::Display,
        allowed: impl Into<String>,
    ) -> Self {
        Self {
            field: field.into(),
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }

    /// The same report with `prefix` put in front of the field path.
    pub fn within(mut self, prefix: &str) -> Self {
        if !prefix.is_empty() {
            self.field = if self.field.is_empty() {
                prefix.to_string()
            } else {
                format!("{prefix}.{}", self.field)
            };
        }
        self
    }
}
