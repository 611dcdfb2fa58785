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
}
