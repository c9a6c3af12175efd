//! Validation: compare estimates with truth and the thesis tables.
