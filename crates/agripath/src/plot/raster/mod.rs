//! SVG → PNG for the maps and charts (`plan.png`, `top_view.png`, the convergence PNGs of
//! `repro`): our own renderer of the SVG subset our writers emit, drawn with tiny-skia (the
//! rasteriser resvg used, so anti-aliasing, strokes, dashes and clipping look the same) and
//! DejaVu Sans outlines read with ttf-parser. resvg parsed all of SVG, CSS and text shaping
//! for three pictures and cost a quarter of a release build (decision 0024).
//!
//! The subset: `svg` (width, height, viewBox: uniform scale), `g`, `path` (M L H V Z), `polyline`,
//! `line`, `rect` (lengths or `%`), `circle`, `text` (one line, text-anchor, font-size,
//! `transform`), `image` (base64 PNG, `preserveAspectRatio="none"`), `clipPath` (rect, path,
//! circle) referenced by `clip-path`, `title`; fill, stroke, their opacities, `opacity`,
//! fill-rule, stroke-width, dasharray, linecap, linejoin, paint-order, transforms. Any other
//! element, attribute or value is an error naming it (see `paint.rs`).

mod paint;
mod parse;
mod text;

use tiny_skia::Transform;

/// Renders `svg` to a PNG `width_px` wide (height in proportion).
pub fn svg_to_png(svg: &str, width_px: u32) -> Result<Vec<u8>, String> {
    let root = parse::document(svg)?;
    let size = |key: &str| {
        root.attribute(key)
            .map(|text| parse::length(text, None))
            .transpose()
    };
    let view_box = root
        .attribute("viewBox")
        .map(parse::number_list)
        .transpose()?;
    let (width, height, user_to_viewport) =
        match (size("width")?, size("height")?, view_box.as_deref()) {
            (Some(width), Some(height), None) => (width, height, Transform::identity()),
            (width, height, Some(view)) => {
                let &[min_x, min_y, view_width, view_height] = view else {
                    return Err("viewBox needs four numbers".into());
                };
                if view_width <= 0.0 || view_height <= 0.0 {
                    return Err("viewBox has no area".into());
                }
                let (width, height) = (width.unwrap_or(view_width), height.unwrap_or(view_height));
                let (scale_x, scale_y) = (width / view_width, height / view_height);
                // Our writers give the viewBox the picture's own proportions; preserveAspectRatio's
                // letterboxing is not implemented.
                if (scale_x - scale_y).abs() > 1e-3 * scale_x.max(scale_y) {
                    return Err("a viewBox with other proportions than width × height".into());
                }
                let transform =
                    Transform::from_scale(scale_x, scale_y).pre_translate(-min_x, -min_y);
                (width, height, transform)
            }
            _ => return Err("<svg> needs width and height, or a viewBox".into()),
        };
    if width <= 0.0 || height <= 0.0 {
        return Err("<svg> has no area".into());
    }
    let scale = width_px as f32 / width;
    let height_px = (height * scale).ceil().max(1.0) as u32;
    let viewport = match &view_box {
        Some(view) => (view[2], view[3]),
        None => (width, height),
    };
    let mut painter = paint::Painter::new(&root, width_px.max(1), height_px, viewport)?;
    let transform = Transform::from_scale(scale, scale).pre_concat(user_to_viewport);
    painter.draw(&root, &paint::Style::default(), transform, None)?;
    // PNG stores straight (not premultiplied) alpha.
    let pixels: Vec<u8> = painter
        .pixmap
        .pixels()
        .iter()
        .flat_map(|pixel| {
            let colour = pixel.demultiply();
            [colour.red(), colour.green(), colour.blue(), colour.alpha()]
        })
        .collect();
    Ok(crate::terrain::hillshade::encode_png(
        painter.pixmap.width() as usize,
        painter.pixmap.height() as usize,
        png::ColorType::Rgba,
        &pixels,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The picture as (width, RGBA pixels).
    fn render(svg: &str, width_px: u32) -> (usize, Vec<u8>) {
        let png = svg_to_png(svg, width_px).unwrap();
        let decoder = png::Decoder::new(std::io::Cursor::new(png));
        let mut reader = decoder.read_info().unwrap();
        let mut pixels = vec![0; reader.output_buffer_size().unwrap()];
        let frame = reader.next_frame(&mut pixels).unwrap();
        assert_eq!(frame.color_type, png::ColorType::Rgba);
        (frame.width as usize, pixels)
    }

    fn pixel(picture: &(usize, Vec<u8>), x: usize, y: usize) -> [u8; 4] {
        let at = 4 * (y * picture.0 + x);
        picture.1[at..at + 4].try_into().unwrap()
    }

    fn document(width: u32, height: u32, body: &str) -> String {
        format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}">{body}</svg>"#
        )
    }

    #[test]
    fn text_and_shapes_are_drawn() {
        let svg = r##"<svg xmlns="http://www.w3.org/2000/svg" width="100" height="40"><rect width="100" height="40" fill="white"/><text x="5" y="30" font-size="24" font-family="Helvetica, sans-serif">Ag</text></svg>"##;
        let png = svg_to_png(svg, 100).unwrap();
        let decoder = png::Decoder::new(std::io::Cursor::new(png));
        let mut reader = decoder.read_info().unwrap();
        let mut pixels = vec![0; reader.output_buffer_size().unwrap()];
        reader.next_frame(&mut pixels).unwrap();
        let dark = pixels.chunks(4).filter(|p| p[0] < 100).count();
        assert!(dark > 20, "the text drew {dark} dark pixels");
    }

    #[test]
    fn a_polygon_with_a_hole_fills_only_the_ring() {
        let svg = document(
            50,
            50,
            r##"<path d="M0,0 L40,0 L40,40 L0,40 Z M10,10 L30,10 L30,30 L10,30 Z" fill="#ff0000" fill-rule="evenodd"/>"##,
        );
        let picture = render(&svg, 100);
        assert_eq!(pixel(&picture, 10, 10), [255, 0, 0, 255], "the ring");
        assert_eq!(pixel(&picture, 40, 40)[3], 0, "the hole");
        assert_eq!(pixel(&picture, 90, 90)[3], 0, "outside");
        // Twice the size: the right edge of the ring at x = 80 px.
        assert_eq!(pixel(&picture, 78, 40), [255, 0, 0, 255]);
        assert_eq!(pixel(&picture, 82, 40)[3], 0);
        // Without evenodd the hole fills (both rings turn the same way).
        let filled = render(&svg.replace(r#" fill-rule="evenodd""#, ""), 100);
        assert_eq!(pixel(&filled, 40, 40), [255, 0, 0, 255]);
    }

    #[test]
    fn dashes_alternate_and_opacity_blends() {
        let svg = document(
            100,
            20,
            r##"<rect width="100%" height="100%" fill="white"/><line x1="0" y1="10" x2="100" y2="10" stroke="#000" stroke-width="4" stroke-dasharray="10 10"/><g stroke-opacity="0.5"><path d="M0,18 H100" stroke="#000" stroke-width="2"/></g>"##,
        );
        let picture = render(&svg, 100);
        for x in [2, 5, 8, 22, 25, 45, 85] {
            assert_eq!(pixel(&picture, x, 10), [0, 0, 0, 255], "dash at {x}");
        }
        for x in [12, 15, 18, 35, 55, 95] {
            assert_eq!(pixel(&picture, x, 10), [255, 255, 255, 255], "gap at {x}");
        }
        let half = pixel(&picture, 50, 17);
        assert!((125..=130).contains(&half[0]) && half[3] == 255, "{half:?}");
    }

    #[test]
    fn text_is_drawn_where_anchored_and_rotated() {
        let svg = document(
            200,
            100,
            r##"<text x="100" y="50" font-size="30" text-anchor="end" fill="#00f">HH</text><text transform="translate(150 90) rotate(-90)" font-size="20">HH</text>"##,
        );
        let picture = render(&svg, 200);
        let inked = |x0: usize, x1: usize, y0: usize, y1: usize| {
            (y0..y1)
                .flat_map(|y| (x0..x1).map(move |x| (x, y)))
                .filter(|&(x, y)| pixel(&picture, x, y)[3] > 128)
                .count()
        };
        // "HH" at 30 px is about 45 px wide, ending at x = 100, cap height about 22 px.
        assert!(inked(55, 100, 28, 50) > 200, "the run left of its end");
        assert_eq!(inked(101, 140, 0, 60), 0, "nothing right of the end anchor");
        // The H's stem: solid blue.
        let stem = (55..75)
            .map(|x| pixel(&picture, x, 40))
            .find(|p| p[3] > 200);
        assert!(
            stem.is_some_and(|p| p[0] == 0 && p[1] == 0 && p[2] >= 250),
            "{stem:?}"
        );
        // Rotated: the run goes up from (150, 90), so it is tall and narrow, left of x = 150.
        assert!(inked(130, 151, 55, 91) > 80, "rotated text");
        assert_eq!(inked(155, 200, 0, 100), 0);
    }

    #[test]
    fn an_embedded_image_is_stretched_clipped_and_faded() {
        // 8 × 8 in quadrants: red, green / blue, white.
        let quadrant = |x: usize, y: usize| match (x < 4, y < 4) {
            (true, true) => [255, 0, 0],
            (false, true) => [0, 255, 0],
            (true, false) => [0, 0, 255],
            (false, false) => [255, 255, 255],
        };
        let pixels: Vec<u8> = (0..64).flat_map(|at| quadrant(at % 8, at / 8)).collect();
        let png = crate::terrain::hillshade::encode_png(8, 8, png::ColorType::Rgb, &pixels);
        let href = crate::plot::plan_html::base64(&png);
        let svg = document(
            80,
            80,
            &format!(
                r##"<clipPath id="c"><rect x="0" y="0" width="80" height="70"/></clipPath><image clip-path="url(#c)" x="0" y="0" width="80" height="80" preserveAspectRatio="none" href="data:image/png;base64,{href}"/><image x="0" y="72" width="8" height="8" opacity="0.5" preserveAspectRatio="none" href="data:image/png;base64,{href}"/>"##
            ),
        );
        let picture = render(&svg, 80);
        let near = |found: [u8; 4], wanted: [u8; 4]| {
            let close = found.iter().zip(wanted).all(|(a, b)| a.abs_diff(b) <= 2);
            assert!(close, "{found:?} is not {wanted:?}");
        };
        near(pixel(&picture, 60, 10), [0, 255, 0, 255]);
        near(pixel(&picture, 10, 62), [0, 0, 255, 255]);
        near(pixel(&picture, 60, 62), [255, 255, 255, 255]);
        assert_eq!(pixel(&picture, 60, 75)[3], 0, "clipped below y = 70");
        near(pixel(&picture, 2, 74), [255, 0, 0, 128]);
    }

    #[test]
    fn unsupported_svg_is_an_error_not_a_gap() {
        let error = |body: &str| svg_to_png(&document(10, 10, body), 10).unwrap_err();
        assert!(error("<ellipse rx='1' ry='2'/>").contains("<ellipse>"));
        assert!(error("<rect width='5' height='5' rx='1'/>").contains("'rx'"));
        assert!(error("<path d='M0,0 Q1,1 2,2'/>").contains("'Q'"));
        assert!(error("<text>a<tspan>b</tspan></text>").contains("tspan"));
        assert!(error("<rect width='5' height='5' fill='url(#g)'/>").contains("url(#g)"));
        assert!(error("<g opacity='0.5'/>").contains("opacity"));
        assert!(error("<rect width='5' height='5' clip-path='url(#none)'/>").contains("#none"));
        assert!(error("<image width='5' height='5' href='a.png'/>").contains("preserveAspectRatio"));
        assert!(svg_to_png("<svg width='4' height='4'><title>t</title></svg>", 4).is_ok());
        assert!(svg_to_png("<html/>", 4).unwrap_err().contains("<html>"));
        assert!(svg_to_png("<svg width='4'>", 4).is_err());
    }
}
