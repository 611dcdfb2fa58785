//! Pictures: maps of plans, the offline viewer, line charts (convergence curves), the
//! terrain map (`terrain.png`, drawn pixel by pixel with its own small font), PNG output
//! (`raster`, with the `png` feature).

pub mod line_chart;
mod map_labels;
pub mod map_svg;
pub mod pixel_font;
pub mod plan_html;
#[cfg(feature = "png")]
pub mod raster;
pub mod terrain_map;
