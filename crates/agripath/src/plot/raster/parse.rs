//! Reading the SVG: the XML into a small element tree (quick-xml), and the value grammars
//! our writers use — path data (`M L H V Z`, absolute and relative), point lists, transforms
//! (`translate`, `scale`, `rotate`, `matrix`), colours (`#rgb`, `#rrggbb`, `rgb()`, `hsl()`,
//! `white`, `black`, `none`), lengths (plain or `px`, `%` where the caller allows it) and
//! base64. Anything outside that grammar is an error naming the value, never a guess.

use quick_xml::events::Event;
use quick_xml::Reader;
use tiny_skia::{Path, PathBuilder, Transform};

/// One SVG element: its name, its attributes in document order, and its children.
#[derive(Debug)]
pub struct Element {
    /// The element's local name (`rect`, `g`, ...).
    pub name: String,
    /// (name, value) pairs, entities resolved.
    pub attributes: Vec<(String, String)>,
    /// Child elements and text runs, in document order.
    pub children: Vec<Node>,
}

/// A child of an element.
#[derive(Debug)]
pub enum Node {
    /// A nested element.
    Element(Element),
    /// Character data, entities resolved.
    Text(String),
}

impl Element {
    /// The value of attribute `name`, if present.
    pub fn attribute(&self, name: &str) -> Option<&str> {
        self.attributes
            .iter()
            .find(|(key, _)| key == name)
            .map(|(_, value)| value.as_str())
    }

    /// The text of the element's text children, joined.
    pub fn text(&self) -> String {
        self.children
            .iter()
            .filter_map(|child| match child {
                Node::Text(text) => Some(text.as_str()),
                Node::Element(_) => None,
            })
            .collect()
    }
}

/// Elements nested deeper than this are refused (ours nest four deep).
const MAX_DEPTH: usize = 64;

/// Parses `svg` into its root element.
pub fn document(svg: &str) -> Result<Element, String> {
    let mut reader = Reader::from_str(svg);
    let mut stack: Vec<Element> = Vec::new();
    let mut root = None;
    loop {
        let position = reader.buffer_position();
        let fault = |error: &dyn std::fmt::Display| format!("{error} (at byte {position})");
        let event = reader.read_event().map_err(|error| fault(&error))?;
        let (start, empty) = match event {
            Event::Start(start) => (start, false),
            Event::Empty(start) => (start, true),
            Event::End(_) => {
                let element = stack.pop().ok_or_else(|| fault(&"unbalanced end tag"))?;
                match stack.last_mut() {
                    Some(parent) => parent.children.push(Node::Element(element)),
                    None => root = Some(element),
                }
                continue;
            }
            Event::Text(text) => {
                let decoded = text.decode().map_err(|error| fault(&error))?;
                push_text(&mut stack, &decoded);
                continue;
            }
            Event::CData(data) => {
                push_text(&mut stack, &String::from_utf8_lossy(&data));
                continue;
            }
            Event::GeneralRef(reference) => {
                let character = match reference.resolve_char_ref() {
                    Ok(Some(character)) => character,
                    _ => match &*reference as &[u8] {
                        b"amp" => '&',
                        b"lt" => '<',
                        b"gt" => '>',
                        b"quot" => '"',
                        b"apos" => '\'',
                        other => {
                            return Err(fault(&format!(
                                "unknown entity '&{};'",
                                String::from_utf8_lossy(other)
                            )))
                        }
                    },
                };
                push_text(&mut stack, &character.to_string());
                continue;
            }
            Event::DocType(_) => return Err(fault(&"a DOCTYPE is not supported")),
            Event::Eof => break,
            // The XML declaration, comments and processing instructions draw nothing.
            _ => continue,
        };
        if root.is_some() {
            return Err(fault(&"content after the root element"));
        }
        let mut attributes = Vec::new();
        for attribute in start.attributes() {
            let attribute = attribute.map_err(|error| fault(&error))?;
            let key = String::from_utf8_lossy(attribute.key.local_name().as_ref()).into_owned();
            let value = attribute
                .normalized_value(quick_xml::XmlVersion::Implicit1_0)
                .map_err(|error| fault(&error))?
                .into_owned();
            attributes.push((key, value));
        }
        let element = Element {
            name: String::from_utf8_lossy(start.local_name().as_ref()).into_owned(),
            attributes,
            children: Vec::new(),
        };
        if empty {
            match stack.last_mut() {
                Some(parent) => parent.children.push(Node::Element(element)),
                None => root = Some(element),
            }
        } else {
            stack.push(element);
            if stack.len() > MAX_DEPTH {
                return Err(fault(&format!("elements nested deeper than {MAX_DEPTH}")));
            }
        }
    }
    if !stack.is_empty() {
        return Err("the document ends inside an element".into());
    }
    let root = root.ok_or("no root element")?;
    if root.name != "svg" {
        return Err(format!("the root element is <{}>, not <svg>", root.name));
    }
    Ok(root)
}

