//! `terrain.png`: the terrain under the farm as an operator reads a map. Heights are tinted
//! along a colour ramp and shaded by the hillshade; the fields (boundaries and holes), the
//! no-spray zones and the supply point are drawn on it; a legend gives the ramp with the
//! lowest and highest height in the picture, the symbols, and a scale bar of a round length.
//!
//! A pixel of height z is c = ramp(t) · (0.35 + 0.65 · s), with t = (z − z_min) / (z_max −
//! z_min) over the heights in the picture (t = 0.5 when the ground is flat) and s the
//! hillshade's grey / 255 (lit from the north-west); the ramp is piecewise linear through
//! green, yellow, brown and near-white, the hypsometric tints of printed maps.
//! Cells without data stay transparent. The picture keeps the hillshade's size and extent
//! (north up, square pixels); the legend sits in the corner where it hides the fewest drawn
//! field pixels. Everything is drawn into the raster (no resvg), so `terrain.png` is the same
//! with or without the `png` feature.

use geo::{Coord, LineString};

use super::pixel_font::{glyph, text_width, ADVANCE, CAP_HEIGHT, GLYPH_HEIGHT, GLYPH_WIDTH};
use crate::model::Farm;
use crate::terrain::hillshade::Shaded;
use crate::terrain::Terrain;

/// Field boundaries: a blue no height tint takes.
pub const FIELD_COLOUR: [u8; 3] = [21, 101, 192];
/// The edges of holes in fields (ground inside a boundary that is not sprayed): a purple no
/// height tint takes, so a hole does not read as a second field.
pub const HOLE_COLOUR: [u8; 3] = [123, 31, 162];
/// No-spray zones.
pub const OBSTACLE_COLOUR: [u8; 3] = [198, 40, 40];
/// The supply point's fill (inside a dark ring).
pub const SUPPLY_COLOUR: [u8; 3] = [255, 235, 59];
const INK: [u8; 3] = [34, 34, 34];
const PAPER: [u8; 3] = [255, 255, 255];

/// Height tint from low to high: green, yellow, brown, near white (the track's top view
/// tints its terrain with the same ramp).
const RAMP: [(f64, [f64; 3]); 4] = [
    (0.0, [74.0, 140.0, 84.0]),
    (0.35, [222.0, 214.0, 128.0]),
    (0.7, [168.0, 118.0, 72.0]),
    (1.0, [245.0, 242.0, 236.0]),
];

/// The tint of height fraction `fraction` ∈ [0, 1] of the relief, linear between the stops.
pub fn height_tint(fraction: f64) -> [f64; 3] {
    let fraction = fraction.clamp(0.0, 1.0);
    for pair in RAMP.windows(2) {
        let ((low, a), (high, b)) = (pair[0], pair[1]);
        if fraction <= high {
            let t = (fraction - low) / (high - low);
            return [0, 1, 2].map(|k| a[k] + t * (b[k] - a[k]));
        }
    }
    RAMP[RAMP.len() - 1].1
}

/// What `terrain.png` shows.
pub struct TerrainPicture<'a> {
    /// The height model, sampled at the hillshade's pixel centres for the tint.
    pub terrain: &'a dyn Terrain,
    /// The hillshade: the picture's size, extent and light.
    pub shaded: &'a Shaded,
    /// The fields and no-spray zones, in the plan frame.
    pub farm: &'a Farm,
    /// Where the drone takes off, refills and swaps batteries, if the plan has one.
    pub supply: Option<Coord<f64>>,
}

/// The colour of the ramp at `t` ∈ [0, 1], in bytes.
pub fn ramp(t: f64) -> [u8; 3] {
    height_tint(t).map(|channel| channel.round() as u8)
}

/// An RGBA raster, row-major from the north-west corner.
struct Canvas {
    width: usize,
    height: usize,
    pixels: Vec<u8>,
}

impl Canvas {
    /// Paints pixel (column, row) with `colour` at `opacity` ∈ [0, 1] over what is there;
    /// outside the picture nothing happens.
    fn blend(&mut self, column: i64, row: i64, colour: [u8; 3], opacity: f64) {
        if column < 0 || row < 0 || column as usize >= self.width || row as usize >= self.height {
            return;
        }
        let index = (row as usize * self.width + column as usize) * 4;
        let below = f64::from(self.pixels[index + 3]) / 255.0;
        let alpha = opacity + below * (1.0 - opacity);
        for (slot, &channel) in self.pixels[index..index + 3].iter_mut().zip(&colour) {
            let old = f64::from(*slot) * below * (1.0 - opacity);
            let new = f64::from(channel) * opacity;
            *slot = ((old + new) / alpha.max(1e-9)).round() as u8;
        }
        self.pixels[index + 3] = (alpha * 255.0).round() as u8;
    }

