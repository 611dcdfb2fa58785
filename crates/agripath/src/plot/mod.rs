//! Pictures: maps of plans, the offline viewer, line charts (convergence curves), PNG output.

pub mod line_chart;
pub mod map_svg;
pub mod plan_html;
pub mod raster;