fn push_text(stack: &mut [Element], text: &str) {
    if let Some(parent) = stack.last_mut() {
        match parent.children.last_mut() {
            Some(Node::Text(previous)) => previous.push_str(text),
            _ => parent.children.push(Node::Text(text.to_string())),
        }
    }
}

/// Reads numbers separated by whitespace and/or commas, the way SVG writes them
/// (`-8,6`, `1e-3`, `10-5` is two numbers).
struct Numbers<'a> {
    text: &'a [u8],
    at: usize,
}

impl<'a> Numbers<'a> {
    fn new(text: &'a str) -> Self {
        Numbers {
            text: text.as_bytes(),
            at: 0,
        }
    }

    fn skip_separators(&mut self) {
        while self.at < self.text.len()
            && (self.text[self.at].is_ascii_whitespace() || self.text[self.at] == b',')
        {
            self.at += 1;
        }
    }

    fn at_end(&mut self) -> bool {
        self.skip_separators();
        self.at >= self.text.len()
    }

    fn peek(&mut self) -> Option<u8> {
        self.skip_separators();
        self.text.get(self.at).copied()
    }

    fn starts_number(&mut self) -> bool {
        matches!(self.peek(), Some(b'0'..=b'9' | b'-' | b'+' | b'.'))
    }

    fn number(&mut self) -> Result<f32, String> {
        self.skip_separators();
        let start = self.at;
        let digits = |numbers: &mut Self| {
            while numbers.at < numbers.text.len() && numbers.text[numbers.at].is_ascii_digit() {
                numbers.at += 1;
            }
        };
        if matches!(self.text.get(self.at), Some(b'-' | b'+')) {
            self.at += 1;
        }
        digits(self);
        if self.text.get(self.at) == Some(&b'.') {
            self.at += 1;
            digits(self);
        }
        if matches!(self.text.get(self.at), Some(b'e' | b'E')) {
            self.at += 1;
            if matches!(self.text.get(self.at), Some(b'-' | b'+')) {
                self.at += 1;
            }
            digits(self);
        }
        let word = std::str::from_utf8(&self.text[start..self.at]).unwrap_or("");
        word.parse::<f32>()
            .ok()
            .filter(|value| value.is_finite())
            .ok_or_else(|| {
                let rest = String::from_utf8_lossy(&self.text[start..]);
                format!(
                    "expected a number at '{}'",
                    rest.chars().take(12).collect::<String>()
                )
            })
    }
}

