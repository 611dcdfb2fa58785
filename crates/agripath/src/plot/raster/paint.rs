//! Drawing the element tree with tiny-skia: inherited presentation attributes, transforms,
//! clipping masks, opacity, fills and strokes (dashes, caps, joins), text outlines and
//! embedded PNG images.
//!
//! Every element and attribute is checked against the subset this file draws; anything
//! else is an error naming it, so a new SVG feature in a writer cannot silently vanish from
//! the PNG.

use std::collections::HashMap;

use tiny_skia::{
    FillRule, FilterQuality, LineCap, LineJoin, Mask, Paint, Path, PathBuilder, Pattern, Pixmap,
    PixmapPaint, Rect, SpreadMode, Stroke, StrokeDash, Transform,
};

use super::parse::{self, Colour, Element, Node};
use super::text::{self, Anchor};

/// The presentation attributes children inherit.
#[derive(Debug, Clone)]
pub struct Style {
    fill: Option<Colour>,
    fill_opacity: f32,
    fill_rule: FillRule,
    stroke: Option<Colour>,
    stroke_opacity: f32,
    stroke_width: f32,
    dash: Option<Vec<f32>>,
    line_cap: LineCap,
    line_join: LineJoin,
    font_size: f32,
    anchor: Anchor,
    stroke_first: bool,
}

impl Default for Style {
    /// SVG's initial values (font-size as usvg's default, 12).
    fn default() -> Self {
        Style {
            fill: Some(Colour {
                red: 0,
                green: 0,
                blue: 0,
            }),
            fill_opacity: 1.0,
            fill_rule: FillRule::Winding,
            stroke: None,
            stroke_opacity: 1.0,
            stroke_width: 1.0,
            dash: None,
            line_cap: LineCap::Butt,
            line_join: LineJoin::Miter,
            font_size: 12.0,
            anchor: Anchor::Start,
            stroke_first: false,
        }
    }
}

/// Attributes every drawn element may carry: the inherited ones and the few that are not.
const PRESENTATION: &[&str] = &[
    "fill",
    "fill-opacity",
    "fill-rule",
    "stroke",
    "stroke-opacity",
    "stroke-width",
    "stroke-dasharray",
    "stroke-linecap",
    "stroke-linejoin",
    "font-family",
    "font-size",
    "font-weight",
    "text-anchor",
    "paint-order",
    "opacity",
    "transform",
    "clip-path",
    // Names for people and scripts reading the SVG; they draw nothing.
    "id",
    "class",
];

/// The attributes each element reads besides [`PRESENTATION`].
fn geometry_attributes(element: &str) -> Option<&'static [&'static str]> {
    Some(match element {
        "svg" => &["xmlns", "width", "height", "viewBox"],
        "g" => &[],
        "path" => &["d"],
        "polyline" => &["points"],
        "line" => &["x1", "y1", "x2", "y2"],
        "rect" => &["x", "y", "width", "height"],
        "circle" => &["cx", "cy", "r"],
        "text" => &["x", "y"],
        "image" => &["x", "y", "width", "height", "preserveAspectRatio", "href"],
        _ => return None,
    })
}

/// The canvas being drawn on, and what the whole document shares.
pub struct Painter<'a> {
    /// The picture.
    pub pixmap: Pixmap,
    /// `clipPath` elements by id.
    clips: HashMap<&'a str, &'a Element>,
    /// The viewport in user units, for percentages.
    viewport: (f32, f32),
}

impl<'a> Painter<'a> {
    /// A transparent canvas `width` × `height` pixels for the document `root`, whose
    /// viewport is `viewport` user units.
    pub fn new(
        root: &'a Element,
        width: u32,
        height: u32,
        viewport: (f32, f32),
    ) -> Result<Self, String> {
        let pixmap = Pixmap::new(width, height).ok_or("picture too large")?;
        let mut clips = HashMap::new();
        collect_clips(root, &mut clips)?;
        Ok(Painter {
            pixmap,
            clips,
            viewport,
        })
    }

