//! Pictures: maps of plans.

pub mod map_svg;
