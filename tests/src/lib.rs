//! Whole-pipeline tests across the SkyForge crates live in `tests/tests/`; the CLI's
//! end-to-end tests live in `sim/tests/` (they need the `skyforge` binary).
