//! Scenarios: TOML schema, checks with located errors, and the bundled scenario files.
