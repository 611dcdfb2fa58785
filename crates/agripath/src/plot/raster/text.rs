//! Text as outlines: DejaVu Sans (compiled in, `assets/fonts/`, licence beside it), read with
//! ttf-parser, so a picture looks the same on every machine whatever fonts it has.
//!
//! Layout is one line, left to right: each character's glyph from the font's cmap, advanced
//! by its hmtx width. No shaping and no kerning (resvg's rustybuzz applied DejaVu's kerning
//! pairs, moving some letters by a fraction of a pixel at our sizes); every `font-family`
//! is DejaVu Sans, and `font-weight: bold` is drawn regular because we ship no bold face
//! (resvg, given the same single face, drew it regular as well).

use std::sync::OnceLock;

use tiny_skia::{Path, PathBuilder};
use ttf_parser::{Face, GlyphId, OutlineBuilder};

const DEJAVU_SANS: &[u8] = include_bytes!("../../../assets/fonts/DejaVuSans.ttf");

fn face() -> Result<&'static Face<'static>, String> {
    static FACE: OnceLock<Option<Face<'static>>> = OnceLock::new();
    FACE.get_or_init(|| Face::parse(DEJAVU_SANS, 0).ok())
        .as_ref()
        .ok_or_else(|| "the embedded DejaVu Sans does not parse".to_string())
}

/// Where a run of text stands relative to its `x`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Anchor {
    /// `x` is the start.
    Start,
    /// `x` is the middle.
    Middle,
    /// `x` is the end.
    End,
}

impl Anchor {
    /// Reads `text-anchor`.
    pub fn parse(text: &str) -> Result<Self, String> {
        match text.trim() {
            "start" => Ok(Anchor::Start),
            "middle" => Ok(Anchor::Middle),
            "end" => Ok(Anchor::End),
            other => Err(format!("text-anchor '{other}' is not supported")),
        }
    }
}

/// Collapses white space as SVG does without `xml:space`: line breaks and tabs become
/// spaces, runs of spaces one, and the ends are trimmed.
pub fn collapse_white_space(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// Feeds glyph outlines (font units, y up) into one path in user units (y down), each glyph
/// moved to its pen position.
struct Outline {
    builder: PathBuilder,
    scale: f32,
    origin_x: f32,
    origin_y: f32,
}

impl Outline {
    fn at(&self, x: f32, y: f32) -> (f32, f32) {
        (
            self.origin_x + x * self.scale,
            self.origin_y - y * self.scale,
        )
    }
}

impl OutlineBuilder for Outline {
    fn move_to(&mut self, x: f32, y: f32) {
        let (x, y) = self.at(x, y);
        self.builder.move_to(x, y);
    }

    fn line_to(&mut self, x: f32, y: f32) {
        let (x, y) = self.at(x, y);
        self.builder.line_to(x, y);
    }

    fn quad_to(&mut self, x1: f32, y1: f32, x: f32, y: f32) {
        let (x1, y1) = self.at(x1, y1);
        let (x, y) = self.at(x, y);
        self.builder.quad_to(x1, y1, x, y);
    }

    fn curve_to(&mut self, x1: f32, y1: f32, x2: f32, y2: f32, x: f32, y: f32) {
        let (x1, y1) = self.at(x1, y1);
        let (x2, y2) = self.at(x2, y2);
        let (x, y) = self.at(x, y);
        self.builder.cubic_to(x1, y1, x2, y2, x, y);
    }

    fn close(&mut self) {
        self.builder.close();
    }
}

/// The outlines of `text` (already collapsed) set at `font_size` with its baseline at
/// (`x`, `y`), placed by `anchor`; `None` when nothing has ink (spaces only).
pub fn outlines(
    text: &str,
    x: f32,
    y: f32,
    font_size: f32,
    anchor: Anchor,
) -> Result<Option<Path>, String> {
    let face = face()?;
    let scale = font_size / f32::from(face.units_per_em());
    let glyphs: Vec<GlyphId> = text
        .chars()
        // A character the font lacks draws its .notdef box, as resvg's did.
        .map(|character| face.glyph_index(character).unwrap_or(GlyphId(0)))
        .collect();
    let advance = |glyph: GlyphId| f32::from(face.glyph_hor_advance(glyph).unwrap_or(0)) * scale;
    let width: f32 = glyphs.iter().map(|&glyph| advance(glyph)).sum();
    let mut pen = match anchor {
        Anchor::Start => x,
        Anchor::Middle => x - width / 2.0,
        Anchor::End => x - width,
    };
    let mut outline = Outline {
        builder: PathBuilder::new(),
        scale,
        origin_x: pen,
        origin_y: y,
    };
    for glyph in glyphs {
        outline.origin_x = pen;
        face.outline_glyph(glyph, &mut outline);
        pen += advance(glyph);
    }
    Ok(outline.builder.finish())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn anchors_place_the_run_and_spaces_collapse() {
        assert_eq!(collapse_white_space("  a \n  b\tc "), "a b c");
        let start = outlines("Ag", 100.0, 50.0, 20.0, Anchor::Start)
            .unwrap()
            .unwrap()
            .bounds();
        let end = outlines("Ag", 100.0, 50.0, 20.0, Anchor::End)
            .unwrap()
            .unwrap()
            .bounds();
        assert!(start.left() >= 100.0 && start.left() < 101.0, "{start:?}");
        assert!(end.right() <= 100.0 && end.right() > 97.0, "{end:?}");
        // "g" descends below the baseline, "A" reaches about three quarters of the size up.
        assert!(start.bottom() > 50.0 && start.top() < 50.0 - 0.7 * 20.0);
        assert!(outlines("  ", 0.0, 0.0, 12.0, Anchor::Start)
            .unwrap()
            .is_none());
    }
}
