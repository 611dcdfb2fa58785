//! Pictures: maps of plans and line charts (convergence curves).

pub mod line_chart;
pub mod map_svg;
pub mod plan_html;