    /// Draws `element` and its children under `transform`, inheriting `parent`.
    pub fn draw(
        &mut self,
        element: &'a Element,
        parent: &Style,
        transform: Transform,
        mask: Option<&Mask>,
    ) -> Result<(), String> {
        let name = element.name.as_str();
        match name {
            // Metadata, and clip paths (drawn only where referenced).
            "title" | "desc" | "clipPath" => return Ok(()),
            _ => {}
        }
        let own =
            geometry_attributes(name).ok_or_else(|| format!("unsupported SVG element <{name}>"))?;
        for (key, _) in &element.attributes {
            if !own.contains(&key.as_str()) && !PRESENTATION.contains(&key.as_str()) {
                return Err(format!("unsupported attribute '{key}' on <{name}>"));
            }
        }
        let style = inherit(parent, element)?;
        let transform = match element.attribute("transform") {
            Some(text) => transform.pre_concat(parse::transform(text)?),
            None => transform,
        };
        let opacity = match element.attribute("opacity") {
            Some(text) => unit_number(text)?,
            None => 1.0,
        };
        let clip = match element.attribute("clip-path") {
            Some(reference) => {
                if mask.is_some() {
                    return Err("a clip-path inside a clipped element is not supported".into());
                }
                Some(self.clip_mask(reference, transform)?)
            }
            None => None,
        };
        let mask = clip.as_ref().or(mask);
        match name {
            "svg" | "g" => {
                if opacity < 1.0 {
                    return Err(format!("opacity on <{name}> is not supported"));
                }
                for child in &element.children {
                    match child {
                        Node::Element(child) => self.draw(child, &style, transform, mask)?,
                        Node::Text(text) if text.trim().is_empty() => {}
                        Node::Text(text) => {
                            return Err(format!("text '{}' outside <text>", text.trim()))
                        }
                    }
                }
                Ok(())
            }
            "image" => self.image(element, opacity, transform, mask),
            _ => {
                let Some(path) = self.shape(element, &style)? else {
                    return Ok(());
                };
                // A line has no inside to fill.
                let style = if name == "line" {
                    Style {
                        fill: None,
                        ..style
                    }
                } else {
                    style
                };
                self.fill_and_stroke(&path, &style, opacity, transform, mask)
            }
        }
    }

    /// The outline of a shape or text element, in its user units.
    fn shape(&self, element: &Element, style: &Style) -> Result<Option<Path>, String> {
        let number = |key: &str, percent_of: Option<f32>| -> Result<f32, String> {
            element
                .attribute(key)
                .map_or(Ok(0.0), |text| parse::length(text, percent_of))
                .map_err(|error| format!("<{}> {key}: {error}", element.name))
        };
        let (width, height) = self.viewport;
        Ok(match element.name.as_str() {
            "path" => parse::path_data(element.attribute("d").unwrap_or(""))?,
            "polyline" => parse::points(element.attribute("points").unwrap_or(""))?,
            "line" => {
                let mut builder = PathBuilder::new();
                builder.move_to(number("x1", None)?, number("y1", None)?);
                builder.line_to(number("x2", None)?, number("y2", None)?);
                builder.finish()
            }
            "rect" => Rect::from_xywh(
                number("x", Some(width))?,
                number("y", Some(height))?,
                number("width", Some(width))?,
                number("height", Some(height))?,
            )
            .map(PathBuilder::from_rect),
            "circle" => PathBuilder::from_circle(
                number("cx", None)?,
                number("cy", None)?,
                number("r", None)?,
            ),
            "text" => {
                if element
                    .children
                    .iter()
                    .any(|child| matches!(child, Node::Element(_)))
                {
                    return Err("elements inside <text> (tspan, ...) are not supported".into());
                }
                let content = text::collapse_white_space(&element.text());
                text::outlines(
                    &content,
                    number("x", None)?,
                    number("y", None)?,
                    style.font_size,
                    style.anchor,
                )?
            }
            other => return Err(format!("unsupported SVG element <{other}>")),
        })
    }

