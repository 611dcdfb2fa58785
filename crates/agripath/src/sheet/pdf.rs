//! `sheet.pdf`: the sheet printed by a headless Chromium, when one is found. Nothing else in
//! agripath needs a browser, so the PDF is asked for (`--pdf`), not made by default: starting
//! a browser costs a second or two, and the HTML prints the same from any browser.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The environment variable naming the browser to print with (a path), or `none`.
pub const BROWSER_VARIABLE: &str = "AGRIPATH_BROWSER";

/// Names tried on `PATH`, in order, when [`BROWSER_VARIABLE`] is not set.
const BROWSER_NAMES: [&str; 4] = [
    "chromium",
    "chromium-browser",
    "google-chrome",
    "google-chrome-stable",
];

/// The longest a print may take before the browser is stopped.
const PRINT_TIMEOUT: Duration = Duration::from_secs(90);

/// The browser to print with: [`BROWSER_VARIABLE`]'s path (`none`: no browser), else the
/// first Chromium on `PATH`.
pub fn find_browser() -> Option<PathBuf> {
    if let Some(value) = std::env::var_os(BROWSER_VARIABLE) {
        return (value != "none" && !value.is_empty()).then(|| PathBuf::from(value));
    }
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .flat_map(|folder| BROWSER_NAMES.iter().map(move |name| folder.join(name)))
        .find(|candidate| candidate.is_file())
}

/// Prints `html` to PDF with `browser` (headless, A4 from the page's print CSS, no header or
/// footer). Works in a scratch folder of its own, removed afterwards.
pub fn pdf(browser: &Path, html: &str) -> Result<Vec<u8>, String> {
    let scratch = std::env::temp_dir().join(format!(
        "agripath-sheet-{}-{}",
        std::process::id(),
        call_number()
    ));
    std::fs::create_dir_all(&scratch).map_err(|error| format!("scratch folder: {error}"))?;
    let result = print(browser, html, &scratch);
    let _ = std::fs::remove_dir_all(&scratch);
    result
}

/// A number that differs between calls in one process (the scratch folder's name).
fn call_number() -> u64 {
    use std::sync::atomic::{AtomicU64, Ordering};
    static CALLS: AtomicU64 = AtomicU64::new(0);
    CALLS.fetch_add(1, Ordering::Relaxed)
}

fn print(browser: &Path, html: &str, scratch: &Path) -> Result<Vec<u8>, String> {
    let page = scratch.join("sheet.html");
    let output = scratch.join("sheet.pdf");
    std::fs::write(&page, html).map_err(|error| format!("{}: {error}", page.display()))?;
    let mut child = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--no-pdf-header-footer",
        ])
        .arg(format!(
            "--user-data-dir={}",
            scratch.join("profile").display()
        ))
        .arg(format!("--print-to-pdf={}", output.display()))
        .arg(format!("file://{}", page.display()))
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .map_err(|error| format!("cannot start {}: {error}", browser.display()))?;
    let started = Instant::now();
    let status = loop {
        match child.try_wait() {
            Ok(Some(status)) => break status,
            Ok(None) if started.elapsed() > PRINT_TIMEOUT => {
                let _ = child.kill();
                let _ = child.wait();
                return Err(format!(
                    "{} did not finish printing in {} s",
                    browser.display(),
                    PRINT_TIMEOUT.as_secs()
                ));
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(50)),
            Err(error) => return Err(format!("{}: {error}", browser.display())),
        }
    };
    let bytes = std::fs::read(&output).map_err(|_| {
        format!(
            "{} printed no PDF (exit status {status})",
            browser.display()
        )
    })?;
    if bytes.starts_with(b"%PDF") {
        Ok(bytes)
    } else {
        Err(format!(
            "{} wrote a file that is not a PDF",
            browser.display()
        ))
    }
}