/// Path data with the commands our writers emit: M/m, L/l, H/h, V/v, Z/z. Curves and arcs
/// are refused, so a writer that starts using them fails a test instead of losing lines.
pub fn path_data(data: &str) -> Result<Option<Path>, String> {
    let fault = |message: String| format!("path data '{}': {message}", clip_text(data));
    let mut numbers = Numbers::new(data);
    let mut builder = PathBuilder::new();
    let (mut x, mut y, mut start_x, mut start_y) = (0.0f32, 0.0f32, 0.0f32, 0.0f32);
    let mut command = None;
    while !numbers.at_end() {
        let current = match numbers.peek() {
            Some(letter) if letter.is_ascii_alphabetic() => {
                numbers.at += 1;
                letter
            }
            // Numbers after a command repeat it (after M/m, as L/l).
            Some(_) => match command {
                Some(b'M') => b'L',
                Some(b'm') => b'l',
                Some(previous) if previous != b'Z' && previous != b'z' => previous,
                _ => return Err(fault("numbers before any command".into())),
            },
            None => break,
        };
        let coordinate = |numbers: &mut Numbers| numbers.number().map_err(fault);
        let relative = current.is_ascii_lowercase();
        let (base_x, base_y) = if relative { (x, y) } else { (0.0, 0.0) };
        match current.to_ascii_uppercase() {
            b'M' => {
                x = base_x + coordinate(&mut numbers)?;
                y = base_y + coordinate(&mut numbers)?;
                builder.move_to(x, y);
                (start_x, start_y) = (x, y);
            }
            b'L' => {
                x = base_x + coordinate(&mut numbers)?;
                y = base_y + coordinate(&mut numbers)?;
                builder.line_to(x, y);
            }
            b'H' => {
                x = base_x + coordinate(&mut numbers)?;
                builder.line_to(x, y);
            }
            b'V' => {
                y = base_y + coordinate(&mut numbers)?;
                builder.line_to(x, y);
            }
            b'Z' => {
                builder.close();
                (x, y) = (start_x, start_y);
            }
            _ => {
                return Err(fault(format!(
                    "command '{}' is not supported (M L H V Z only)",
                    current as char
                )))
            }
        }
        if command.is_none() && !matches!(current, b'M' | b'm') {
            return Err(fault("does not begin with M".into()));
        }
        command = Some(current);
        if matches!(current, b'Z' | b'z') && numbers.starts_number() {
            return Err(fault("numbers after Z".into()));
        }
    }
    Ok(builder.finish())
}

/// A polyline's `points`: pairs of numbers, as an open path.
pub fn points(text: &str) -> Result<Option<Path>, String> {
    let mut numbers = Numbers::new(text);
    let mut builder = PathBuilder::new();
    while !numbers.at_end() {
        let fault = |message: String| format!("points '{}': {message}", clip_text(text));
        let x = numbers.number().map_err(fault)?;
        let y = numbers.number().map_err(fault)?;
        if builder.is_empty() {
            builder.move_to(x, y);
        } else {
            builder.line_to(x, y);
        }
    }
    Ok(builder.finish())
}

/// A list of numbers (`stroke-dasharray`, `viewBox`).
pub fn number_list(text: &str) -> Result<Vec<f32>, String> {
    let mut numbers = Numbers::new(text);
    let mut values = Vec::new();
    while !numbers.at_end() {
        values.push(numbers.number()?);
    }
    Ok(values)
}

/// A length in user units: a number, optionally `px`; with `percent_of`, `N%` is that
/// fraction of it.
pub fn length(text: &str, percent_of: Option<f32>) -> Result<f32, String> {
    let trimmed = text.trim();
    let (number, factor) = if let Some(number) = trimmed.strip_suffix('%') {
        let whole =
            percent_of.ok_or_else(|| format!("a percentage '{text}' is not supported here"))?;
        (number, whole / 100.0)
    } else {
        (trimmed.strip_suffix("px").unwrap_or(trimmed), 1.0)
    };
    number
        .parse::<f32>()
        .ok()
        .filter(|value| value.is_finite())
        .map(|value| value * factor)
        .ok_or_else(|| format!("'{text}' is not a length"))
}

