//! Hillshade: the terrain lit from the north-west (azimuth 315°, 45° above the horizon), as
//! GIS tools draw it, so people can see what was read. Cells without data are transparent.

use std::io::BufWriter;
use std::path::Path;

use super::{Extent, Terrain};

/// A grey-and-alpha picture of the terrain, north up.
#[derive(Debug, Clone)]
pub struct Shaded {
    /// Width, pixels.
    pub width: usize,
    /// Height, pixels.
    pub height: usize,
    /// Pairs of (grey, alpha) bytes, row-major from the north-west corner.
    pub pixels: Vec<u8>,
    /// The plane rectangle the picture covers, metres.
    pub extent: Extent,
}

/// Samples `terrain` over `extent` on a raster of at most `max_side` pixels on its longer
/// side (keeping square pixels) and shades it. `vertical_exaggeration` scales heights.
pub fn hillshade(
    terrain: &dyn Terrain,
    extent: Extent,
    max_side: usize,
    vertical_exaggeration: f64,
) -> Shaded {
    let pixel = extent.width().max(extent.height()) / max_side.max(2) as f64;
    let width = ((extent.width() / pixel).round() as usize).max(2);
    let height = ((extent.height() / pixel).round() as usize).max(2);
    let pixel_x = extent.width() / width as f64;
    let pixel_y = extent.height() / height as f64;
    let mut heights = vec![f64::NAN; width * height];
    for row in 0..height {
        let y = extent.max_y - (row as f64 + 0.5) * pixel_y;
        for column in 0..width {
            let x = extent.min_x + (column as f64 + 0.5) * pixel_x;
            if let Ok(value) = terrain.height_m(x, y) {
                heights[row * width + column] = value * vertical_exaggeration;
            }
        }
    }
    let azimuth = 315f64.to_radians();
    let altitude = 45f64.to_radians();
    let light = [
        azimuth.sin() * altitude.cos(),
        azimuth.cos() * altitude.cos(),
        altitude.sin(),
    ];
    let at = |row: usize, column: usize| heights[row * width + column];
    let mut pixels = vec![0u8; width * height * 2];
    for row in 0..height {
        for column in 0..width {
            let centre = at(row, column);
            if centre.is_nan() {
                continue;
            }
            // Central differences, falling back to one side at edges and holes.
            let sample = |r: usize, c: usize| {
                let value = at(r, c);
                if value.is_nan() {
                    centre
                } else {
                    value
                }
            };
            let west = sample(row, column.saturating_sub(1));
            let east = sample(row, (column + 1).min(width - 1));
            let north = sample(row.saturating_sub(1), column);
            let south = sample((row + 1).min(height - 1), column);
            let span_x = pixel_x * ((column + 1).min(width - 1) - column.saturating_sub(1)) as f64;
            let span_y = pixel_y * ((row + 1).min(height - 1) - row.saturating_sub(1)) as f64;
            let slope_east = (east - west) / span_x;
            let slope_north = (north - south) / span_y;
            let normal = [-slope_east, -slope_north, 1.0];
            let length = (normal[0] * normal[0] + normal[1] * normal[1] + 1.0).sqrt();
            let lit = (normal[0] * light[0] + normal[1] * light[1] + normal[2] * light[2]) / length;
            let index = (row * width + column) * 2;
            pixels[index] = (lit.clamp(0.0, 1.0) * 255.0).round() as u8;
            pixels[index + 1] = 255;
        }
    }
    Shaded {
        width,
        height,
        pixels,
        extent,
    }
}

/// Encodes `pixels` (8 bits a channel, rows top down, `colour`'s channels) as a PNG in memory:
/// the one encoder of every raster the crate writes.
pub fn encode_png(width: usize, height: usize, colour: png::ColorType, pixels: &[u8]) -> Vec<u8> {
    let mut bytes = Vec::new();
    {
        let mut encoder =
            png::Encoder::new(BufWriter::new(&mut bytes), width as u32, height as u32);
        encoder.set_color(colour);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder
            .write_header()
            .expect("writing a PNG header to memory cannot fail");
        writer
            .write_image_data(pixels)
            .expect("the pixel buffer matches the declared size");
    }
    bytes
}

impl Shaded {
    /// Encodes the picture as an 8-bit grey-and-alpha PNG.
    pub fn to_png(&self) -> Vec<u8> {
        encode_png(
            self.width,
            self.height,
            png::ColorType::GrayscaleAlpha,
            &self.pixels,
        )
    }

    /// Writes the picture as a PNG file, atomically.
    pub fn write_png(&self, path: &Path) -> std::io::Result<()> {
        crate::output::write_file_atomically(path, &self.to_png())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::terrain::{Composite, Flat};

    #[test]
    fn flat_ground_is_evenly_lit_and_slopes_facing_the_light_are_brighter() {
        let extent = Extent {
            min_x: 0.0,
            min_y: 0.0,
            max_x: 100.0,
            max_y: 100.0,
        };
        let flat = hillshade(&Flat::new(5.0), extent, 10, 1.0);
        let level = flat.pixels[0];
        assert!(flat.pixels.chunks(2).all(|pixel| pixel == [level, 255]));
        // sin(45°) · 255 ≈ 180
        assert_eq!(level, 180);
        let hills = hillshade(
            &Composite::seed000(),
            Extent {
                max_x: 1000.0,
                max_y: 1000.0,
                ..extent
            },
            64,
            1.0,
        );
        let greys: Vec<u8> = hills.pixels.chunks(2).map(|pixel| pixel[0]).collect();
        assert!(greys.iter().any(|&grey| grey > level) && greys.iter().any(|&grey| grey < level));
        assert_eq!(&hills.to_png()[1..4], b"PNG");
    }
}
