//! End-to-end tests of the `skyforge` binary live in `tests/tests/`.
