//! The viewer of `agripath view DIR`: serves a plan folder on 127.0.0.1 so that `plan.html`
//! (which also works straight from disk) and the files beside it open in a browser.
//!
//! Only what a local viewer needs, and nothing a hostile page or client can abuse:
//! - it listens on the loopback address only, and answers only requests whose `Host` is
//!   `127.0.0.1:PORT` or `localhost:PORT` (a DNS-rebinding page sends its own host name);
//! - each connection has its own thread (at most `MAX_CONNECTIONS` at once; beyond that a
//!   client gets 503 at once), with one deadline for the whole request head and a write
//!   timeout, so an idle or trickling client blocks no one; files are streamed;
//! - the request line and headers are read within `MAX_HEAD_BYTES`;
//! - a file is served only if its canonical path (links resolved) is a regular file directly
//!   inside the folder's canonical path: traversal and links out of DIR get 404.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::{TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::Duration;

use crate::{Fault, InputError};

/// Connections served at once.
const MAX_CONNECTIONS: usize = 256;
/// Request line and headers together, bytes.
const MAX_HEAD_BYTES: u64 = 16 * 1024;
/// How long a client may take to send its request, or to read the answer.
const TIMEOUT: Duration = Duration::from_secs(10);

fn content_type(name: &str) -> &'static str {
    match name.rsplit('.').next().unwrap_or("") {
        "html" => "text/html; charset=utf-8",
        "json" | "geojson" | "plan" => "application/json",
        "svg" => "image/svg+xml",
        "png" => "image/png",
        "kml" => "application/vnd.google-earth.kml+xml",
        "csv" => "text/csv",
        _ => "text/plain; charset=utf-8",
    }
}

/// The file a request path names inside `folder` (given canonical), if it is a plain file
/// name there whose canonical path stays inside the folder.
fn resolve(folder: &Path, request_path: &str) -> Option<PathBuf> {
    let name = request_path.trim_start_matches('/');
    let name = if name.is_empty() { "plan.html" } else { name };
    let plain = !name.contains('/') && !name.contains('\\') && !name.starts_with('.');
    if !plain {
        return None;
    }
    let path = folder.join(name).canonicalize().ok()?;
    (path.parent() == Some(folder) && path.is_file()).then_some(path)
}

/// A request's method, path and `Host`, read within the byte budget.
struct Request {
    method: String,
    path: String,
    host: Option<String>,
}

enum Refusal {
    /// The head did not end within the budget, or was not HTTP.
    Malformed,
    /// The client went quiet or the connection broke: nothing to answer.
    Gone,
}

fn read_request(stream: &TcpStream) -> Result<Request, Refusal> {
    // One deadline for the whole head, not per read: a client trickling a header line every
    // few seconds is cut off at TIMEOUT all the same.
    let deadline = std::time::Instant::now() + TIMEOUT;
    let mut reader = BufReader::new(
        stream
            .try_clone()
            .map_err(|_| Refusal::Gone)?
            .take(MAX_HEAD_BYTES),
    );
    let mut line = String::new();
    let read_line = |reader: &mut BufReader<_>, line: &mut String| -> Result<(), Refusal> {
        line.clear();
        let left = deadline.saturating_duration_since(std::time::Instant::now());
        if left.is_zero() || stream.set_read_timeout(Some(left)).is_err() {
            return Err(Refusal::Gone);
        }
        match reader.read_line(line) {
            Ok(0) | Err(_) => Err(Refusal::Gone),
            Ok(_) if !line.ends_with('\n') => Err(Refusal::Malformed),
            Ok(_) => Ok(()),
        }
    };
    read_line(&mut reader, &mut line)?;
    let mut parts = line.split_whitespace();
    let (Some(method), Some(target), Some(version)) = (parts.next(), parts.next(), parts.next())
    else {
        return Err(Refusal::Malformed);
    };
    if !version.starts_with("HTTP/") {
        return Err(Refusal::Malformed);
    }
    let (method, path) = (
        method.to_string(),
        target.split('?').next().unwrap_or("/").to_string(),
    );
    let mut host = None;
    loop {
        read_line(&mut reader, &mut line)?;
        let header = line.trim_end();
        if header.is_empty() {
            break;
        }
        if let Some((name, value)) = header.split_once(':') {
            if name.eq_ignore_ascii_case("host") {
                // Two Host headers are how a request smuggles a second name past a check.
                if host.is_some() {
                    return Err(Refusal::Malformed);
                }
                host = Some(value.trim().to_ascii_lowercase());
            }
        }
    }
    Ok(Request { method, path, host })
}

fn respond(
    stream: &mut TcpStream,
    status: &str,
    content_type: &str,
    body: &[u8],
) -> std::io::Result<()> {
    write!(
        stream,
        "HTTP/1.1 {status}\r\nContent-Type: {content_type}\r\nContent-Length: {}\r\nX-Content-Type-Options: nosniff\r\nConnection: close\r\n\r\n",
        body.len()
    )?;
    stream.write_all(body)
}