    fn rectangle(
        &mut self,
        left: i64,
        top: i64,
        width: i64,
        height: i64,
        colour: [u8; 3],
        opacity: f64,
    ) {
        for row in top..top + height {
            for column in left..left + width {
                self.blend(column, row, colour, opacity);
            }
        }
    }

    /// The pixels whose centres lie within `radius` of (x, y).
    fn disc(&mut self, x: f64, y: f64, radius: f64, colour: [u8; 3]) {
        for row in (y - radius).floor() as i64..=(y + radius).ceil() as i64 {
            for column in (x - radius).floor() as i64..=(x + radius).ceil() as i64 {
                let (dx, dy) = (column as f64 + 0.5 - x, row as f64 + 0.5 - y);
                if dx * dx + dy * dy <= radius * radius {
                    self.blend(column, row, colour, 1.0);
                }
            }
        }
    }

    /// A line `2 · radius` wide: discs every half pixel along it (no anti-aliasing, so the
    /// line is drawn in exactly its colour).
    fn segment(&mut self, from: (f64, f64), to: (f64, f64), radius: f64, colour: [u8; 3]) {
        let length = ((to.0 - from.0).powi(2) + (to.1 - from.1).powi(2)).sqrt();
        let steps = (length * 2.0).ceil().max(1.0) as usize;
        for step in 0..=steps {
            let share = step as f64 / steps as f64;
            let x = from.0 + share * (to.0 - from.0);
            let y = from.1 + share * (to.1 - from.1);
            self.disc(x, y, radius, colour);
        }
    }

    /// `text` with its top-left corner at (left, top), each font pixel `scale` pixels wide.
    fn text(&mut self, left: i64, top: i64, text: &str, scale: usize, colour: [u8; 3]) {
        for (index, character) in text.chars().enumerate() {
            let rows = glyph(character);
            let origin = left + (index * ADVANCE * scale) as i64;
            for (row, bits) in rows.iter().enumerate() {
                for column in 0..GLYPH_WIDTH {
                    if bits & (1 << (GLYPH_WIDTH - 1 - column)) != 0 {
                        let x = origin + (column * scale) as i64;
                        let y = top + (row * scale) as i64;
                        self.rectangle(x, y, scale as i64, scale as i64, colour, 1.0);
                    }
                }
            }
        }
    }

    /// How many pixels of the rectangle are exactly one of `colours` (drawn symbols).
    fn count(&self, left: i64, top: i64, width: i64, height: i64, colours: &[[u8; 3]]) -> usize {
        let mut found = 0;
        for row in top.max(0)..(top + height).min(self.height as i64) {
            for column in left.max(0)..(left + width).min(self.width as i64) {
                let index = (row as usize * self.width + column as usize) * 4;
                if colours
                    .iter()
                    .any(|colour| self.pixels[index..index + 3] == colour[..])
                {
                    found += 1;
                }
            }
        }
        found
    }

    fn to_png(&self) -> Vec<u8> {
        crate::terrain::hillshade::encode_png(
            self.width,
            self.height,
            png::ColorType::Rgba,
            &self.pixels,
        )
    }
}

/// A height as the legend prints it: whole metres, tenths when the relief is under 10 m.
fn height_label(height_m: f64, relief_m: f64) -> String {
    if relief_m < 10.0 {
        format!("{height_m:.1} m")
    } else {
        format!("{height_m:.0} m")
    }
}

