//! Reading input files within a byte budget, with one clear message per failure.

use std::path::Path;

use crate::error::{Fault, InputError};
use crate::limits::MAX_TEXT_FILE_BYTES;

/// A file's extension in lower case ("" when it has none): what chooses its reader.
pub fn extension_of(path: &Path) -> String {
    path.extension()
        .and_then(|extension| extension.to_str())
        .unwrap_or("")
        .to_ascii_lowercase()
}

/// Reads a whole file as bytes, with the size limit and a clear message on failure.
pub fn read_bytes(path: &Path) -> Result<Vec<u8>, InputError> {
    read_bytes_within(path, MAX_TEXT_FILE_BYTES)
}

/// Reads a whole regular file of at most `budget` bytes. The budget bounds the read itself,
/// not the size the file system reports: a link to `/dev/zero` or a file that grows while
/// read stops at `budget + 1` bytes. FIFOs, devices and sockets are refused before they are
/// opened (opening a FIFO with no writer blocks for ever).
pub fn read_bytes_within(path: &Path, budget: u64) -> Result<Vec<u8>, InputError> {
    use std::io::Read;
    let metadata =
        std::fs::metadata(path).map_err(|error| InputError::new(path, unreadable(&error)))?;
    if metadata.is_dir() {
        return Err(InputError::new(
            path,
            Fault::Unreadable("it is a folder, not a file".into()),
        ));
    }
    if !metadata.is_file() {
        return Err(InputError::new(
            path,
            Fault::Unreadable(format!(
                "it is {}, not a regular file",
                special_kind(&metadata)
            )),
        ));
    }
    let too_large = |size: String| {
        InputError::new(
            path,
            Fault::TooLarge(format!("{size} bytes (limit {budget})")),
        )
    };
    if metadata.len() > budget {
        return Err(too_large(metadata.len().to_string()));
    }
    let file =
        std::fs::File::open(path).map_err(|error| InputError::new(path, unreadable(&error)))?;
    let mut bytes = Vec::with_capacity(metadata.len() as usize);
    file.take(budget + 1)
        .read_to_end(&mut bytes)
        .map_err(|error| InputError::new(path, unreadable(&error)))?;
    if bytes.len() as u64 > budget {
        return Err(too_large(format!("more than {budget}")));
    }
    if bytes.iter().all(u8::is_ascii_whitespace) {
        return Err(InputError::new(path, Fault::Empty));
    }
    Ok(bytes)
}

/// What a file that is neither a folder nor a regular file is, for the message.
fn special_kind(metadata: &std::fs::Metadata) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let kind = metadata.file_type();
        if kind.is_fifo() {
            return "a FIFO (named pipe)";
        }
        if kind.is_char_device() || kind.is_block_device() {
            return "a device";
        }
        if kind.is_socket() {
            return "a socket";
        }
    }
    let _ = metadata;
    "a special file"
}

/// Refuses a file whose first bytes are not what its format starts with, before the whole
/// file is read: a 2 GB sparse file (all zero bytes) is refused after 64 KB, not 2 GB.
/// `text`: no NUL byte may appear; else one of `magics` must begin the file, which is then
/// a `format` ("a TIFF", "a KMZ (zip) archive").
pub fn check_start(
    path: &Path,
    text: bool,
    magics: &[&[u8]],
    format: &str,
) -> Result<(), InputError> {
    use std::io::Read;
    let metadata =
        std::fs::metadata(path).map_err(|error| InputError::new(path, unreadable(&error)))?;
    if !metadata.is_file() {
        // read_bytes_within gives the message for folders and special files.
        return Ok(());
    }
    let mut head = Vec::with_capacity(64 * 1024);
    std::fs::File::open(path)
        .and_then(|file| file.take(64 * 1024).read_to_end(&mut head))
        .map_err(|error| InputError::new(path, unreadable(&error)))?;
    if text {
        if let Some(offset) = head.iter().position(|&byte| byte == 0) {
            return Err(InputError::new(
                path,
                Fault::Unreadable(format!("not UTF-8 text (a NUL byte at offset {offset})")),
            ));
        }
    } else if !head.is_empty() && !magics.iter().any(|magic| head.starts_with(magic)) {
        return Err(InputError::new(
            path,
            Fault::Unreadable(format!("not {format}: its first bytes are not its header")),
        ));
    }
    Ok(())
}

/// Reads a whole text file (UTF-8).
pub fn read_text(path: &Path) -> Result<String, InputError> {
    check_start(path, true, &[], "text")?;
    let mut bytes = read_bytes(path)?;
    // A byte-order mark, which Windows editors write before UTF-8 text, is not part of the
    // text (JSON parsers reject it at line 1, column 1).
    if bytes.starts_with(UTF8_BOM) {
        bytes.drain(..UTF8_BOM.len());
    }
    String::from_utf8(bytes).map_err(|error| {
        InputError::new(
            path,
            Fault::Unreadable(format!(
                "not UTF-8 text (invalid byte at offset {})",
                error.utf8_error().valid_up_to()
            )),
        )
    })
}

/// The UTF-8 byte-order mark.
const UTF8_BOM: &[u8] = b"\xEF\xBB\xBF";

pub(crate) fn unreadable(error: &std::io::Error) -> Fault {
    Fault::Unreadable(reason(error))
}

/// An I/O error in words (no "os error 13").
pub fn reason(error: &std::io::Error) -> String {
    match error.kind() {
        std::io::ErrorKind::NotFound => "no such file".to_string(),
        std::io::ErrorKind::PermissionDenied => "permission denied".to_string(),
        _ => error.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_byte_order_mark_is_not_part_of_the_text() {
        let path =
            std::env::temp_dir().join(format!("agripath-bom-{}.geojson", std::process::id()));
        std::fs::write(&path, b"\xEF\xBB\xBF{\"type\":\"FeatureCollection\"}").unwrap();
        let text = read_text(&path).unwrap();
        std::fs::remove_file(&path).unwrap();
        assert_eq!(text, "{\"type\":\"FeatureCollection\"}");
    }
}
