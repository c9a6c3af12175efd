//! The bundled software receiver. It sees samples and what a real receiver could be told
//! (ephemerides, approximate time and position), never simulator truth: this crate does not
//! depend on `skyforge-signals`.

pub mod tracking;