/// Draws `terrain.png` (see the module comment) and encodes it as an RGBA PNG.
pub fn terrain_map_png(picture: &TerrainPicture) -> Vec<u8> {
    let shaded = picture.shaded;
    let (width, height, extent) = (shaded.width, shaded.height, shaded.extent);
    let pixel_x = extent.width() / width as f64;
    let pixel_y = extent.height() / height as f64;
    // Heights at the hillshade's own pixel centres, so tint and light agree.
    let mut heights = vec![f64::NAN; width * height];
    for row in 0..height {
        let y = extent.max_y - (row as f64 + 0.5) * pixel_y;
        for column in 0..width {
            let x = extent.min_x + (column as f64 + 0.5) * pixel_x;
            if shaded.pixels[(row * width + column) * 2 + 1] > 0 {
                if let Ok(value) = picture.terrain.height_m(x, y) {
                    heights[row * width + column] = value;
                }
            }
        }
    }
    let (lowest, highest) = heights
        .iter()
        .filter(|value| value.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), &value| {
            (low.min(value), high.max(value))
        });
    let relief = (highest - lowest).max(0.0);
    let mut canvas = Canvas {
        width,
        height,
        pixels: vec![0; width * height * 4],
    };
    for (cell, value) in heights.iter().enumerate() {
        if !value.is_finite() {
            continue;
        }
        let t = if relief > 0.0 {
            (value - lowest) / relief
        } else {
            0.5
        };
        let light = 0.35 + 0.65 * f64::from(shaded.pixels[cell * 2]) / 255.0;
        let colour = ramp(t);
        for (slot, &channel) in canvas.pixels[cell * 4..cell * 4 + 3]
            .iter_mut()
            .zip(&colour)
        {
            *slot = (f64::from(channel) * light).round().min(255.0) as u8;
        }
        canvas.pixels[cell * 4 + 3] = 255;
    }
    let to_pixel = |point: &Coord<f64>| {
        (
            (point.x - extent.min_x) / pixel_x,
            (extent.max_y - point.y) / pixel_y,
        )
    };
    let ring = |canvas: &mut Canvas, line: &LineString<f64>, colour| {
        for pair in line.0.windows(2) {
            canvas.segment(to_pixel(&pair[0]), to_pixel(&pair[1]), 1.5, colour);
        }
    };
    for field in &picture.farm.fields {
        ring(&mut canvas, field.polygon.exterior(), FIELD_COLOUR);
        for hole in field.polygon.interiors() {
            ring(&mut canvas, hole, HOLE_COLOUR);
        }
    }
    for obstacle in &picture.farm.obstacles {
        for line in std::iter::once(obstacle.polygon.exterior()).chain(obstacle.polygon.interiors())
        {
            ring(&mut canvas, line, OBSTACLE_COLOUR);
        }
    }
    if let Some(supply) = picture.supply {
        let (x, y) = to_pixel(&supply);
        canvas.disc(x, y, 7.0, INK);
        canvas.disc(x, y, 5.0, SUPPLY_COLOUR);
    }
    let legend = Legend {
        lowest: height_label(lowest.min(highest), relief),
        highest: height_label(highest.max(lowest), relief),
        holes: picture
            .farm
            .fields
            .iter()
            .any(|field| !field.polygon.interiors().is_empty()),
        obstacles: !picture.farm.obstacles.is_empty(),
        supply: picture.supply.is_some(),
        scale_bar_m: super::map_svg::scale_bar_m(extent.width()),
        metres_per_pixel: pixel_x,
        // Twice-size letters unless the picture is too small for them.
        scale: if width.min(height) >= 400 { 2 } else { 1 },
    };
    legend.draw(&mut canvas);
    canvas.to_png()
}

/// The legend's content and how large it is drawn.
struct Legend {
    lowest: String,
    highest: String,
    holes: bool,
    obstacles: bool,
    supply: bool,
    scale_bar_m: f64,
    metres_per_pixel: f64,
    scale: usize,
}

