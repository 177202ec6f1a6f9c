//! Writing a whole folder or nothing: the files go into a hidden sibling folder, which is renamed
//! to the target only once everything is written.

use std::io;
use std::path::{Path, PathBuf};

use super::files::File;

/// Why the folder could not be created.
#[derive(Debug)]
pub enum StagingError {
    /// The target exists and is not an empty folder.
    NotEmpty(PathBuf),
    /// The target's parent folder does not exist.
    NoParent(PathBuf),
    /// Reading the target or writing a file failed (nothing was left behind).
    Io(PathBuf, io::Error),
}

impl std::fmt::Display for StagingError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::NotEmpty(path) => write!(
                f,
                "{} already exists and is not an empty folder: nothing was written",
                path.display()
            ),
            Self::NoParent(path) => write!(
                f,
                "the folder {} does not exist: create it first",
                path.display()
            ),
            Self::Io(path, e) => write!(f, "{}: {e} (nothing was written)", path.display()),
        }
    }
}

/// Creates `target` with `files`, or leaves the file system as it was.
pub fn create_folder(target: &Path, files: &[File]) -> Result<(), StagingError> {
    check_target(target)?;
    let staging = staging_path(target);
    let result = write_all(&staging, files).and_then(|()| move_into_place(&staging, target));
    if result.is_err() {
        // Best effort: the staging folder is ours alone; the target was never touched.
        let _ = std::fs::remove_dir_all(&staging);
    }
    result
}

/// The target may be missing or an empty folder; its parent must exist.
fn check_target(target: &Path) -> Result<(), StagingError> {
    match std::fs::read_dir(target).map(|mut entries| entries.next().is_none()) {
        Ok(true) => Ok(()),
        Ok(false) => Err(StagingError::NotEmpty(target.to_path_buf())),
        Err(e) if e.kind() == io::ErrorKind::NotFound => {
            let parent = parent_of(target);
            if parent.is_dir() {
                Ok(())
            } else {
                Err(StagingError::NoParent(parent))
            }
        }
        Err(_) if target.exists() => Err(StagingError::NotEmpty(target.to_path_buf())),
        Err(e) => Err(StagingError::Io(target.to_path_buf(), e)),
    }
}

fn parent_of(target: &Path) -> PathBuf {
    match target.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// A hidden sibling of `target`, on the same file system so that the rename is atomic.
fn staging_path(target: &Path) -> PathBuf {
    let name = target
        .file_name()
        .map_or_else(|| "crate".into(), |n| n.to_string_lossy().into_owned());
    parent_of(target).join(format!(".{name}.drivegen-new-{}", std::process::id()))
}

fn write_all(staging: &Path, files: &[File]) -> Result<(), StagingError> {
    for file in files {
        let path = staging.join(&file.path);
        if let Some(folder) = path.parent() {
            std::fs::create_dir_all(folder).map_err(|e| StagingError::Io(folder.into(), e))?;
        }
        std::fs::write(&path, &file.bytes).map_err(|e| StagingError::Io(path.clone(), e))?;
    }
    Ok(())
}

/// Renames the staging folder to `target`, replacing an empty folder there.
fn move_into_place(staging: &Path, target: &Path) -> Result<(), StagingError> {
    if target.is_dir() {
        std::fs::remove_dir(target).map_err(|e| StagingError::Io(target.into(), e))?;
    }
    std::fs::rename(staging, target).map_err(|e| StagingError::Io(target.into(), e))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp(label: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("drivegen-staging-{label}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn file(path: &str) -> File {
        File {
            path: path.into(),
            bytes: b"x".to_vec(),
        }
    }

    #[test]
    fn a_failed_write_leaves_no_trace() {
        let dir = temp("fail");
        let target = dir.join("crate");
        // `a` is a file, so `a/b` cannot be created: the second write fails.
        let error = create_folder(&target, &[file("a"), file("a/b")]).unwrap_err();
        assert!(matches!(error, StagingError::Io(..)), "{error}");
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn an_empty_folder_is_filled() {
        let dir = temp("empty");
        let target = dir.join("crate");
        std::fs::create_dir(&target).unwrap();
        create_folder(&target, &[file("src/lib.rs")]).unwrap();
        assert_eq!(std::fs::read(target.join("src/lib.rs")).unwrap(), b"x");
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn a_missing_parent_is_refused() {
        let dir = temp("parent");
        let error = create_folder(&dir.join("no/such/crate"), &[file("a")]).unwrap_err();
        assert!(matches!(error, StagingError::NoParent(_)), "{error}");
        std::fs::remove_dir_all(dir).unwrap();
    }
}
