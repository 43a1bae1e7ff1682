//! Atomic outputs: a file is written to a temporary sibling and renamed into place, a directory is
//! assembled in a temporary sibling and renamed into place; a failed run leaves nothing behind.

use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};

/// A failed output operation: what was attempted, on which path, and the I/O error.
#[derive(Debug, thiserror::Error)]
#[error("{message}")]
pub struct OutputError {
    /// What failed, naming the path (e.g. `cannot create directory out/cards`).
    pub message: String,
    /// The underlying I/O error, when there is one.
    #[source]
    pub source: Option<std::io::Error>,
}

impl OutputError {
    fn io(message: String) -> impl FnOnce(std::io::Error) -> Self {
        move |e| Self { message, source: Some(e) }
    }

    fn plain(message: String) -> Self {
        Self { message, source: None }
    }
}

/// Result of an output operation.
pub type Result<T, E = OutputError> = std::result::Result<T, E>;

/// Writes `contents` to `path` atomically (temporary file in the same directory, fsync, rename).
pub fn write_atomic(path: &Path, contents: &[u8]) -> Result<()> {
    let dir = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    fs::create_dir_all(dir).map_err(OutputError::io(format!("cannot create directory {}", dir.display())))?;
    let name = path.file_name().ok_or_else(|| OutputError::plain(format!("{} has no file name", path.display())))?;
    let tmp = dir.join(format!(".{}.tmp-{}", name.to_string_lossy(), std::process::id()));
    let result = (|| -> Result<()> {
        let mut f = fs::File::create(&tmp).map_err(OutputError::io(format!("cannot create {}", tmp.display())))?;
        f.write_all(contents).map_err(OutputError::io(format!("cannot write {}", tmp.display())))?;
        f.sync_all().ok();
        fs::rename(&tmp, path).map_err(OutputError::io(format!(
            "cannot move {} to {}",
            tmp.display(),
            path.display()
        )))?;
        Ok(())
    })();
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    result
}

/// A directory built under a temporary name and moved into place by [`StagedDir::commit`].
/// Dropped without commit, it removes itself.
#[derive(Debug)]
pub struct StagedDir {
    staging: PathBuf,
    target: PathBuf,
    committed: bool,
}

impl StagedDir {
    /// Starts staging `target` (its parent is created).
    pub fn new(target: &Path) -> Result<Self> {
        let parent = target.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
        fs::create_dir_all(parent).map_err(OutputError::io(format!("cannot create directory {}", parent.display())))?;
        let name = target
            .file_name()
            .ok_or_else(|| OutputError::plain(format!("{} has no directory name", target.display())))?;
        let staging = parent.join(format!(".{}.staging-{}", name.to_string_lossy(), std::process::id()));
        if staging.exists() {
            fs::remove_dir_all(&staging).map_err(OutputError::io(format!("cannot clear {}", staging.display())))?;
        }
        fs::create_dir_all(&staging).map_err(OutputError::io(format!("cannot create {}", staging.display())))?;
        Ok(Self { staging, target: target.to_path_buf(), committed: false })
    }

    /// Path of `relative` inside the staging directory.
    #[must_use]
    pub fn path(&self, relative: &str) -> PathBuf {
        self.staging.join(relative)
    }

    /// Writes a file into the staging directory.
    pub fn write(&self, relative: &str, contents: &[u8]) -> Result<()> {
        let p = self.path(relative);
        if let Some(d) = p.parent() {
            fs::create_dir_all(d).map_err(OutputError::io(format!("cannot create {}", d.display())))?;
        }
        fs::write(&p, contents).map_err(OutputError::io(format!("cannot write {}", p.display())))
    }

    /// Replaces the target directory by the staged one.
    pub fn commit(mut self) -> Result<PathBuf> {
        if self.target.exists() {
            let old = self.staging.with_extension("old");
            let _ = fs::remove_dir_all(&old);
            fs::rename(&self.target, &old)
                .map_err(OutputError::io(format!("cannot move away {}", self.target.display())))?;
            fs::rename(&self.staging, &self.target)
                .map_err(OutputError::io(format!("cannot move {} into place", self.target.display())))?;
            let _ = fs::remove_dir_all(&old);
        } else {
            fs::rename(&self.staging, &self.target)
                .map_err(OutputError::io(format!("cannot move {} into place", self.target.display())))?;
        }
        self.committed = true;
        Ok(self.target.clone())
    }
}

impl Drop for StagedDir {
    fn drop(&mut self) {
        if !self.committed {
            let _ = fs::remove_dir_all(&self.staging);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn staged_dir_leaves_nothing_when_dropped() {
        let root = tempfile::tempdir().unwrap();
        let target = root.path().join("out");
        {
            let s = StagedDir::new(&target).unwrap();
            s.write("a/b.txt", b"x").unwrap();
        }
        assert!(!target.exists());
        assert_eq!(fs::read_dir(root.path()).unwrap().count(), 0);
        let s = StagedDir::new(&target).unwrap();
        s.write("c.txt", b"y").unwrap();
        s.commit().unwrap();
        assert_eq!(fs::read(target.join("c.txt")).unwrap(), b"y");
    }

    #[test]
    fn atomic_write_replaces_file() {
        let root = tempfile::tempdir().unwrap();
        let p = root.path().join("f.txt");
        write_atomic(&p, b"one").unwrap();
        write_atomic(&p, b"two").unwrap();
        assert_eq!(fs::read(&p).unwrap(), b"two");
        assert_eq!(fs::read_dir(root.path()).unwrap().count(), 1);
    }
}
