//! Writing outputs so that an error or an interrupt never leaves half of them behind.
//!
//! A plan folder is written into a hidden sibling (`.NAME.partial-PID`) and renamed into
//! place at the end; a single file is written beside its target and renamed over it.

use std::path::{Path, PathBuf};

/// Writes `bytes` to `path` through a temporary file in the same folder and a rename.
pub fn write_file_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let folder = path
        .parent()
        .filter(|parent| !parent.as_os_str().is_empty());
    let name = path
        .file_name()
        .map(|name| name.to_string_lossy().into_owned())
        .unwrap_or_else(|| "output".into());
    let temporary = match folder {
        Some(folder) => folder.join(format!(".{name}.partial-{}", std::process::id())),
        None => PathBuf::from(format!(".{name}.partial-{}", std::process::id())),
    };
    std::fs::write(&temporary, bytes)?;
    std::fs::rename(&temporary, path).inspect_err(|_| {
        let _ = std::fs::remove_file(&temporary);
    })
}

/// An output folder being written. Files go to a staging folder; [`StagedFolder::commit`]
/// replaces the target folder with it. Dropped without a commit, it removes the staging.
///
/// A kill at any instant leaves the target whole: either the old folder or the new one.
/// On Linux the commit swaps the two in one `renameat2(RENAME_EXCHANGE)`; elsewhere (or on a
/// file system without it) the old folder is first moved to `.NAME.old-PID`, and a later run
/// that finds the target missing moves it back. Whatever a dead run left (`.NAME.partial-PID`,
/// `.NAME.old-PID`, the `.NAME.old` of versions before 0.2) is removed by the next run.
pub struct StagedFolder {
    target: PathBuf,
    staging: PathBuf,
    committed: bool,
}

impl StagedFolder {
    /// Starts staging a new `target` folder (cleaning up what dead runs left); errs when `target` cannot be a plan folder ([`check_target`]) or the staging folder cannot be made.
    pub fn new(target: &Path) -> std::io::Result<Self> {
        check_target(target)?;
        let parent = parent_of(target);
        std::fs::create_dir_all(parent)?;
        let name = name_of(target);
        recover_abandoned(parent, &name, target);
        let staging = parent.join(format!(".{name}.partial-{}", std::process::id()));
        if staging.exists() {
            std::fs::remove_dir_all(&staging)?;
        }
        std::fs::create_dir_all(&staging)?;
        std::fs::write(staging.join(MARKER), MARKER_TEXT)?;
        Ok(Self {
            target: target.to_path_buf(),
            staging,
            committed: false,
        })
    }

    /// Where a file named `name` is staged.
    pub fn path(&self, name: &str) -> PathBuf {
        self.staging.join(name)
    }

    /// Writes `bytes` to the staged file `name`.
    pub fn write(&self, name: &str, bytes: &[u8]) -> std::io::Result<()> {
        std::fs::write(self.path(name), bytes)?;
        fault_point();
        Ok(())
    }

    /// Moves the staged folder into place, replacing what was there.
    pub fn commit(mut self) -> std::io::Result<PathBuf> {
        fault_point();
        if self.target.exists() {
            if exchange(&self.staging, &self.target).is_ok() {
                // The old folder now sits where the staging was.
                self.committed = true;
                fault_point();
                // The new plan is in place; an old file that cannot be removed is left in
                // the staging folder, and the next run removes it.
                let _ = remove_folder(&self.staging);
            } else {
                let old = parent_of(&self.target).join(format!(
                    ".{}.old-{}",
                    name_of(&self.target),
                    std::process::id()
                ));
                std::fs::rename(&self.target, &old)?;
                fault_point();
                std::fs::rename(&self.staging, &self.target)?;
                self.committed = true;
                fault_point();
                let _ = remove_folder(&old);
            }
        } else {
            std::fs::rename(&self.staging, &self.target)?;
            self.committed = true;
        }
        fault_point();
        Ok(self.target.clone())
    }
}

/// The file every output folder holds, so that a later run knows the folder is one it may
/// replace whole.
pub const MARKER: &str = ".agripath-output";
const MARKER_TEXT: &str =
    "This folder was written by agripath. A run that writes to it again replaces it whole.\n";