/// A `transform` attribute: a list of translate/scale/rotate/matrix, applied right to left.
pub fn transform(text: &str) -> Result<Transform, String> {
    let fault = |message: &str| format!("transform '{text}': {message}");
    let mut result = Transform::identity();
    let mut rest = text.trim();
    while !rest.is_empty() {
        let open = rest.find('(').ok_or_else(|| fault("expected '('"))?;
        let close = rest.find(')').ok_or_else(|| fault("expected ')'"))?;
        let name = rest[..open].trim();
        let arguments = number_list(&rest[open + 1..close]).map_err(|error| fault(&error))?;
        let step = match (name, arguments.as_slice()) {
            ("translate", &[x]) => Transform::from_translate(x, 0.0),
            ("translate", &[x, y]) => Transform::from_translate(x, y),
            ("scale", &[s]) => Transform::from_scale(s, s),
            ("scale", &[sx, sy]) => Transform::from_scale(sx, sy),
            ("rotate", &[angle]) => Transform::from_rotate(angle),
            ("rotate", &[angle, cx, cy]) => Transform::from_rotate_at(angle, cx, cy),
            ("matrix", &[a, b, c, d, e, f]) => Transform::from_row(a, b, c, d, e, f),
            _ => return Err(fault(&format!("'{name}' with {} numbers", arguments.len()))),
        };
        result = result.pre_concat(step);
        rest = rest[close + 1..].trim_start_matches(|c: char| c.is_whitespace() || c == ',');
    }
    Ok(result)
}

/// An sRGB colour, 8 bits a channel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Colour {
    /// Red.
    pub red: u8,
    /// Green.
    pub green: u8,
    /// Blue.
    pub blue: u8,
}

/// A paint: `None` for `none`.
pub fn paint(text: &str) -> Result<Option<Colour>, String> {
    let text = text.trim();
    let fault = || format!("colour '{text}' is not supported");
    let channel = |value: f32| value.round().clamp(0.0, 255.0) as u8;
    let colour = |red, green, blue| Ok(Some(Colour { red, green, blue }));
    if let Some(hex) = text.strip_prefix('#') {
        let digit = |index: usize| {
            u8::from_str_radix(hex.get(index..index + 1).unwrap_or("x"), 16).map_err(|_| fault())
        };
        return match hex.len() {
            3 => colour(digit(0)? * 17, digit(1)? * 17, digit(2)? * 17),
            6 => colour(
                digit(0)? * 16 + digit(1)?,
                digit(2)? * 16 + digit(3)?,
                digit(4)? * 16 + digit(5)?,
            ),
            _ => Err(fault()),
        };
    }
    let arguments = |prefix: &str| -> Option<Vec<String>> {
        let inner = text.strip_prefix(prefix)?.strip_suffix(')')?;
        Some(
            inner
                .split(',')
                .map(|part| part.trim().to_string())
                .collect(),
        )
    };
    if let Some(parts) = arguments("rgb(") {
        let values: Vec<f32> = parts
            .iter()
            .map(|part| part.parse::<f32>().map_err(|_| fault()))
            .collect::<Result<_, _>>()?;
        return match values.as_slice() {
            &[red, green, blue] => colour(channel(red), channel(green), channel(blue)),
            _ => Err(fault()),
        };
    }
    if let Some(parts) = arguments("hsl(") {
        let percent = |part: &String| -> Result<f32, String> {
            let number = part.strip_suffix('%').ok_or_else(fault)?;
            number
                .parse::<f32>()
                .map(|value| value / 100.0)
                .map_err(|_| fault())
        };
        let [hue, saturation, lightness] = parts.as_slice() else {
            return Err(fault());
        };
        let hue = hue.parse::<f32>().map_err(|_| fault())?.rem_euclid(360.0) / 60.0;
        let (saturation, lightness) = (percent(saturation)?, percent(lightness)?);
        // CSS Color 3's hsl-to-rgb.
        let chroma = (1.0 - (2.0 * lightness - 1.0).abs()) * saturation;
        let second = chroma * (1.0 - (hue % 2.0 - 1.0).abs());
        let (red, green, blue) = match hue as u32 {
            0 => (chroma, second, 0.0),
            1 => (second, chroma, 0.0),
            2 => (0.0, chroma, second),
            3 => (0.0, second, chroma),
            4 => (second, 0.0, chroma),
            _ => (chroma, 0.0, second),
        };
        let lift = lightness - chroma / 2.0;
        let scale = |value: f32| channel((value + lift) * 255.0);
        return colour(scale(red), scale(green), scale(blue));
    }
    match text {
        "none" => Ok(None),
        "white" => colour(255, 255, 255),
        "black" => colour(0, 0, 0),
        _ => Err(fault()),
    }
}