    /// Fills and strokes `path` in the order `paint-order` gives; with both and `opacity`
    /// below one, through a layer, so the stroke does not show through the fill.
    fn fill_and_stroke(
        &mut self,
        path: &Path,
        style: &Style,
        opacity: f32,
        transform: Transform,
        mask: Option<&Mask>,
    ) -> Result<(), String> {
        let both = style.fill.is_some() && style.stroke.is_some() && style.stroke_width > 0.0;
        if both && opacity < 1.0 {
            let mut layer = Painter {
                pixmap: Pixmap::new(self.pixmap.width(), self.pixmap.height())
                    .ok_or("picture too large")?,
                clips: HashMap::new(),
                viewport: self.viewport,
            };
            layer.fill_and_stroke(path, style, 1.0, transform, None)?;
            let paint = PixmapPaint {
                opacity,
                ..PixmapPaint::default()
            };
            self.pixmap.draw_pixmap(
                0,
                0,
                layer.pixmap.as_ref(),
                &paint,
                Transform::identity(),
                mask,
            );
            return Ok(());
        }
        let paint_of = |colour: Colour, alpha: f32| {
            let mut paint = Paint::default();
            paint.set_color_rgba8(
                colour.red,
                colour.green,
                colour.blue,
                (alpha * 255.0).round().clamp(0.0, 255.0) as u8,
            );
            paint.anti_alias = true;
            paint
        };
        let fill = |pixmap: &mut Pixmap| {
            if let Some(colour) = style.fill {
                let paint = paint_of(colour, style.fill_opacity * opacity);
                pixmap.fill_path(path, &paint, style.fill_rule, transform, mask);
            }
        };
        let stroke = |pixmap: &mut Pixmap| -> Result<(), String> {
            let Some(colour) = style.stroke else {
                return Ok(());
            };
            if style.stroke_width <= 0.0 {
                return Ok(());
            }
            let dash = match &style.dash {
                // An odd list is repeated to make it even (SVG's rule).
                Some(list) if list.len() % 2 == 1 => StrokeDash::new(list.repeat(2), 0.0),
                Some(list) => StrokeDash::new(list.clone(), 0.0),
                None => None,
            };
            if style.dash.is_some() && dash.is_none() {
                return Err(format!("stroke-dasharray {:?} is not drawable", style.dash));
            }
            let stroke = Stroke {
                width: style.stroke_width,
                line_cap: style.line_cap,
                line_join: style.line_join,
                dash,
                ..Stroke::default()
            };
            let paint = paint_of(colour, style.stroke_opacity * opacity);
            pixmap.stroke_path(path, &paint, &stroke, transform, mask);
            Ok(())
        };
        if style.stroke_first {
            stroke(&mut self.pixmap)?;
            fill(&mut self.pixmap);
        } else {
            fill(&mut self.pixmap);
            stroke(&mut self.pixmap)?;
        }
        Ok(())
    }

