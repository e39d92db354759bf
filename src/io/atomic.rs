//! Atomic file output: every file capmesh writes (meshes, reports, CSV, coefficients) goes
//! through here, so that a target path holds either its earlier content or the complete new
//! file, never a part of one.
//!
//! The bytes go to a temporary file in the target's directory, named
//! `.capmesh-tmp-PID-N.NAME` (hidden, same file system, so the final step is a rename; the
//! name keeps the target's extension for writers that choose a format by it). When the
//! writer is done the temporary is flushed and synced to disk ([`AtomicFile::finish`]); the
//! [`StagedFile`] this gives is renamed over the target by [`StagedFile::commit`]. Dropping
//! either before that removes the temporary, so an error, a panic or a cancellation (the
//! command line stops at `SIGINT`/`SIGTERM` through [`crate::progress::Progress`]) leaves the
//! target untouched. Staging several files and committing them together keeps a mesh and
//! its report from different runs apart.
//!
//! A process killed outright (`SIGKILL`, power loss) cannot remove its temporary; the next
//! write to the same directory (Linux) removes temporaries whose process no longer runs.
//!
//! The target keeps the permissions of the file it replaces; a symbolic link at the target
//! stays a link and the file it points to is replaced. A target that is a directory is
//! refused before anything is written.

use std::fs::{self, File, OpenOptions};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use super::WriteError;

/// Marker in the names of temporary files: `.capmesh-tmp-PID-N.NAME`.
const TEMP_MARKER: &str = ".capmesh-tmp-";

/// A file being written to a temporary next to its target. Implements [`Write`] (buffered).
#[derive(Debug)]
pub struct AtomicFile {
    writer: BufWriter<File>,
    staged: StagedFile,
}

/// A complete file, synced to disk under its temporary name, waiting for
/// [`StagedFile::commit`]. Dropped uncommitted, the temporary is removed.
#[derive(Debug)]
pub struct StagedFile {
    target: PathBuf,
    temp: PathBuf,
    /// `true` while the temporary exists and is ours to remove.
    armed: bool,
}

impl AtomicFile {
    /// Start writing `target`: create its temporary. Fails when `target` is a directory or
    /// its directory does not exist or is not writable.
    pub fn create(target: &Path) -> io::Result<AtomicFile> {
        let target = resolve_link(target);
        if fs::metadata(&target).is_ok_and(|m| m.is_dir()) {
            return Err(is_a_directory());
        }
        let dir = directory_of(&target);
        let name = target.file_name().ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "the path has no file name"))?;
        remove_stale_temporaries(dir);
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        // A name taken (by an earlier process that had this PID) is skipped.
        let mut attempt = 0;
        let (temp, file) = loop {
            let temp_name = format!("{TEMP_MARKER}{}-{}.{}", std::process::id(), COUNTER.fetch_add(1, Ordering::Relaxed), name.to_string_lossy());
            let temp = dir.join(temp_name);
            match OpenOptions::new().write(true).create_new(true).open(&temp) {
                Ok(file) => break (temp, file),
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists && attempt < 100 => attempt += 1,
                Err(e) => return Err(e),
            }
        };
        Ok(AtomicFile {
            writer: BufWriter::with_capacity(1 << 20, file),
            staged: StagedFile { target, temp, armed: true },
        })
    }

    /// The path the file will have once committed.
    pub fn target(&self) -> &Path {
        &self.staged.target
    }

    /// Flush and sync the temporary to disk; the target is not touched yet.
    pub fn finish(self) -> io::Result<StagedFile> {
        // On an error `staged` is dropped here, which removes the temporary.
        let AtomicFile { writer, staged } = self;
        writer.into_inner().map_err(|e| e.into_error())?.sync_all()?;
        Ok(staged)
    }

    /// [`finish`](Self::finish) and [`StagedFile::commit`].
    pub fn commit(self) -> io::Result<()> {
        self.finish()?.commit()
    }
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.writer.write(buf)
    }

    fn write_all(&mut self, buf: &[u8]) -> io::Result<()> {
        self.writer.write_all(buf)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.writer.flush()
    }
}