/// Decodes standard base64 (with `=` padding, whitespace ignored).
pub fn base64(text: &str) -> Result<Vec<u8>, String> {
    let value = |byte: u8| -> Option<u32> {
        Some(match byte {
            b'A'..=b'Z' => byte - b'A',
            b'a'..=b'z' => byte - b'a' + 26,
            b'0'..=b'9' => byte - b'0' + 52,
            b'+' => 62,
            b'/' => 63,
            _ => return None,
        } as u32)
    };
    let symbols: Vec<u8> = text
        .bytes()
        .filter(|byte| !byte.is_ascii_whitespace())
        .collect();
    let data = symbols
        .strip_suffix(b"==")
        .or_else(|| symbols.strip_suffix(b"="))
        .unwrap_or(&symbols);
    let mut bytes = Vec::with_capacity(data.len() * 3 / 4);
    for chunk in data.chunks(4) {
        let mut group = 0u32;
        for &symbol in chunk {
            group = group << 6 | value(symbol).ok_or("invalid base64")?;
        }
        group <<= 6 * (4 - chunk.len() as u32);
        let count = match chunk.len() {
            4 => 3,
            3 => 2,
            2 => 1,
            _ => return Err("truncated base64".into()),
        };
        bytes.extend_from_slice(&group.to_be_bytes()[1..1 + count]);
    }
    Ok(bytes)
}

/// The first characters of `text`, for messages.
fn clip_text(text: &str) -> String {
    let mut clipped: String = text.chars().take(40).collect();
    if clipped.len() < text.len() {
        clipped.push('…');
    }
    clipped
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn path_data_reads_absolute_relative_and_closes() {
        let path = path_data("M10,20 l8,22 l-8,-6 L0,0 Z M1 1 2 2 H5 v3 z")
            .unwrap()
            .unwrap();
        let bounds = path.bounds();
        assert_eq!((bounds.left(), bounds.top()), (0.0, 0.0));
        assert_eq!((bounds.right(), bounds.bottom()), (18.0, 42.0));
        assert!(path_data("M0,0 C1,1 2,2 3,3").unwrap_err().contains("'C'"));
        assert!(path_data("M0,0 L1").is_err());
        assert!(path_data("L1,1").is_err());
    }

    #[test]
    fn colours_in_every_form_we_write() {
        let rgb = |red, green, blue| Some(Colour { red, green, blue });
        assert_eq!(paint("#0072B2").unwrap(), rgb(0, 0x72, 0xB2));
        assert_eq!(paint("#A33").unwrap(), rgb(0xAA, 0x33, 0x33));
        assert_eq!(paint("rgb(1,2,3)").unwrap(), rgb(1, 2, 3));
        assert_eq!(paint("hsl(120,100%,50%)").unwrap(), rgb(0, 255, 0));
        assert_eq!(paint("hsl(0.0,70%,38%)").unwrap(), rgb(165, 29, 29));
        assert_eq!(paint("none").unwrap(), None);
        assert!(paint("currentColor").is_err());
        assert!(paint("#12345").is_err());
    }

    #[test]
    fn transforms_compose_left_to_right() {
        let transform = transform("translate(18 200) rotate(-90)").unwrap();
        let mut point = [tiny_skia::Point::from_xy(10.0, 0.0)];
        transform.map_points(&mut point);
        assert!((point[0].x - 18.0).abs() < 1e-4 && (point[0].y - 190.0).abs() < 1e-4);
        assert!(super::transform("skewX(3)").is_err());
    }

    #[test]
    fn base64_round_trips_our_encoder() {
        for bytes in [&b""[..], b"a", b"ab", b"abc", b"abcd", &[0, 255, 17, 3, 9]] {
            let text = crate::plot::plan_html::base64(bytes);
            assert_eq!(base64(&text).unwrap(), bytes);
        }
    }
}
