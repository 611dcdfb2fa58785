//! `agripath view DIR`: serves a plan folder on 127.0.0.1 so that `plan.html` (which also
//! works straight from disk) and the files beside it open in a browser. Only files directly
//! inside DIR are served; nothing listens beyond the loopback address.

use std::io::{BufRead, BufReader, Write};
use std::net::{TcpListener, TcpStream};
use std::path::{Path, PathBuf};

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

/// The file a request path names inside `folder`, if it is a plain file name there.
fn resolve(folder: &Path, request_path: &str) -> Option<PathBuf> {
    let name = request_path.trim_start_matches('/');
    let name = if name.is_empty() { "plan.html" } else { name };
    let plain = !name.contains('/') && !name.contains('\\') && !name.starts_with('.');
    let path = folder.join(name);
    (plain && path.is_file()).then_some(path)
}

fn answer(stream: &mut TcpStream, folder: &Path) -> std::io::Result<()> {
    let mut request = String::new();
    BufReader::new(stream.try_clone()?).read_line(&mut request)?;
    let mut parts = request.split_whitespace();
    let (method, path) = (parts.next().unwrap_or(""), parts.next().unwrap_or("/"));
    let path = path.split('?').next().unwrap_or("/");
    match resolve(folder, path).filter(|_| method == "GET") {
        Some(file) => {
            let body = std::fs::read(&file)?;
            let name = file
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            write!(
                stream,
                "HTTP/1.1 200 OK\r\nContent-Type: {}\r\nContent-Length: {}\r\nConnection: close\r\n\r\n",
                content_type(&name),
                body.len()
            )?;
            stream.write_all(&body)
        }
        None => stream.write_all(
            b"HTTP/1.1 404 Not Found\r\nContent-Length: 9\r\nConnection: close\r\n\r\nnot found",
        ),
    }
}

/// Serves `folder` until the process is stopped; `on_ready` gets the URL once listening.
pub fn serve(folder: &Path, port: u16, on_ready: impl FnOnce(&str)) -> std::io::Result<()> {
    let listener = TcpListener::bind(("127.0.0.1", port))?;
    let url = format!(
        "http://127.0.0.1:{}/plan.html",
        listener.local_addr()?.port()
    );
    on_ready(&url);
    for stream in listener.incoming() {
        let Ok(mut stream) = stream else { continue };
        // One bad request must not stop the viewer.
        let _ = answer(&mut stream, folder);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_plain_files_of_the_folder_are_served() {
        let folder = std::env::temp_dir().join(format!("agripath-view-{}", std::process::id()));
        std::fs::create_dir_all(&folder).unwrap();
        std::fs::write(folder.join("plan.html"), "x").unwrap();
        assert!(resolve(&folder, "/").is_some());
        assert!(resolve(&folder, "/plan.html").is_some());
        assert!(resolve(&folder, "/../etc/passwd").is_none());
        assert!(resolve(&folder, "/missing.json").is_none());
        assert!(resolve(&folder, "/.hidden").is_none());
        std::fs::remove_dir_all(&folder).unwrap();
    }
}