impl StagedFile {
    /// The path the file will have once committed.
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// The temporary file holding the content until [`commit`](Self::commit).
    pub fn temporary(&self) -> &Path {
        &self.temp
    }

    /// Rename the temporary over the target (atomic on POSIX file systems) and sync the
    /// directory. The target keeps the permissions of the file it replaces.
    pub fn commit(mut self) -> io::Result<()> {
        if fs::metadata(&self.target).is_ok_and(|m| m.is_dir()) {
            return Err(is_a_directory());
        }
        if let Ok(old) = fs::metadata(&self.target) {
            // Best effort: a file we may replace but not chmod keeps the default mode.
            let _ = fs::set_permissions(&self.temp, old.permissions());
        }
        fs::rename(&self.temp, &self.target)?;
        self.armed = false;
        sync_directory(directory_of(&self.target));
        Ok(())
    }
}

impl Drop for StagedFile {
    fn drop(&mut self) {
        if self.armed {
            let _ = fs::remove_file(&self.temp);
        }
    }
}

/// Write `target` atomically with `write`, which gets a buffered writer to the temporary;
/// errors name `target`.
pub fn write_atomically(target: &Path, write: impl FnOnce(&mut dyn Write) -> io::Result<()>) -> Result<(), WriteError> {
    stage(target, write)?.commit().map_err(|source| io_error(target, source))
}

/// Like [`write_atomically`] but leave the complete file staged: commit it (with others)
/// when everything has been written.
pub fn stage(target: &Path, write: impl FnOnce(&mut dyn Write) -> io::Result<()>) -> Result<StagedFile, WriteError> {
    let named = |source| io_error(target, source);
    let mut file = AtomicFile::create(target).map_err(named)?;
    write(&mut file).map_err(named)?;
    file.finish().map_err(named)
}

/// Stage `target` through a writer that takes a path (a C++ library, a plotting backend):
/// `write` gets the temporary's path, which keeps the target's extension.
pub fn stage_path(target: &Path, write: impl FnOnce(&Path) -> io::Result<()>) -> Result<StagedFile, WriteError> {
    let named = |source| io_error(target, source);
    let file = AtomicFile::create(target).map_err(named)?;
    let staged = file.finish().map_err(named)?;
    write(staged.temporary()).map_err(named)?;
    File::open(staged.temporary()).and_then(|f| f.sync_all()).map_err(named)?;
    Ok(staged)
}

/// Write `bytes` to `target` atomically.
pub fn write_bytes(target: &Path, bytes: &[u8]) -> Result<(), WriteError> {
    write_atomically(target, |w| w.write_all(bytes))
}

/// Commit staged files in order; the first failure stops (the rest are removed on drop).
pub fn commit_all(files: Vec<StagedFile>) -> Result<(), WriteError> {
    for file in files {
        let target = file.target().to_path_buf();
        file.commit().map_err(|source| io_error(&target, source))?;
    }
    Ok(())
}

fn io_error(path: &Path, source: io::Error) -> WriteError {
    WriteError::Io { path: path.to_path_buf(), source }
}

/// The directory a file of `path` lives in (`.` for a bare name).
fn directory_of(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// The file a symbolic link at `path` points to (so the link survives the rename), else `path`.
fn resolve_link(path: &Path) -> PathBuf {
    match fs::symlink_metadata(path) {
        Ok(m) if m.file_type().is_symlink() => fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf()),
        _ => path.to_path_buf(),
    }
}

fn is_a_directory() -> io::Error {
    #[cfg(unix)]
    {
        io::Error::from_raw_os_error(libc::EISDIR)
    }
    #[cfg(not(unix))]
    {
        io::Error::new(io::ErrorKind::Other, "Is a directory")
    }
}

/// Make the rename durable (POSIX; elsewhere and on file systems that refuse, nothing).
fn sync_directory(dir: &Path) {
    #[cfg(unix)]
    if let Ok(d) = File::open(dir) {
        let _ = d.sync_all();
    }
    #[cfg(not(unix))]
    let _ = dir;
}

