//! The CSV of `capmesh shape`: its columns, one line per mesh, and reading the lines of an
//! earlier run back for `--resume`.
//!
//! Each line is complete in itself (RFC 4180 quoting, no line breaks inside fields), so a
//! file cut short by a kill loses at most its last, unterminated line. The columns `bytes`,
//! `modified` and `sha256` identify the file a row was computed from; `--resume` keeps a row
//! when the file still has the same size and modification time (or, with `--resume=hash`, the
//! same SHA-256). The CSV holds no timings, so the same inputs give the same bytes whether
//! the run was resumed or not.

use capmesh::harmonics::HarmonicsReport;
use capmesh::mesh::SurfaceKind;
use capmesh::param::FlattenReport;
use sha2::{Digest, Sha256};
use std::collections::HashMap;
use std::path::Path;

/// CSV columns, in order.
pub const HEADER: &str = "file,status,quality,vertices,faces,kind,z_star,aspect_ratio,ellipsoid_aspect_ratio,\
                          sigma1,sigma2,sigma3,mean_abs_area_distortion,lambda,error,bytes,modified,sha256";

/// How `--resume` decides that a mesh file is unchanged.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum ResumeBy {
    /// Same size and modification time (the default of `--resume`).
    Mtime,
    /// Same SHA-256 of the content (`--resume=hash`): reads every file.
    Hash,
}

/// What identifies a mesh file's content: size, modification time, SHA-256.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Identity {
    pub bytes: String,
    pub modified: String,
    pub sha256: String,
}

impl Identity {
    /// Size and modification time of `path` (empty when it cannot be read).
    pub fn stat(path: &Path) -> Identity {
        let Ok(meta) = std::fs::metadata(path) else { return Identity::default() };
        let modified = meta
            .modified()
            .ok()
            .and_then(|t| t.duration_since(std::time::UNIX_EPOCH).ok())
            .map(|d| format!("{}.{:09}", d.as_secs(), d.subsec_nanos()))
            .unwrap_or_default();
        Identity { bytes: meta.len().to_string(), modified, sha256: String::new() }
    }

    /// [`stat`](Self::stat) and the SHA-256 of the content.
    pub fn full(path: &Path) -> Identity {
        let mut id = Identity::stat(path);
        id.sha256 = sha256(path).unwrap_or_default();
        id
    }

    /// `true` when `earlier` (from a row) names the same content as `self` by `by`.
    pub fn unchanged(&self, earlier: &Identity, by: ResumeBy) -> bool {
        match by {
            ResumeBy::Mtime => !self.bytes.is_empty() && self.bytes == earlier.bytes && !self.modified.is_empty() && self.modified == earlier.modified,
            ResumeBy::Hash => !self.sha256.is_empty() && self.sha256 == earlier.sha256,
        }
    }
}

/// Lowercase hex SHA-256 of the file at `path`.
fn sha256(path: &Path) -> std::io::Result<String> {
    let mut file = std::fs::File::open(path)?;
    let mut hasher = Sha256::new();
    std::io::copy(&mut file, &mut hasher)?;
    Ok(hasher.finalize().iter().map(|b| format!("{b:02x}")).collect())
}

/// The CSV line (without the line break) of one mesh's outcome.
pub fn line(file: &str, result: &Result<(usize, HarmonicsReport), String>, id: &Identity) -> String {
    let file = quote(file);
    let identity = format!("{},{},{}", id.bytes, id.modified, id.sha256);
    match result {
        Ok((faces, r)) => {
            let kind = if r.param.kind == SurfaceKind::OpenDisk { "open" } else { "closed" };
            let [s1, s2, s3] = r.singular_values;
            // The composition factor a closed surface was mapped with (another than asked
            // when it fell back, see `param::lambda_fallback`).
            let lambda = match (&r.param.flatten, kind) {
                (FlattenReport::Closed(f), "closed") => f.lambda.to_string(),
                _ => String::new(),
            };
            format!(
                "{file},ok,{},{},{faces},{kind},{},{},{},{s1},{s2},{s3},{},{lambda},,{identity}",
                r.param.quality, r.vertices, r.z_star, r.aspect_ratio, r.ellipsoid_aspect_ratio, r.param.area_distortion.mean_abs
            )
        }
        Err(e) => format!("{file},failed,,,,,,,,,,,,,{},{identity}", quote(&e.replace(['\n', '\r'], " "))),
    }
}