/// Files a desktop drops in any folder it shows: a folder holding only these is empty.
const SYSTEM_FILES: [&str; 3] = [".DS_Store", "Thumbs.db", "desktop.ini"];

/// Whether `folder` is a plan folder written before output folders were marked (2026-12-06):
/// its `report.json` is agripath's (it names the scenario and the time the plan took).
fn is_earlier_output(folder: &Path) -> bool {
    let Ok(text) = crate::files::read_text(&folder.join("report.json")) else {
        return false;
    };
    serde_json::from_str::<serde_json::Value>(&text)
        .is_ok_and(|report| report.get("scenario").is_some() && report.get("runtime_s").is_some())
}

/// Refuses an output folder that holds one of the run's own inputs: replacing the folder
/// would delete the file being read (a field file saved into an earlier plan's folder, say).
pub fn check_inputs_outside(target: &Path, inputs: &[PathBuf]) -> std::io::Result<()> {
    let Ok(folder) = target.canonicalize() else {
        return Ok(()); // Not there yet: nothing in it to lose.
    };
    for input in inputs {
        let Ok(file) = input.canonicalize() else {
            continue; // Not a file (a terrain keyword such as `flat`), or the reader will say.
        };
        if file.starts_with(&folder) {
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                format!(
                    "{} holds {}, an input of this run: a run replaces its output folder whole, so give --out another folder",
                    target.display(),
                    input.display()
                ),
            ));
        }
    }
    Ok(())
}

/// Refuses an output path that cannot become a plan folder, before anything is written or
/// moved: an existing file (which a commit would otherwise move aside), a path whose parent
/// is a file, or a folder with files in it that agripath did not write (the field file's own
/// folder, say), which the commit would delete.
pub fn check_target(target: &Path) -> std::io::Result<()> {
    let refused = |why: String| std::io::Error::new(std::io::ErrorKind::InvalidInput, why);
    let not_a_folder = |path: &Path| {
        refused(format!(
            "{} is a file, not a folder: give --out a folder to write the plan into",
            path.display()
        ))
    };
    // `.`, `..` or a path ending in them would make the commit swap the working folder.
    if !matches!(
        target.components().next_back(),
        Some(std::path::Component::Normal(_))
    ) {
        return Err(refused(format!(
            "{} does not name a folder of its own: give --out a new or plan folder's name",
            target.display()
        )));
    }
    // A link would be swapped as a link and the folder it points to emptied: refused, as
    // is a dangling one.
    if let Ok(metadata) = std::fs::symlink_metadata(target) {
        if metadata.file_type().is_symlink() {
            return Err(refused(format!(
                "{} is a symbolic link: give --out the folder itself",
                target.display()
            )));
        }
        if !metadata.is_dir() {
            return Err(not_a_folder(target));
        }
        if !target.join(MARKER).exists() && !is_earlier_output(target) {
            let mut held: Vec<String> = std::fs::read_dir(target)?
                .flatten()
                .map(|entry| entry.file_name().to_string_lossy().into_owned())
                .filter(|name| !SYSTEM_FILES.contains(&name.as_str()))
                .collect();
            if !held.is_empty() {
                held.sort();
                let shown = held.len().min(3);
                return Err(refused(format!(
                    "{} is a folder agripath did not write (it holds {}{}, and no {MARKER}): a run replaces its output folder whole, so give --out a new folder or one an earlier run wrote",
                    target.display(),
                    held[..shown].join(", "),
                    if held.len() > shown { ", …" } else { "" }
                )));
            }
        }
    }
    let existing_parent = target
        .ancestors()
        .skip(1)
        .find(|ancestor| !ancestor.as_os_str().is_empty() && ancestor.exists());
    if let Some(file) = existing_parent.filter(|ancestor| !ancestor.is_dir()) {
        return Err(not_a_folder(file));
    }
    // The staging folder is made beside the target: the nearest existing folder above it
    // must take new entries (probed, not guessed from permission bits).
    let parent = existing_parent.unwrap_or(Path::new("."));
    let probe = parent.join(format!(".agripath-probe-{}", std::process::id()));
    match std::fs::create_dir(&probe) {
        Ok(()) => {
            let _ = std::fs::remove_dir(&probe);
            Ok(())
        }
        // The machine's refusal, not the caller's path: its kind is kept (the CLI exits 1).
        Err(error) => Err(std::io::Error::new(
            error.kind(),
            format!(
                "cannot write in {}: {}",
                parent.display(),
                crate::files::reason(&error)
            ),
        )),
    }
}

