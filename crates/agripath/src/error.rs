//! Typed errors for everything a user hands to agripath.
//!
//! Every fault in an input is an [`InputError`]: the file it came from, where in the file
//! (a feature, a key, a pixel), and the [`Fault`]. Its `Display` is the one line the CLI
//! prints before exiting with status 2.

use std::fmt;
use std::path::{Path, PathBuf};

/// A fault in one input file (or command-line value), with its place.
#[derive(Debug, thiserror::Error)]
pub struct InputError {
    /// The file (or `--flag`) the fault was found in.
    pub file: PathBuf,
    /// Where in the file, when known: "feature 3 (S4)", "row 12", "key vehicle.swath_width_m".
    pub place: Option<String>,
    /// What is wrong.
    pub fault: Fault,
}

impl fmt::Display for InputError {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(formatter, "{}", self.file.display())?;
        // A TOML fault's line and column as compilers print them, `file:line:column:`, so
        // editors and terminals jump to it.
        if let Fault::Toml {
            line_column: Some((line, column)),
            ..
        } = self.fault
        {
            write!(formatter, ":{line}:{column}")?;
        }
        if let Some(place) = &self.place {
            write!(formatter, ": {place}")?;
        }
        write!(formatter, ": {}", self.fault)
    }
}

impl InputError {
    /// A fault in `file`, with no place yet (add one with [`InputError::at`]).
    pub fn new(file: impl AsRef<Path>, fault: Fault) -> Self {
        Self {
            file: file.as_ref().to_path_buf(),
            place: None,
            fault,
        }
    }

    /// A TOML file `file` that does not parse (or holds a value of the wrong type), placed
    /// at the line and column where the parser's span begins in `text`, the file's text.
    pub fn toml(file: impl AsRef<Path>, error: &toml::de::Error, text: &str) -> Self {
        let line_column = error
            .span()
            .filter(|span| span.start <= text.len())
            .map(|span| line_column(text, span.start));
        Self::new(
            file,
            Fault::Toml {
                message: toml_message(error),
                line_column: line_column.map(|(line, column)| {
                    (
                        u32::try_from(line).unwrap_or(u32::MAX),
                        u32::try_from(column).unwrap_or(u32::MAX),
                    )
                }),
            },
        )
    }

    /// Adds (or prefixes) the place in the file where the fault lies.
    pub fn at(mut self, place: impl Into<String>) -> Self {
        let place = place.into();
        self.place = Some(match self.place.take() {
            Some(inner) => format!("{place}: {inner}"),
            None => place,
        });
        self
    }
}

/// The TOML parser's message in one line (it may span several). A misspelt key, which serde
/// reports as "unknown field `x`, expected one of …", is said in the operator's words: the
/// key, the nearest valid one, and the valid keys.
pub(crate) fn toml_message(error: &toml::de::Error) -> String {
    let message = error.message().trim().replace('\n', " ");
    unknown_key_message(&message).unwrap_or(format!("not valid TOML: {message}"))
}

/// "unknown key `tanc_l` (did you mean `tank_l`?); the keys are name, …" from serde's
/// "unknown field `tanc_l`, expected one of `name`, …" (or "expected `name`" for one key).
fn unknown_key_message(message: &str) -> Option<String> {
    let rest = message.strip_prefix("unknown field `")?;
    let (key, expected) = rest.split_once('`')?;
    let keys: Vec<&str> = expected
        .split('`')
        .skip(1)
        .step_by(2)
        .filter(|name| !name.is_empty())
        .collect();
    if keys.is_empty() {
        return None;
    }
    let nearest = keys
        .iter()
        .map(|name| (edit_distance(key, name), *name))
        .min()
        .filter(|(distance, _)| *distance <= key.chars().count().div_ceil(3).max(2))
        .map(|(_, name)| format!(" (did you mean `{name}`?)"))
        .unwrap_or_default();
    Some(format!(
        "unknown key `{key}`{nearest}; the keys are {}",
        keys.join(", ")
    ))
}

/// Levenshtein distance between two words, in characters.
fn edit_distance(first: &str, second: &str) -> usize {
    let second: Vec<char> = second.chars().collect();
    let mut previous: Vec<usize> = (0..=second.len()).collect();
    for (row, letter) in first.chars().enumerate() {
        let mut current = vec![row + 1; second.len() + 1];
        for (column, other) in second.iter().enumerate() {
            let replace = previous[column] + usize::from(letter != *other);
            current[column + 1] = replace
                .min(previous[column + 1] + 1)
                .min(current[column] + 1);
        }
        previous = current;
    }
    previous[second.len()]
}

