//! Pictures: maps of plans, the offline viewer, line charts (convergence curves), PNG output
//! (`raster`, with the `png` feature).

pub mod line_chart;
pub mod map_svg;
pub mod plan_html;
#[cfg(feature = "png")]
pub mod raster;
