//! Object File Format (OFF): an optional `OFF` / `COFF` / `NOFF` / `STOFF` ... keyword, the
//! counts `nv nf [ne]` (on the keyword's line or the next one), `nv` vertex lines (first three
//! numbers used) and `nf` face lines `k i1 .. ik [colour]` (0-based, fan-triangulated). `#`
//! comments and blank lines are skipped. Binary OFF and 4D / nD OFF are refused.

use std::io::Write;
use std::path::Path;

use super::error::{Location, ReadError};
use super::text::{is_blank, parse_i64, read_point, show, strip_comment, tokens, Lines};
use super::{fan, parse_error};
use crate::mesh::TriMesh;

/// Does this token look like an OFF keyword (`OFF`, `COFF`, `STCNOFF`, `4OFF`, `nOFF`, ...)?
fn is_keyword(tok: &[u8]) -> bool {
    tok.len() >= 3 && tok[tok.len() - 3..].eq_ignore_ascii_case(b"OFF")
}

/// Parse an OFF file's bytes.
pub(crate) fn read(path: &Path, data: &[u8]) -> Result<TriMesh, ReadError> {
    let mut lines = Lines::new(data)
        .map(|(n, l)| (n, strip_comment(l)))
        .filter(|(_, l)| !is_blank(l));
    let err = |line: usize, message: String| parse_error(path, Location::Line(line), message);

    let Some((first_line, first)) = lines.next() else {
        return Err(ReadError::Empty {
            path: path.to_path_buf(),
        });
    };
    let mut toks: Vec<&[u8]> = tokens(first).collect();
    let mut counts_line = first_line;
    if toks.first().is_some_and(|t| is_keyword(t)) {
        let prefix = &toks[0][..toks[0].len() - 3];
        if prefix.contains(&b'4') || prefix.contains(&b'n') {
            return Err(err(
                first_line,
                format!(
                    "'{}' (4D or n-dimensional OFF) is not supported; convert to a 3D OFF, OBJ or PLY",
                    show(toks[0])
                ),
            ));
        }
        if toks
            .iter()
            .skip(1)
            .any(|t| t.eq_ignore_ascii_case(b"BINARY"))
        {
            return Err(err(
                first_line,
                "binary OFF is not supported; convert it to ASCII OFF, OBJ or PLY".into(),
            ));
        }
        toks.remove(0);
        if toks.is_empty() {
            let Some((n, l)) = lines.next() else {
                return Err(ReadError::Empty {
                    path: path.to_path_buf(),
                });
            };
            counts_line = n;
            toks = tokens(l).collect();
        }
    }
    let count = |k: usize, what: &str| -> Result<usize, ReadError> {
        let tok = toks.get(k).ok_or_else(|| {
            err(
                counts_line,
                format!("missing the number of {what}; expected 'nv nf ne' after 'OFF'"),
            )
        })?;
        parse_i64(tok)
            .and_then(|v| usize::try_from(v).ok())
            .ok_or_else(|| {
                err(
                    counts_line,
                    format!(
                        "'{}' is not a valid number of {what}; expected 'nv nf ne' after 'OFF'",
                        show(tok)
                    ),
                )
            })
    };
    let nv = count(0, "vertices")?;
    let nf = count(1, "faces")?;
    if nv > u32::MAX as usize {
        return Err(err(
            counts_line,
            format!("{nv} vertices are more than capmesh supports"),
        ));
    }

    let mut vertices = Vec::with_capacity(nv.min(data.len() / 6));
    for i in 0..nv {
        let Some((line, l)) = lines.next() else {
            return Err(ReadError::Truncated {
                path: path.to_path_buf(),
                what: "vertices".into(),
                expected: nv as u64,
                found: i as u64,
            });
        };
        let p = read_point(&mut tokens(l), path, Location::Line(line), |k| format!("a vertex needs 3 coordinates, found {k}; fix this line"))?;
        vertices.push(p);
    }

    let mut faces = Vec::with_capacity(nf.min(data.len() / 8));
    let mut polygon = Vec::with_capacity(8);
    for i in 0..nf {
        let Some((line, l)) = lines.next() else {
            return Err(ReadError::Truncated {
                path: path.to_path_buf(),
                what: "faces".into(),
                expected: nf as u64,
                found: i as u64,
            });
        };
        let mut it = tokens(l);
        let k = it
            .next()
            .and_then(parse_i64)
            .ok_or_else(|| err(line, "a face line must start with its vertex count".into()))?;
        if k < 3 {
            return Err(err(
                line,
                format!("a face needs at least 3 vertices, this one has {k}; delete this face"),
            ));
        }
        polygon.clear();
        for j in 0..k {
            let tok = it.next().ok_or_else(|| {
                err(
                    line,
                    format!("the face lists {k} vertices but has only {j} indices"),
                )
            })?;
            let index = parse_i64(tok).ok_or_else(|| {
                err(
                    line,
                    format!("'{}' is not a vertex index; fix this face", show(tok)),
                )
            })?;
            if index < 0 || index as u64 >= nv as u64 {
                return Err(ReadError::IndexOutOfRange {
                    path: path.to_path_buf(),
                    at: Location::Line(line),
                    index,
                    n_vertices: nv,
                });
            }
            polygon.push(index as u32);
        }
        fan(&polygon, &mut faces);
    }
    Ok(TriMesh::new(vertices, faces))
}

/// Write OFF. The mesh has been checked by the caller.
pub(crate) fn write(w: &mut dyn Write, mesh: &TriMesh) -> std::io::Result<()> {
    writeln!(w, "OFF")?;
    writeln!(w, "# written by capmesh")?;
    writeln!(w, "{} {} 0", mesh.n_vertices(), mesh.n_faces())?;
    for p in &mesh.vertices {
        writeln!(w, "{:?} {:?} {:?}", p[0], p[1], p[2])?;
    }
    for f in &mesh.faces {
        writeln!(w, "3 {} {} {}", f[0], f[1], f[2])?;
    }
    Ok(())
}