/// Closes after an answer sent before the whole request was read: the rest the client sends
/// is read and dropped (within a budget and a short timeout) so that the close does not reset
/// the connection and lose the answer.
fn linger(stream: &mut TcpStream) -> std::io::Result<()> {
    stream.shutdown(std::net::Shutdown::Write)?;
    stream.set_read_timeout(Some(Duration::from_secs(1)))?;
    let _ = std::io::copy(&mut (&*stream).take(1 << 20), &mut std::io::sink());
    Ok(())
}

fn answer(stream: &mut TcpStream, folder: &Path, port: u16) -> std::io::Result<()> {
    stream.set_read_timeout(Some(TIMEOUT))?;
    stream.set_write_timeout(Some(TIMEOUT))?;
    let text = "text/plain; charset=utf-8";
    let request = match read_request(stream) {
        Ok(request) => request,
        Err(Refusal::Malformed) => {
            respond(stream, "400 Bad Request", text, b"bad request")?;
            return linger(stream);
        }
        Err(Refusal::Gone) => return Ok(()),
    };
    let allowed_hosts = [format!("127.0.0.1:{port}"), format!("localhost:{port}")];
    if !request
        .host
        .as_ref()
        .is_some_and(|host| allowed_hosts.contains(host))
    {
        return respond(
            stream,
            "403 Forbidden",
            text,
            b"only 127.0.0.1 or localhost",
        );
    }
    if request.method != "GET" {
        return respond(stream, "405 Method Not Allowed", text, b"GET only");
    }
    match resolve(folder, &request.path) {
        Some(file) => {
            // Streamed, not read whole: a large file in DIR costs a buffer, not its size.
            let mut body = std::fs::File::open(&file)?;
            let length = body.metadata()?.len();
            let name = file
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            write!(
                stream,
                "HTTP/1.1 200 OK\r\nContent-Type: {}\r\nContent-Length: {length}\r\nX-Content-Type-Options: nosniff\r\nConnection: close\r\n\r\n",
                content_type(&name)
            )?;
            std::io::copy(&mut (&mut body).take(length), stream)?;
            Ok(())
        }
        None => respond(stream, "404 Not Found", text, b"not found"),
    }
}

/// Refuses a folder with no `plan.html`: only what `agripath plan` or `agripath demo` wrote
/// is served.
pub fn check_folder(folder: &Path) -> Result<(), InputError> {
    if folder.join("plan.html").is_file() {
        return Ok(());
    }
    Err(InputError::new(
        folder,
        Fault::Structure(
            "no plan.html here: give a folder written by `agripath plan` or `agripath demo`".into(),
        ),
    ))
}

/// Serves `folder` until the process is stopped; `on_ready` gets the URL once listening.
pub fn serve(folder: &Path, port: u16, on_ready: impl FnOnce(&str)) -> std::io::Result<()> {
    let folder: Arc<Path> = folder.canonicalize()?.into();
    let listener = TcpListener::bind(("127.0.0.1", port))?;
    let port = listener.local_addr()?.port();
    on_ready(&format!("http://127.0.0.1:{port}/plan.html"));
    let open = Arc::new(AtomicUsize::new(0));
    for stream in listener.incoming() {
        let Ok(mut stream) = stream else { continue };
        if open.fetch_add(1, Ordering::SeqCst) >= MAX_CONNECTIONS {
            open.fetch_sub(1, Ordering::SeqCst);
            let _ = stream.set_write_timeout(Some(TIMEOUT));
            let _ = respond(
                &mut stream,
                "503 Service Unavailable",
                "text/plain",
                b"busy",
            );
            continue;
        }
        let (folder, still_open) = (Arc::clone(&folder), Arc::clone(&open));
        let spawned = std::thread::Builder::new().spawn(move || {
            // One bad request must not stop the viewer.
            let _ = answer(&mut stream, &folder, port);
            still_open.fetch_sub(1, Ordering::SeqCst);
        });
        if spawned.is_err() {
            // No thread to be had: the connection is dropped and the counter given back.
            open.fetch_sub(1, Ordering::SeqCst);
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_plain_files_of_the_folder_are_served() {
        let root = std::env::temp_dir().join(format!("agripath-view-{}", std::process::id()));
        let folder = root.join("plan");
        std::fs::create_dir_all(&folder).unwrap();
        std::fs::write(folder.join("plan.html"), "x").unwrap();
        std::fs::write(root.join("secret.txt"), "no").unwrap();
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink(root.join("secret.txt"), folder.join("link.txt")).unwrap();
            std::os::unix::fs::symlink(&root, folder.join("up")).unwrap();
        }
        let folder = folder.canonicalize().unwrap();
        assert!(resolve(&folder, "/").is_some());
        assert!(resolve(&folder, "/plan.html").is_some());
        assert!(resolve(&folder, "/../secret.txt").is_none());
        assert!(resolve(&folder, "/link.txt").is_none());
        assert!(resolve(&folder, "/up").is_none());
        assert!(resolve(&folder, "/up/secret.txt").is_none());
        assert!(resolve(&folder, "/missing.json").is_none());
        assert!(resolve(&folder, "/.hidden").is_none());
        std::fs::remove_dir_all(&root).unwrap();
    }
}
