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
pub struct StagedFolder {
    target: PathBuf,
    staging: PathBuf,
    committed: bool,
}

impl StagedFolder {
    pub fn new(target: &Path) -> std::io::Result<Self> {
        let parent = target
            .parent()
            .filter(|parent| !parent.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        std::fs::create_dir_all(parent)?;
        let name = target
            .file_name()
            .map(|name| name.to_string_lossy().into_owned())
            .unwrap_or_else(|| "out".into());
        remove_abandoned_stagings(parent, &name);
        let staging = parent.join(format!(".{name}.partial-{}", std::process::id()));
        if staging.exists() {
            std::fs::remove_dir_all(&staging)?;
        }
        std::fs::create_dir_all(&staging)?;
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

    pub fn write(&self, name: &str, bytes: &[u8]) -> std::io::Result<()> {
        std::fs::write(self.path(name), bytes)
    }

    /// Moves the staged folder into place, replacing what was there.
    pub fn commit(mut self) -> std::io::Result<PathBuf> {
        if self.target.exists() {
            let old = self.staging.with_extension("old");
            std::fs::rename(&self.target, &old)?;
            std::fs::rename(&self.staging, &self.target)?;
            std::fs::remove_dir_all(&old)?;
        } else {
            std::fs::rename(&self.staging, &self.target)?;
        }
        self.committed = true;
        Ok(self.target.clone())
    }
}

/// Removes `.NAME.partial-PID` (and `.old`) folders left by a run that was killed while it
/// wrote (an interrupt ends the program before it can clean up): those whose process is gone.
/// Where running processes cannot be listed (no `/proc`), nothing is removed.
fn remove_abandoned_stagings(parent: &Path, name: &str) {
    let proc = Path::new("/proc");
    if !proc.join("self").exists() {
        return;
    }
    let prefix = format!(".{name}.partial-");
    let Ok(entries) = std::fs::read_dir(parent) else {
        return;
    };
    for entry in entries.flatten() {
        let file_name = entry.file_name().to_string_lossy().into_owned();
        let Some(rest) = file_name.strip_prefix(&prefix) else {
            continue;
        };
        let pid = rest.strip_suffix(".old").unwrap_or(rest);
        if pid.parse::<u32>().is_ok() && !proc.join(pid).exists() {
            let _ = std::fs::remove_dir_all(entry.path());
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
        let staged = StagedFolder::new(&target).unwrap();
        staged.write("a.txt", b"new").unwrap();
        staged.commit().unwrap();
        assert!(!target.join("stale.txt").exists());
        assert_eq!(std::fs::read(target.join("a.txt")).unwrap(), b"new");
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn stagings_of_dead_runs_are_removed_and_live_ones_kept() {
        let root = std::env::temp_dir().join(format!("agripath-abandoned-{}", std::process::id()));
        // PID 4294967295 cannot exist; this test's own PID is alive.
        let dead = root.join(".plan.partial-4294967295");
        let alive = root.join(format!(".plan.partial-{}.old", std::process::id()));
        std::fs::create_dir_all(&dead).unwrap();
        std::fs::create_dir_all(&alive).unwrap();
        let staged = StagedFolder::new(&root.join("plan")).unwrap();
        if Path::new("/proc/self").exists() {
            assert!(!dead.exists());
        }
        assert!(alive.exists());
        drop(staged);
        std::fs::remove_dir_all(&root).unwrap();
    }
}
