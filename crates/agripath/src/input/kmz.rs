//! KMZ field files: a zip holding a KML document ([`super::kml`] reads it), as Google Earth
//! and ground stations write them. The document is `doc.kml`, else the first `.kml` entry;
//! macOS's resource forks are passed over, and other `.kml` documents are named in a note.

use std::io::Read;
use std::path::Path;

use super::kml::parse;
use super::CoordinateChoice;
use crate::error::{Fault, InputError};
use crate::files::read_bytes;
use crate::model::Farm;

/// Biggest KML document inflated from a KMZ, bytes (a zip bomb stops here): 128 MB of KML
/// is some 4 million vertices, twice the most a field file may hold.
const MAX_INFLATED_KML_BYTES: u64 = 128 * 1024 * 1024;

/// A KMZ is a zip holding `doc.kml` (or another `.kml` at its root).
pub fn read_kmz(path: &Path, choice: CoordinateChoice) -> Result<Farm, InputError> {
    crate::files::check_start(path, false, &[b"PK\x03\x04"], "a KMZ (zip) archive")?;
    let bytes = read_bytes(path)?;
    parse_kmz(path, bytes, choice)
}

/// A KMZ's bytes (`path` names it in messages).
pub fn parse_kmz(
    path: &Path,
    bytes: Vec<u8>,
    choice: CoordinateChoice,
) -> Result<Farm, InputError> {
    let fail = |message: String| InputError::new(path, Fault::Kml(message));
    let mut archive = zip::ZipArchive::new(std::io::Cursor::new(bytes))
        .map_err(|error| fail(format!("not a KMZ (zip) archive: {error}")))?;
    let names: Vec<String> = archive
        .file_names()
        .map(|name| name.map(|name| name.into_owned()))
        .collect::<Result<_, _>>()
        .map_err(|error| fail(format!("unreadable entry name in the archive: {error}")))?;
    // macOS's Finder adds "__MACOSX/._name.kml" resource forks beside the real entries: they
    // are not KML.
    let documents: Vec<&String> = names
        .iter()
        .filter(|name| {
            let file_name = name.rsplit(['/', '\\']).next().unwrap_or(name);
            name.to_ascii_lowercase().ends_with(".kml")
                && !name.starts_with("__MACOSX/")
                && !file_name.starts_with("._")
        })
        .collect();
    let entry = documents
        .iter()
        .find(|name| name.eq_ignore_ascii_case("doc.kml"))
        .or_else(|| documents.first())
        .map(|name| (*name).clone())
        .ok_or_else(|| fail("the KMZ archive holds no .kml document".into()))?;
    let others: Vec<&str> = documents
        .iter()
        .filter(|name| **name != &entry)
        .map(|name| name.as_str())
        .collect();
    let file = archive
        .by_name(&entry)
        .map_err(|error| fail(format!("cannot open {entry} in the archive: {error}")))?;
    // The size the archive declares refuses an honest bomb at once; the bounded read below
    // stops one that lies about it.
    if file.size() > MAX_INFLATED_KML_BYTES {
        return Err(InputError::new(
            path,
            Fault::TooLarge(format!(
                "{entry} inflates to {} bytes (limit {MAX_INFLATED_KML_BYTES})",
                file.size()
            )),
        ));
    }
    // Sized from the declaration (at most the limit): no doubling of the buffer past it.
    let mut text = String::with_capacity(file.size().min(MAX_INFLATED_KML_BYTES) as usize);
    file.take(MAX_INFLATED_KML_BYTES + 1)
        .read_to_string(&mut text)
        .map_err(|error| fail(format!("cannot inflate {entry}: {error}")))?;
    if text.len() as u64 > MAX_INFLATED_KML_BYTES {
        return Err(InputError::new(
            path,
            Fault::TooLarge(format!(
                "{entry} inflates past {MAX_INFLATED_KML_BYTES} bytes"
            )),
        ));
    }
    let mut farm = parse(path, &text, choice).map_err(|error| error.at_inner(&entry))?;
    if !others.is_empty() {
        farm.notes.push(format!(
            "the KMZ holds {} more .kml document(s) ({}), not read: a KMZ's fields are those of its root document, {entry}",
            others.len(),
            others.join(", ")
        ));
    }
    Ok(farm)
}

impl InputError {
    fn at_inner(self, entry: &str) -> Self {
        if self.place.is_some() {
            let place = self.place.clone().unwrap_or_default();
            Self {
                place: Some(format!("{entry}: {place}")),
                ..self
            }
        } else {
            self
        }
    }
}