fn parent_of(target: &Path) -> &Path {
    target
        .parent()
        .filter(|parent| !parent.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
}

/// The target's name as its hidden siblings (`.NAME.partial-PID`, `.NAME.old-PID`) carry
/// it: whole up to [`LONGEST_SIBLING_NAME`] bytes, else its first bytes and a hash of the
/// whole, so that a folder name near the file system's 255-byte limit still gets siblings
/// (trial 7: a 245-byte `--out` failed with "File name too long").
fn name_of(target: &Path) -> String {
    let name = target
        .file_name()
        .map(|name| name.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    if name.len() <= LONGEST_SIBLING_NAME {
        return name;
    }
    let mut cut = LONGEST_SIBLING_NAME - HASH_SUFFIX_BYTES;
    while !name.is_char_boundary(cut) {
        cut -= 1;
    }
    // FNV-1a: stable across runs and builds, so a later run finds a dead run's siblings.
    let hash = name.bytes().fold(0xcbf2_9ce4_8422_2325_u64, |hash, byte| {
        (hash ^ u64::from(byte)).wrapping_mul(0x0100_0000_01b3)
    });
    format!("{}~{hash:016x}", &name[..cut])
}

/// Longest target name kept whole in its siblings' names, bytes: well under the 235 that
/// 255 leaves once the dot and `.partial-` with a ten-digit process id are added.
const LONGEST_SIBLING_NAME: usize = 200;

/// Bytes of the hash a shortened name ends with: `~` and 16 hexadecimal digits.
const HASH_SUFFIX_BYTES: usize = 17;

/// Swaps two paths in one step (Linux `renameat2` with `RENAME_EXCHANGE`). The project's one
/// `unsafe`: std has no atomic exchange, and without one a kill between two renames leaves
/// no folder at the target.
#[cfg(target_os = "linux")]
#[allow(unsafe_code)]
fn exchange(a: &Path, b: &Path) -> std::io::Result<()> {
    use std::os::unix::ffi::OsStrExt;
    let path = |path: &Path| {
        std::ffi::CString::new(path.as_os_str().as_bytes())
            .map_err(|_| std::io::Error::from(std::io::ErrorKind::InvalidInput))
    };
    let (a, b) = (path(a)?, path(b)?);
    // SAFETY: both pointers are NUL-terminated strings that outlive the call.
    let result = unsafe {
        libc::syscall(
            libc::SYS_renameat2,
            libc::AT_FDCWD,
            a.as_ptr(),
            libc::AT_FDCWD,
            b.as_ptr(),
            libc::RENAME_EXCHANGE,
        )
    };
    if result == 0 {
        Ok(())
    } else {
        Err(std::io::Error::last_os_error())
    }
}

#[cfg(not(target_os = "linux"))]
fn exchange(_a: &Path, _b: &Path) -> std::io::Result<()> {
    Err(std::io::Error::from(std::io::ErrorKind::Unsupported))
}

/// Removes a plan folder file by file (a fault point after each, for the kill test).
fn remove_folder(folder: &Path) -> std::io::Result<()> {
    for entry in std::fs::read_dir(folder)? {
        let entry = entry?;
        if entry.file_type()?.is_dir() {
            std::fs::remove_dir_all(entry.path())?;
        } else {
            std::fs::remove_file(entry.path())?;
        }
        fault_point();
    }
    std::fs::remove_dir(folder)
}

/// The kill test's hook: with `AGRIPATH_FAULT_AT=N` in the environment the process aborts
/// (no destructor runs, as under `kill -9`) at the N-th fault point it reaches. Unset, it
/// costs one environment lookup per call.
fn fault_point() {
    // Release builds carry no hook: a stray environment variable cannot abort a real run.
    if !cfg!(debug_assertions) {
        return;
    }
    use std::sync::atomic::{AtomicU64, Ordering};
    static REACHED: AtomicU64 = AtomicU64::new(0);
    let Some(at) = std::env::var("AGRIPATH_FAULT_AT")
        .ok()
        .and_then(|value| value.parse::<u64>().ok())
    else {
        return;
    };
    if REACHED.fetch_add(1, Ordering::SeqCst) + 1 == at {
        std::process::abort();
    }
}

/// Cleans up after runs that were killed while they wrote (an interrupt ends the program
/// before it can): their `.NAME.partial-PID` and `.NAME.old-PID` folders, when that process
/// is gone, and the `.NAME.old` of earlier versions. If the target itself is missing and a
/// dead run's `.NAME.old-PID` holds it (killed between the fallback's two renames), it is
/// moved back first. Where running processes cannot be listed (no `/proc`), only the
/// target's recovery and `.NAME.old` are done.
fn recover_abandoned(parent: &Path, name: &str, target: &Path) {
    let proc = Path::new("/proc");
    let can_list = proc.join("self").exists();
    let Ok(entries) = std::fs::read_dir(parent) else {
        return;
    };
    let mut dead = Vec::new();
    for entry in entries.flatten() {
        let file_name = entry.file_name().to_string_lossy().into_owned();
        let Some(rest) = file_name.strip_prefix(&format!(".{name}.")) else {
            continue;
        };
        if rest == "old" {
            // Earlier versions' leftover: a folder holding a plan, nothing else.
            if entry.path().join("report.json").is_file() {
                dead.push((entry.path(), true));
            }
            continue;
        }
        let (pid, is_old) = match (rest.strip_prefix("partial-"), rest.strip_prefix("old-")) {
            (Some(pid), _) => (pid.strip_suffix(".old").unwrap_or(pid), false),
            (None, Some(pid)) => (pid, true),
            (None, None) => continue,
        };
        if pid.parse::<u32>().is_ok() && can_list && !proc.join(pid).exists() {
            dead.push((entry.path(), is_old));
        }
    }
    if !target.exists() {
        if let Some((old, _)) = dead.iter().find(|(_, is_old)| *is_old) {
            let _ = std::fs::rename(old, target);
        }
    }
    for (path, _) in dead {
        if path.exists() {
            let _ = std::fs::remove_dir_all(path);
        }
    }
}

impl Drop for StagedFolder {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_dir_all(&self.staging);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uncommitted_folder_leaves_nothing_and_commit_replaces() {
        let root = std::env::temp_dir().join(format!("agripath-output-{}", std::process::id()));
        let target = root.join("plan");
        {
            let staged = StagedFolder::new(&target).unwrap();
            staged.write("a.txt", b"half").unwrap();
        }
        assert!(!target.exists());
        assert_eq!(std::fs::read_dir(&root).unwrap().count(), 0);
        std::fs::create_dir_all(&target).unwrap();
        std::fs::write(target.join("stale.txt"), b"old").unwrap();
        // A folder agripath did not write is refused, and left as it was.
        let refused = StagedFolder::new(&target).err().unwrap().to_string();
        assert!(
            refused.contains("is a folder agripath did not write (it holds stale.txt,"),
            "{refused}"
        );
        assert!(target.join("stale.txt").exists());
        // One an earlier run wrote is replaced whole.
        std::fs::write(target.join(MARKER), MARKER_TEXT).unwrap();
        let staged = StagedFolder::new(&target).unwrap();
        staged.write("a.txt", b"new").unwrap();
        staged.commit().unwrap();
        assert!(!target.join("stale.txt").exists());
        assert_eq!(std::fs::read(target.join("a.txt")).unwrap(), b"new");
        assert!(target.join(MARKER).exists(), "the new folder is marked too");
        // A plan folder from before the mark (its report.json is agripath's) is replaced; a
        // folder holding only what a desktop drops is as good as empty.
        let earlier = root.join("earlier");
        std::fs::create_dir_all(&earlier).unwrap();
        std::fs::write(
            earlier.join("report.json"),
            br#"{"scenario":"demo","runtime_s":0.2}"#,
        )
        .unwrap();
        assert!(check_target(&earlier).is_ok());
        let shown = root.join("shown");
        std::fs::create_dir_all(&shown).unwrap();
        std::fs::write(shown.join(".DS_Store"), b"x").unwrap();
        assert!(check_target(&shown).is_ok());
        // An input of the run inside the folder is refused, marked or not.
        std::fs::write(target.join("fields.geojson"), b"{}").unwrap();
        let inside = check_inputs_outside(&target, &[target.join("fields.geojson")])
            .err()
            .unwrap()
            .to_string();
        assert!(inside.contains("an input of this run"), "{inside}");
        assert!(check_inputs_outside(&target, &[root.join("elsewhere.geojson")]).is_ok());
        std::fs::remove_dir_all(&earlier).unwrap();
        std::fs::remove_dir_all(&shown).unwrap();
        assert_eq!(
            std::fs::read_dir(&root).unwrap().count(),
            1,
            "only the target is left"
        );
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn a_file_or_a_path_through_a_file_is_not_a_target() {
        let root = std::env::temp_dir().join(format!("agripath-target-{}", std::process::id()));
        std::fs::create_dir_all(&root).unwrap();
        let file = root.join("notes.txt");
        std::fs::write(&file, b"mine").unwrap();
        for target in [file.clone(), file.join("plan")] {
            let error = StagedFolder::new(&target).err().unwrap();
            assert!(error.to_string().contains("notes.txt is a file"), "{error}");
        }
        assert_eq!(std::fs::read(&file).unwrap(), b"mine");
        assert_eq!(std::fs::read_dir(&root).unwrap().count(), 1);
        // A link to a folder is refused, and the folder it points to keeps its files.
        #[cfg(unix)]
        {
            let precious = root.join("precious");
            std::fs::create_dir_all(&precious).unwrap();
            std::fs::write(precious.join("keep.txt"), b"keep").unwrap();
            std::os::unix::fs::symlink(&precious, root.join("link")).unwrap();
            let error = StagedFolder::new(&root.join("link")).err().unwrap();
            assert!(error.to_string().contains("symbolic link"), "{error}");
            assert!(precious.join("keep.txt").exists());
        }
        for target in [Path::new("."), Path::new(".."), &root.join("..")] {
            assert!(StagedFolder::new(target).is_err(), "{}", target.display());
        }
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn stagings_of_dead_runs_are_removed_and_live_ones_kept() {
        let root = std::env::temp_dir().join(format!("agripath-abandoned-{}", std::process::id()));
        // PID 4294967295 cannot exist; this test's own PID is alive.
        let dead = root.join(".plan.partial-4294967295");
        let alive = root.join(format!(".plan.partial-{}", std::process::id()));
        let dead_old = root.join(".plan.old-4294967295");
        let legacy_old = root.join(".plan.old");
        std::fs::create_dir_all(&dead_old).unwrap();
        std::fs::create_dir_all(&legacy_old).unwrap();
        std::fs::write(legacy_old.join("report.json"), b"{}").unwrap();
        std::fs::write(dead_old.join("report.json"), b"old").unwrap();
        std::fs::create_dir_all(&dead).unwrap();
        std::fs::create_dir_all(&alive).unwrap();
        let staged = StagedFolder::new(&root.join("plan")).unwrap();
        if Path::new("/proc/self").exists() {
            assert!(!dead.exists());
            // The target was missing: the dead run's old folder became it again.
            assert_eq!(
                std::fs::read(root.join("plan/report.json")).unwrap(),
                b"old"
            );
            assert!(!dead_old.exists());
        }
        assert!(!legacy_old.exists());
        assert!(alive.exists());
        drop(staged);
        std::fs::remove_dir_all(&root).unwrap();
    }

    /// A folder name of 245 bytes (legal: the limit is 255) gets siblings within the limit,
    /// the same on every run, distinct from another long name with the same first bytes.
    #[test]
    fn a_long_folder_name_gets_short_siblings() {
        let long = "c".repeat(245);
        let name = name_of(Path::new(&long));
        assert!(
            name.len() + ".partial-4294967295".len() < 255,
            "{}",
            name.len()
        );
        assert_eq!(name, name_of(Path::new(&long)));
        assert_ne!(name, name_of(Path::new(&("c".repeat(244) + "d"))));
        assert_eq!(name_of(Path::new("plan")), "plan");
        let root = std::env::temp_dir().join(format!("agripath-long-{}", std::process::id()));
        let target = root.join("é".repeat(120));
        let staged = StagedFolder::new(&target).unwrap();
        staged.write("report.json", b"{}").unwrap();
        staged.commit().unwrap();
        assert!(target.join("report.json").is_file());
        std::fs::remove_dir_all(&root).unwrap();
    }
}