/// Remove temporaries in `dir` left by capmesh processes that no longer run (killed before
/// they could clean up). Linux only: a process is running when `/proc/PID` exists.
fn remove_stale_temporaries(dir: &Path) {
    #[cfg(target_os = "linux")]
    {
        let Ok(entries) = fs::read_dir(dir) else { return };
        for entry in entries.flatten() {
            let name = entry.file_name();
            let Some(rest) = name.to_str().and_then(|n| n.strip_prefix(TEMP_MARKER)) else { continue };
            let Some(pid) = rest.split('-').next().and_then(|p| p.parse::<u32>().ok()) else { continue };
            if pid != std::process::id() && !Path::new("/proc").join(pid.to_string()).exists() {
                let _ = fs::remove_file(entry.path());
            }
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = dir;
}

/// `true` when `name` is one of this module's temporary file names.
pub fn is_temporary_name(name: &str) -> bool {
    name.starts_with(TEMP_MARKER)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(tag: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("capmesh-atomic-{tag}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
        v.sort();
        v
    }

    #[test]
    fn a_failed_write_leaves_the_earlier_file_and_no_temporary() {
        let dir = scratch("fail");
        let target = dir.join("out.txt");
        fs::write(&target, "earlier\n").unwrap();
        let err = write_atomically(&target, |w| {
            w.write_all(b"half of the new")?;
            Err(io::Error::other("disk on fire"))
        })
        .unwrap_err();
        assert!(err.to_string().contains("out.txt") && err.to_string().contains("disk on fire"), "{err}");
        assert_eq!(fs::read_to_string(&target).unwrap(), "earlier\n");
        assert_eq!(names(&dir), ["out.txt"]);
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn staged_files_appear_only_when_committed() {
        let dir = scratch("stage");
        let target = dir.join("mesh.obj");
        let staged = stage(&target, |w| w.write_all(b"v 0 0 0\n")).unwrap();
        assert!(!target.exists());
        assert!(staged.temporary().to_string_lossy().ends_with(".mesh.obj"), "{:?}", staged.temporary());
        drop(staged);
        assert!(names(&dir).is_empty(), "{:?}", names(&dir));
        let staged = stage(&target, |w| w.write_all(b"v 1 1 1\n")).unwrap();
        commit_all(vec![staged]).unwrap();
        assert_eq!(fs::read_to_string(&target).unwrap(), "v 1 1 1\n");
        assert_eq!(names(&dir), ["mesh.obj"]);
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_directory_target_is_refused_before_writing() {
        let dir = scratch("dir");
        let target = dir.join("sub");
        fs::create_dir(&target).unwrap();
        let err = write_bytes(&target, b"x").unwrap_err();
        assert!(err.to_string().contains("is a directory"), "{err}");
        assert_eq!(names(&dir), ["sub"]);
        fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn links_and_permissions_are_kept() {
        use std::os::unix::fs::{symlink, PermissionsExt};
        let dir = scratch("link");
        let real = dir.join("real.txt");
        fs::write(&real, "old").unwrap();
        fs::set_permissions(&real, fs::Permissions::from_mode(0o640)).unwrap();
        let link = dir.join("link.txt");
        symlink(&real, &link).unwrap();
        write_bytes(&link, b"new").unwrap();
        assert!(fs::symlink_metadata(&link).unwrap().file_type().is_symlink());
        assert_eq!(fs::read_to_string(&real).unwrap(), "new");
        assert_eq!(fs::metadata(&real).unwrap().permissions().mode() & 0o777, 0o640);
        fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn temporaries_of_dead_processes_are_removed() {
        let dir = scratch("stale");
        // PIDs are below 2^22 on Linux: this one never runs.
        let stale = dir.join(format!("{TEMP_MARKER}4294967294-0.out.obj"));
        fs::write(&stale, "partial").unwrap();
        let mine = dir.join(format!("{TEMP_MARKER}{}-999999.other.obj", std::process::id()));
        fs::write(&mine, "in progress").unwrap();
        write_bytes(&dir.join("out.obj"), b"done").unwrap();
        assert!(!stale.exists());
        assert!(mine.exists(), "a running process's temporary stays");
        fs::remove_dir_all(&dir).unwrap();
    }
}
