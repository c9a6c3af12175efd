//! A static ground site.
