//! A command's output files: each is written complete under a temporary name next to its
//! target (`capmesh::io::atomic`), and all are renamed into place together once the last is
//! written, unless a signal arrived meanwhile. A failed or interrupted command leaves no
//! partial file and every earlier file of those names as it was.

use crate::failure::Failure;
use capmesh::io::atomic::{self, StagedFile};
use std::path::Path;

/// Stage `value` as pretty JSON at `path`.
pub fn stage_json(path: &Path, value: &impl serde::Serialize) -> Result<StagedFile, Failure> {
    let text = serde_json::to_string_pretty(value).map_err(|e| format!("cannot write report {}: {e}", path.display()))?;
    Ok(atomic::stage(path, |w| w.write_all((text + "\n").as_bytes()))?)
}

/// Stage `mesh` at `path` (format from the extension).
pub fn stage_mesh(path: &Path, mesh: &capmesh::TriMesh) -> Result<StagedFile, Failure> {
    Ok(capmesh::io::stage_mesh(path, mesh)?)
}

/// Rename the staged files over their targets, unless a signal arrived (then they are
/// removed and the command is interrupted while doing `what`).
pub fn commit(files: Vec<StagedFile>, what: impl FnOnce() -> String) -> Result<(), Failure> {
    crate::interrupt::check(|| format!("{}; nothing written (earlier files untouched)", what()))?;
    Ok(atomic::commit_all(files)?)
}

/// Refuse two outputs of one command that name the same file.
pub fn refuse_duplicates(paths: &[&Path]) -> Result<(), String> {
    for (i, a) in paths.iter().enumerate() {
        for b in &paths[i + 1..] {
            if a == b || capmesh::io::same_file(a, b) {
                return Err(format!("two outputs name the same file {}; give each its own path", a.display()));
            }
        }
    }
    Ok(())
}
