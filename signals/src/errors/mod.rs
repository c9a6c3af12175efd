//! Error models: receiver oscillator, ionosphere, troposphere, link budget, multipath,
//! fault events.

pub mod clock;
pub mod events;
pub mod ionosphere;
pub mod link_budget;
pub mod multipath;
pub mod seed;
pub mod troposphere;