    /// An `<image>`: an embedded PNG stretched over its box (`preserveAspectRatio="none"`),
    /// sampled bicubically as resvg does for `image-rendering: optimizeQuality`.
    fn image(
        &mut self,
        element: &Element,
        opacity: f32,
        transform: Transform,
        mask: Option<&Mask>,
    ) -> Result<(), String> {
        if element.attribute("preserveAspectRatio") != Some("none") {
            return Err(
                "<image> needs preserveAspectRatio=\"none\" (the only one supported)".into(),
            );
        }
        let href = element.attribute("href").unwrap_or("");
        let data = href
            .strip_prefix("data:image/png;base64,")
            .ok_or("<image> href must be a base64 PNG data URL")?;
        let picture = decode_png(&parse::base64(data)?)?;
        let number = |key: &str| {
            element
                .attribute(key)
                .map_or(Ok(0.0), |text| parse::length(text, None))
        };
        let (x, y, width, height) = (
            number("x")?,
            number("y")?,
            number("width")?,
            number("height")?,
        );
        if width <= 0.0 || height <= 0.0 {
            return Ok(());
        }
        let (picture_width, picture_height) = (picture.width() as f32, picture.height() as f32);
        let placement = transform
            .pre_translate(x, y)
            .pre_scale(width / picture_width, height / picture_height);
        let paint = Paint {
            shader: Pattern::new(
                picture.as_ref(),
                SpreadMode::Pad,
                // Bilinear: the pictures are hillshades scaled up smoothly; bicubic cost an eighth of
                // the demo's whole run for no difference one sees at map scale.
                FilterQuality::Bilinear,
                opacity,
                Transform::identity(),
            ),
            ..Paint::default()
        };
        let area = Rect::from_xywh(0.0, 0.0, picture_width, picture_height).ok_or("empty image")?;
        self.pixmap.fill_rect(area, &paint, placement, mask);
        Ok(())
    }

    /// The coverage mask of `clip-path="url(#id)"`: its shapes filled under `transform`.
    fn clip_mask(&self, reference: &str, transform: Transform) -> Result<Mask, String> {
        let id = reference
            .trim()
            .strip_prefix("url(#")
            .and_then(|rest| rest.strip_suffix(')'))
            .ok_or_else(|| format!("clip-path '{reference}' is not url(#id)"))?;
        let clip = self
            .clips
            .get(id)
            .ok_or_else(|| format!("clip-path '#{id}' names no <clipPath>"))?;
        let mut mask =
            Mask::new(self.pixmap.width(), self.pixmap.height()).ok_or("picture too large")?;
        for child in &clip.children {
            let Node::Element(shape) = child else {
                continue;
            };
            if !matches!(shape.name.as_str(), "rect" | "path" | "circle") {
                return Err(format!(
                    "<{}> inside <clipPath> is not supported",
                    shape.name
                ));
            }
            let own = geometry_attributes(&shape.name).unwrap_or(&[]);
            for (key, _) in &shape.attributes {
                if !own.contains(&key.as_str()) && !["id", "class"].contains(&key.as_str()) {
                    return Err(format!(
                        "unsupported attribute '{key}' on <{}> in <clipPath>",
                        shape.name
                    ));
                }
            }
            if let Some(path) = self.shape(shape, &Style::default())? {
                mask.fill_path(&path, FillRule::Winding, true, transform);
            }
        }
        Ok(mask)
    }
}

fn collect_clips<'a>(
    element: &'a Element,
    clips: &mut HashMap<&'a str, &'a Element>,
) -> Result<(), String> {
    for child in &element.children {
        if let Node::Element(child) = child {
            if child.name == "clipPath" {
                for (key, _) in &child.attributes {
                    if key != "id" {
                        return Err(format!("unsupported attribute '{key}' on <clipPath>"));
                    }
                }
                let id = child.attribute("id").ok_or("a <clipPath> without an id")?;
                clips.insert(id, child);
            } else {
                collect_clips(child, clips)?;
            }
        }
    }
    Ok(())
}

/// A number in [0, 1] (opacities).
fn unit_number(text: &str) -> Result<f32, String> {
    text.trim()
        .parse::<f32>()
        .ok()
        .filter(|value| value.is_finite())
        .map(|value| value.clamp(0.0, 1.0))
        .ok_or_else(|| format!("'{text}' is not an opacity"))
}