/// Line and column, both counted from 1 (columns in characters), of byte `offset` of
/// `text`; an offset inside a character counts as that character.
pub(crate) fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let mut end = offset.min(text.len());
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    let before = &text[..end];
    let line = before.matches('\n').count() + 1;
    let column = before
        .rsplit('\n')
        .next()
        .map_or(0, |tail| tail.chars().count())
        + 1;
    (line, column)
}

/// What is wrong with an input.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Fault {
    /// The file cannot be read (missing, a folder, a special file, an I/O error); the reason.
    #[error("cannot read the file: {0}")]
    Unreadable(String),
    /// The file is empty or holds only whitespace.
    #[error("the file is empty")]
    Empty,
    /// The text is not JSON; the parser's message.
    #[error("not valid JSON: {0}")]
    Json(String),
    /// The text is not TOML (or a value has the wrong type); the parser's message in one line.
    #[error("{message}")]
    Toml {
        /// What the parser says, in one line: "not valid TOML: …", or "unknown key …".
        message: String,
        /// Line and column in the file, both from 1 (columns in characters), when the parser
        /// gives a place: [`InputError`] prints them `file:line:column`.
        line_column: Option<(u32, u32)>,
    },
    /// The text is not KML agripath can read; the reason.
    #[error("not valid KML: {0}")]
    Kml(String),
    /// The file is not a GeoTIFF agripath can read; the reason.
    #[error("not a readable GeoTIFF: {0}")]
    Tiff(String),
    /// The file's extension (lower case) chooses no reader for what the file was given as.
    #[error("unsupported file type '{extension}' for {role} (expected {expected})")]
    UnknownExtension {
        /// The extension, lower case.
        extension: String,
        /// What the file was given as: "fields" or "terrain".
        role: &'static str,
        /// The extensions read for that role, in words.
        expected: &'static str,
    },
    /// The file parses but its structure is not what the format requires.
    #[error("{0}")]
    Structure(String),
    /// A coordinate is NaN or infinite.
    #[error("coordinate is not a finite number")]
    NonFinite,
    #[error("longitude/latitude ({lon}, {lat}) is out of range (longitudes lie in -180..180, latitudes in -90..90)")]
    /// A longitude/latitude position off the globe.
    OutOfRange {
        /// The longitude, degrees.
        lon: f64,
        /// The latitude, degrees.
        lat: f64,
    },
    /// A ring with fewer than 3 distinct points.
    #[error("ring has fewer than 3 distinct points")]
    DegenerateRing,
    /// A ring whose first and last positions differ.
    #[error("ring is not closed (first and last positions differ)")]
    UnclosedRing,
    /// A ring that encloses no area (all its points on one line).
    #[error("ring has zero area")]
    ZeroArea,
    #[error("boundary intersects itself near ({x:.3}, {y:.3})")]
    /// A ring that crosses or touches itself.
    SelfIntersection {
        /// Easting of the contact in the planning frame, metres.
        x: f64,
        /// Northing of the contact in the planning frame, metres.
        y: f64,
    },
    #[error("hole {hole} touches or crosses the outer boundary near ({x:.3}, {y:.3})")]
    /// A hole that crosses or touches the outer boundary.
    HoleCrossesShell {
        /// The hole's number, counted from 1 in file order.
        hole: usize,
        /// Easting of the contact in the planning frame, metres.
        x: f64,
        /// Northing of the contact in the planning frame, metres.
        y: f64,
    },
    #[error("hole {hole} lies outside the outer boundary")]
    /// A hole that lies wholly outside the outer boundary.
    HoleOutsideShell {
        /// The hole's number, counted from 1 in file order.
        hole: usize,
    },
    #[error("holes {first} and {second} touch along their edges near ({x:.3}, {y:.3}) without overlapping: draw them as one hole, or leave a gap between them")]
    /// Two holes whose edges meet along a line (or at a point) with no area in common: a
    /// polygon's holes may not share edges, and agripath does not guess which outline is meant.
    HolesTouch {
        /// The first hole's number, counted from 1 in file order.
        first: usize,
        /// The second hole's number, counted from 1 in file order.
        second: usize,
        /// Where they touch.
        x: f64,
        /// Where they touch.
        y: f64,
    },
    #[error("holes {first} and {second} overlap")]
    /// Two holes that cross, or lie one inside the other.
    HolesOverlap {
        /// The first hole's number, counted from 1 in file order.
        first: usize,
        /// The second hole's number, counted from 1 in file order.
        second: usize,
    },
    /// A point of the route from which no sortie can reach the rest and fly back on one
    /// battery and one tank: the vehicle is too weak for the farm.
    #[error("battery_endurance_s = {endurance_s} is invalid: the route near ({x:.1}, {y:.1}) cannot be reached and flown back on one battery and one tank")]
    UnreachableOnOneBattery {
        /// Easting of the point in the planning frame, metres.
        x: f64,
        /// Northing of the point in the planning frame, metres.
        y: f64,
        /// The vehicle's endurance, seconds.
        endurance_s: f64,
        /// When the tank is what is short: the swath metres one tank sprays, and the spray
        /// metres of the route's step there.
        tank: Option<(f64, f64)>,
    },
    /// No transit between two places of the flight keeps out of the obstacles (one of them
    /// inside an obstacle, or walled in); both in the planning frame, metres.
    #[error("no transit from ({:.1}, {:.1}) to ({:.1}, {:.1}) keeps out of the obstacles", from.0, from.1, to.0, to.1)]
    NoTransit {
        /// Where the transit starts.
        from: (f64, f64),
        /// Where it ends.
        to: (f64, f64),
    },
    /// The file holds no field polygon.
    #[error("no field polygons found")]
    NoFields,
    /// A value outside what agripath accepts.
    #[error("{what} = {value} is invalid: {why}")]
    InvalidValue {
        /// The setting or key the value was given for.
        what: String,
        /// The value as given.
        value: String,
        /// Why it is refused (the accepted range, for example).
        why: String,
    },
    /// The input exceeds one of agripath's size limits (see [`crate::limits`]); the sizes.
    #[error("too large: {0}")]
    TooLarge(String),
    /// A terrain query that cannot be answered.
    #[error("{0}")]
    Terrain(#[from] TerrainError),
}

