//! Error models: receiver oscillator, ionosphere, troposphere.

pub mod clock;
pub mod events;
pub mod ionosphere;
pub mod link_budget;
pub mod seed;
pub mod troposphere;