/// `parent`'s style with `element`'s presentation attributes applied.
fn inherit(parent: &Style, element: &Element) -> Result<Style, String> {
    let mut style = parent.clone();
    for (key, value) in &element.attributes {
        let fault = |what: &str| format!("{key} '{value}' on <{}>: {what}", element.name);
        let trimmed = value.trim();
        match key.as_str() {
            "fill" => style.fill = parse::paint(value)?,
            "stroke" => style.stroke = parse::paint(value)?,
            "fill-opacity" => style.fill_opacity = unit_number(value)?,
            "stroke-opacity" => style.stroke_opacity = unit_number(value)?,
            "stroke-width" => style.stroke_width = parse::length(value, None)?,
            "font-size" => style.font_size = parse::length(value, None)?,
            "text-anchor" => style.anchor = Anchor::parse(value)?,
            "fill-rule" => {
                style.fill_rule = match trimmed {
                    "nonzero" => FillRule::Winding,
                    "evenodd" => FillRule::EvenOdd,
                    _ => return Err(fault("not nonzero or evenodd")),
                }
            }
            "stroke-dasharray" => {
                style.dash = match trimmed {
                    "none" => None,
                    _ => Some(parse::number_list(value).map_err(|error| fault(&error))?),
                }
            }
            "stroke-linecap" => {
                style.line_cap = match trimmed {
                    "butt" => LineCap::Butt,
                    "round" => LineCap::Round,
                    "square" => LineCap::Square,
                    _ => return Err(fault("not butt, round or square")),
                }
            }
            "stroke-linejoin" => {
                style.line_join = match trimmed {
                    "miter" => LineJoin::Miter,
                    "round" => LineJoin::Round,
                    "bevel" => LineJoin::Bevel,
                    _ => return Err(fault("not miter, round or bevel")),
                }
            }
            "paint-order" => {
                style.stroke_first = match trimmed {
                    "normal" | "fill" | "fill stroke" => false,
                    "stroke" | "stroke fill" => true,
                    _ => return Err(fault("not normal or stroke")),
                }
            }
            // Every family is the embedded DejaVu Sans (see text.rs).
            "font-family" => {}
            // Drawn regular: no bold face is shipped (see text.rs).
            "font-weight" if !matches!(trimmed, "normal" | "bold" | "400" | "700") => {
                return Err(fault("not normal or bold"));
            }
            _ => {}
        }
    }
    Ok(style)
}

/// Decodes a PNG into a premultiplied tiny-skia pixmap (8-bit grey, grey + alpha, RGB, RGBA;
/// palettes and 16-bit channels are expanded to those).
fn decode_png(bytes: &[u8]) -> Result<Pixmap, String> {
    let fault = |error: &dyn std::fmt::Display| format!("embedded PNG: {error}");
    let mut decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    decoder.set_transformations(png::Transformations::normalize_to_color8());
    let mut reader = decoder.read_info().map_err(|error| fault(&error))?;
    let mut buffer = vec![
        0;
        reader
            .output_buffer_size()
            .ok_or_else(|| fault(&"too large"))?
    ];
    let frame = reader
        .next_frame(&mut buffer)
        .map_err(|error| fault(&error))?;
    let channels = frame.color_type.samples();
    let mut pixmap = Pixmap::new(frame.width, frame.height).ok_or_else(|| fault(&"empty"))?;
    let rows = buffer.chunks(frame.line_size).take(frame.height as usize);
    let pixels = rows.flat_map(|row| row[..frame.width as usize * channels].chunks(channels));
    for (target, source) in pixmap.data_mut().chunks_mut(4).zip(pixels) {
        let [red, green, blue, alpha] = match *source {
            [grey] => [grey, grey, grey, 255],
            [grey, alpha] => [grey, grey, grey, alpha],
            [red, green, blue] => [red, green, blue, 255],
            [red, green, blue, alpha] => [red, green, blue, alpha],
            _ => return Err(fault(&"unexpected channel count")),
        };
        // Premultiplied, rounded as resvg's decoder did.
        let scale = |channel: u8| (f64::from(channel) * f64::from(alpha) / 255.0 + 0.5) as u8;
        target.copy_from_slice(&[scale(red), scale(green), scale(blue), alpha]);
    }
    Ok(pixmap)
}
