//! Error models: receiver oscillator, ionosphere, troposphere.