/// A number as a message shows it: `1e308` as written, not as 309 digits.
pub fn figure(value: f64) -> String {
    if value != 0.0 && !(1e-3..1e6).contains(&value.abs()) {
        format!("{value:e}")
    } else {
        value.to_string()
    }
}

/// A terrain query that cannot be answered.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum TerrainError {
    #[error("point ({x:.2}, {y:.2}) is outside the terrain model")]
    /// The position is outside the terrain model's extent.
    Outside {
        /// Easting in the planning frame, metres.
        x: f64,
        /// Northing in the planning frame, metres.
        y: f64,
    },
    #[error("the terrain model has no data at ({x:.2}, {y:.2})")]
    /// The position is inside the extent but the model holds no height there (a no-data cell).
    NoData {
        /// Easting in the planning frame, metres.
        x: f64,
        /// Northing in the planning frame, metres.
        y: f64,
    },
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_toml_error_is_placed_at_file_line_column_in_one_line() {
        let text = "name = \"x\"\n# a comment\nswath_width_m = = 3\n";
        let error = toml::from_str::<toml::Table>(text).unwrap_err();
        let message = InputError::toml("farm/vehicle.toml", &error, text).to_string();
        assert!(
            message.starts_with("farm/vehicle.toml:3:17: not valid TOML: "),
            "{message}"
        );
        assert!(!message.contains('\n'), "{message}");
        // Columns count characters, not bytes.
        assert_eq!(line_column("é = 1\nab", 8), (2, 2));
        assert_eq!(line_column("é", 1), (1, 1));
    }

    #[test]
    fn a_misspelt_key_is_named_with_the_nearest_valid_one() {
        #[derive(Debug, serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        #[allow(dead_code)]
        struct Tank {
            tank_l: f64,
            swath_width_m: f64,
        }
        let text = "swath_width_m = 3\ntanc_l = 16\n";
        let error = toml::from_str::<Tank>(text).unwrap_err();
        let message = InputError::toml("vehicle.toml", &error, text).to_string();
        assert_eq!(
            message,
            "vehicle.toml:2:1: unknown key `tanc_l` (did you mean `tank_l`?); the keys are tank_l, swath_width_m"
        );
        // Nothing near: no guess.
        let text = "colour = 3\n";
        let error = toml::from_str::<Tank>(text).unwrap_err();
        let message = InputError::toml("vehicle.toml", &error, text).to_string();
        assert!(
            message.ends_with(": unknown key `colour`; the keys are tank_l, swath_width_m"),
            "{message}"
        );
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("", "ab"), 2);
    }
}
