//! Tests of the strapdown INS against closed-form truth: error-free increments generated
//! here (tests/truth.rs), never by another crate's simulator.

mod alignment;
mod bad_input;
mod mechanisation;
mod rotation;
pub(crate) mod truth;