impl Legend {
    /// Its rows, top to bottom: the ramp with its ends, the symbols, the scale bar.
    fn draw(&self, canvas: &mut Canvas) {
        let unit = self.scale as i64;
        let line = (GLYPH_HEIGHT as i64 + 3) * unit;
        let pad = 6 * unit;
        let ramp_width = 100 * unit;
        let bar_px = (self.scale_bar_m / self.metres_per_pixel).round() as i64;
        let bar_label = format!("{} m", self.scale_bar_m);
        let symbol = 16 * unit;
        let mut keys = vec![(FIELD_COLOUR, "field")];
        if self.holes {
            keys.push((HOLE_COLOUR, "hole"));
        }
        if self.obstacles {
            keys.push((OBSTACLE_COLOUR, "obstacle"));
        }
        let key_width = keys
            .iter()
            .map(|(_, word)| text_width(word, self.scale))
            .chain([
                text_width("supply", self.scale),
                text_width("north up", self.scale),
            ])
            .max()
            .unwrap_or(0) as i64
            + symbol
            + 4 * unit;
        let panel_width = [
            ramp_width,
            text_width(&self.lowest, self.scale) as i64
                + text_width(&self.highest, self.scale) as i64
                + 4 * unit,
            key_width,
            bar_px + 4 * unit + text_width(&bar_label, self.scale) as i64,
        ]
        .into_iter()
        .max()
        .unwrap_or(0)
            + 2 * pad;
        let rows = 1 + 2 + keys.len() as i64 + i64::from(self.supply) + 1 + 1;
        let panel_height = rows * line + 8 * unit + 2 * pad;
        let margin = 8;
        let (width, height) = (canvas.width as i64, canvas.height as i64);
        let corners = [
            (margin, height - margin - panel_height),
            (width - margin - panel_width, height - margin - panel_height),
            (margin, margin),
            (width - margin - panel_width, margin),
        ];
        let drawn = [FIELD_COLOUR, HOLE_COLOUR, OBSTACLE_COLOUR, SUPPLY_COLOUR];
        // The first corner hiding fewest symbol pixels (ties keep the order above).
        let (left, top) = corners
            .into_iter()
            .min_by_key(|&(left, top)| canvas.count(left, top, panel_width, panel_height, &drawn))
            .unwrap_or(corners[0]);
        canvas.rectangle(left, top, panel_width, panel_height, PAPER, 0.88);
        let (x, mut y) = (left + pad, top + pad);
        canvas.text(x, y, "elevation", self.scale, INK);
        y += line;
        for column in 0..ramp_width {
            let colour = ramp(column as f64 / (ramp_width - 1) as f64);
            canvas.rectangle(x + column, y, 1, 8 * unit, colour, 1.0);
        }
        y += 8 * unit + 2 * unit;
        canvas.text(x, y, &self.lowest, self.scale, INK);
        let highest_width = text_width(&self.highest, self.scale) as i64;
        let ramp_end = x + ramp_width.max(panel_width - 2 * pad);
        canvas.text(ramp_end - highest_width, y, &self.highest, self.scale, INK);
        y += line + line / 2;
        let middle = |y: i64| y as f64 + CAP_HEIGHT as f64 * unit as f64 / 2.0;
        for (colour, word) in &keys {
            canvas.segment(
                (x as f64, middle(y)),
                ((x + symbol) as f64, middle(y)),
                1.5,
                *colour,
            );
            canvas.text(x + symbol + 4 * unit, y, word, self.scale, INK);
            y += line;
        }
        if self.supply {
            let centre = (x + symbol / 2) as f64;
            canvas.disc(centre, middle(y), 3.5 * unit as f64, INK);
            canvas.disc(centre, middle(y), 2.5 * unit as f64, SUPPLY_COLOUR);
            canvas.text(x + symbol + 4 * unit, y, "supply", self.scale, INK);
            y += line;
        }
        canvas.text(x + symbol + 4 * unit, y, "north up", self.scale, INK);
        y += line + line / 4;
        // The bar in two halves, dark then light in a dark frame, as survey maps draw it.
        let bar_height = 4 * unit;
        canvas.rectangle(x, y, bar_px, bar_height, INK, 1.0);
        canvas.rectangle(
            x + bar_px / 2,
            y + 1,
            bar_px - bar_px / 2 - 1,
            bar_height - 2,
            PAPER,
            1.0,
        );
        let label_top = y + bar_height / 2 - (CAP_HEIGHT as i64 * unit) / 2;
        canvas.text(
            x + bar_px + 4 * unit,
            label_top,
            &bar_label,
            self.scale,
            INK,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{CoordinateSystem, Field, Obstacle};
    use crate::terrain::hillshade::hillshade;
    use crate::terrain::{Composite, Extent};
    use geo::polygon;

    fn decode(png: &[u8]) -> (usize, usize, Vec<u8>) {
        let decoder = png::Decoder::new(std::io::Cursor::new(png));
        let mut reader = decoder.read_info().unwrap();
        let mut pixels = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut pixels).unwrap();
        assert_eq!(info.color_type, png::ColorType::Rgba);
        (info.width as usize, info.height as usize, pixels)
    }

    fn farm() -> Farm {
        Farm {
            source: "test.geojson".into(),
            coordinate_system: CoordinateSystem::Local,
            fields: vec![Field::new(
                "a",
                geo::Polygon::new(
                    LineString::from(vec![
                        (200.0, 200.0),
                        (600.0, 200.0),
                        (600.0, 500.0),
                        (200.0, 500.0),
                        (200.0, 200.0),
                    ]),
                    vec![LineString::from(vec![
                        (350.0, 300.0),
                        (450.0, 300.0),
                        (450.0, 400.0),
                        (350.0, 300.0),
                    ])],
                ),
            )],
            obstacles: vec![Obstacle {
                name: "pylon".into(),
                polygon: polygon![(x: 700.0, y: 700.0), (x: 750.0, y: 700.0), (x: 750.0, y: 750.0)],
            }],
            markers: Vec::new(),
            access: Vec::new(),
            embedded_terrain: None,
            stated_swath_width_m: None,
            notes: Vec::new(),
        }
    }

    #[test]
    fn the_ramp_runs_through_its_stops() {
        assert_eq!(ramp(0.0), [74, 140, 84]);
        assert_eq!(ramp(1.0), [245, 242, 236]);
        assert_eq!(ramp(0.35), [222, 214, 128]);
        assert_eq!(ramp(-1.0), ramp(0.0));
        assert_eq!(height_tint(0.175), [148.0, 177.0, 106.0]);
        // No tint is the field blue: the outline cannot be mistaken for ground.
        assert!((0..=100).all(|step| {
            let tint = ramp(f64::from(step) / 100.0);
            tint != FIELD_COLOUR && tint != HOLE_COLOUR
        }));
    }

    #[test]
    fn fields_holes_obstacles_supply_and_legend_are_drawn_on_the_terrain() {
        let terrain = Composite::seed000();
        let extent = Extent {
            min_x: 0.0,
            min_y: 0.0,
            max_x: 1000.0,
            max_y: 800.0,
        };
        let shaded = hillshade(&terrain, extent, 500, 1.0);
        let farm = farm();
        let png = terrain_map_png(&TerrainPicture {
            terrain: &terrain,
            shaded: &shaded,
            farm: &farm,
            supply: Some(Coord { x: 100.0, y: 650.0 }),
        });
        let (width, height, pixels) = decode(&png);
        assert_eq!(
            (width, height),
            (shaded.width, shaded.height),
            "the hillshade's size"
        );
        let pixel = 1000.0 / width as f64;
        let at = |x: f64, y: f64| {
            let (column, row) = ((x / pixel) as usize, ((800.0 - y) / pixel) as usize);
            let index = (row * width + column) * 4;
            [pixels[index], pixels[index + 1], pixels[index + 2]]
        };
        let count = |colour: [u8; 3], min: (f64, f64), max: (f64, f64)| {
            let mut found = 0;
            for row in ((800.0 - max.1) / pixel) as usize..((800.0 - min.1) / pixel) as usize {
                for column in (min.0 / pixel) as usize..(max.0 / pixel) as usize {
                    let index = (row * width + column) * 4;
                    found += usize::from(pixels[index..index + 3] == colour);
                }
            }
            found
        };
        // The boundary (1400 m long, 2 m pixels) is in field blue, the hole's edge in purple.
        let boundary = count(FIELD_COLOUR, (190.0, 190.0), (610.0, 510.0));
        assert!(boundary > 2 * 700, "{boundary} field pixels");
        assert_eq!(at(200.0, 350.0), FIELD_COLOUR, "the west edge");
        assert_eq!(at(400.0, 300.0), HOLE_COLOUR, "the hole's south edge");
        assert_ne!(
            at(400.0, 250.0),
            FIELD_COLOUR,
            "inside the field, off its edges"
        );
        assert!(count(OBSTACLE_COLOUR, (690.0, 690.0), (760.0, 760.0)) > 50);
        assert_eq!(at(100.0, 650.0), SUPPLY_COLOUR);
        // The legend: the full ramp at its ends, in a pale panel, in one of the corners.
        let ramp_ends = [ramp(0.0), ramp(1.0)];
        let exact = |colour: [u8; 3]| pixels.chunks(4).filter(|p| p[..3] == colour).count();
        assert!(
            ramp_ends.iter().all(|&colour| exact(colour) >= 8),
            "the ramp is drawn"
        );
        assert!(exact(INK) > 200, "the legend's letters and the scale bar");
        // Ground is tinted, not grey.
        let ground = at(900.0, 100.0);
        assert!(
            ground[0] != ground[1] || ground[1] != ground[2],
            "{ground:?}"
        );
    }

    #[test]
    fn flat_ground_gets_the_middle_tint_and_one_height_label() {
        let terrain = crate::terrain::Flat::new(12.0);
        let extent = Extent {
            min_x: 0.0,
            min_y: 0.0,
            max_x: 900.0,
            max_y: 900.0,
        };
        let shaded = hillshade(&terrain, extent, 300, 1.0);
        let farm = farm();
        let png = terrain_map_png(&TerrainPicture {
            terrain: &terrain,
            shaded: &shaded,
            farm: &farm,
            supply: None,
        });
        let (width, _, pixels) = decode(&png);
        let light = 0.35 + 0.65 * 180.0 / 255.0;
        let expected: Vec<u8> = ramp(0.5)
            .iter()
            .map(|&c| (f64::from(c) * light).round() as u8)
            .collect();
        let index = (10 * width + width / 2) * 4;
        assert_eq!(&pixels[index..index + 3], &expected[..]);
        assert_eq!(height_label(12.0, 0.0), "12.0 m");
        assert_eq!(height_label(123.4, 50.0), "123 m");
    }
}