/// A CSV field in double quotes, inner quotes doubled (RFC 4180).
fn quote(s: &str) -> String {
    format!("\"{}\"", s.replace('"', "\"\""))
}

/// Fields of one CSV line (RFC 4180 quoting, no line breaks inside fields).
fn fields(line: &str) -> Vec<String> {
    let (mut fields, mut field, mut quoted, mut chars) = (Vec::new(), String::new(), false, line.chars().peekable());
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                field.push('"');
                chars.next();
            }
            ('"', _) => quoted = !quoted,
            (',', false) => fields.push(std::mem::take(&mut field)),
            _ => field.push(c),
        }
    }
    fields.push(field);
    fields
}

/// A row of an earlier run: its line as written, its error if it failed, whether its map is
/// poor, and its file's identity.
#[derive(Debug, Clone)]
pub struct EarlierRow {
    pub line: String,
    pub error: Option<String>,
    pub poor: bool,
    pub id: Identity,
}

/// The `aspect_ratio` column of a row (`None` when empty or not a number).
pub fn aspect_ratio_of(line: &str) -> Option<f64> {
    let col = HEADER.split(',').position(|c| c == "aspect_ratio")?;
    fields(line).get(col)?.parse::<f64>().ok().filter(|x| x.is_finite())
}

/// Add the rows of the CSV at `path` (absent: none) to `rows`, by file, replacing rows of
/// the same file. Returns the number of lines ignored (cut short by a kill, or malformed);
/// a file with another header is refused (an older capmesh or another table).
pub fn read_earlier(path: &Path, rows: &mut HashMap<String, EarlierRow>) -> Result<usize, String> {
    let text = match std::fs::read(path) {
        Ok(bytes) => String::from_utf8_lossy(&bytes).into_owned(),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(0),
        Err(e) => return Err(format!("cannot read {} for --resume: {e}", path.display())),
    };
    let mut lines = text.split_inclusive('\n');
    match lines.next() {
        None => return Ok(0),
        Some(h) if h.trim_end_matches(['\n', '\r']) == HEADER => {}
        Some(_) => {
            return Err(format!(
                "{}: its columns are not those of this capmesh shape (an older version or another file); \
                 rerun without --resume, or move the file away",
                path.display()
            ))
        }
    }
    let columns = HEADER.split(',').count();
    let col = |name: &str| HEADER.split(',').position(|c| c == name).unwrap_or(0);
    let mut ignored = 0;
    for raw in lines {
        let Some(line) = raw.strip_suffix('\n') else {
            ignored += 1; // the last line, cut short
            continue;
        };
        let f = fields(line);
        if f.len() != columns || f[col("file")].is_empty() {
            ignored += 1;
            continue;
        }
        let id = Identity { bytes: f[col("bytes")].clone(), modified: f[col("modified")].clone(), sha256: f[col("sha256")].clone() };
        let error = (f[col("status")] == "failed").then(|| f[col("error")].clone());
        let poor = f[col("quality")] == "poor";
        rows.insert(f[col("file")].clone(), EarlierRow { line: line.to_string(), error, poor, id });
    }
    Ok(ignored)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_read_back_with_their_identity() {
        let id = Identity { bytes: "12".into(), modified: "1.000000002".into(), sha256: "ab".into() };
        let text = line("dir/a \"b\", c.obj", &Err("bad\nmesh, \"quoted\"".into()), &id);
        let f = fields(&text);
        assert_eq!(f.len(), HEADER.split(',').count(), "{text}");
        assert_eq!(f[0], "dir/a \"b\", c.obj");
        assert_eq!(f[1], "failed");
        assert_eq!(f[14], "bad mesh, \"quoted\"");
        assert_eq!(&f[15..], ["12", "1.000000002", "ab"]);
    }

    #[test]
    fn unchanged_needs_a_known_identity() {
        let a = Identity { bytes: "1".into(), modified: "2.0".into(), sha256: "x".into() };
        assert!(a.unchanged(&a, ResumeBy::Mtime) && a.unchanged(&a, ResumeBy::Hash));
        let b = Identity { modified: "3.0".into(), ..a.clone() };
        assert!(!b.unchanged(&a, ResumeBy::Mtime) && b.unchanged(&a, ResumeBy::Hash));
        assert!(!Identity::default().unchanged(&Identity::default(), ResumeBy::Mtime));
        assert!(!Identity::default().unchanged(&Identity::default(), ResumeBy::Hash));
    }
}
