//! Wavefront OBJ: `v x y z [...]` and `f` records with `a`, `a/b`, `a/b/c` or `a//c` corners,
//! 1-based or negative (relative) indices; polygons are fan-triangulated; comments and every
//! other record (`vn`, `vt`, `usemtl`, `g`, `l`, ...) are ignored. Written with full `f64`
//! precision.

use std::io::Write;
use std::path::Path;

use super::error::{Location, ReadError};
use super::text::{parse_i64, read_point, show, strip_comment, tokens, Lines};
use super::{fan, parse_error};
use super::VertexProperties;
use crate::mesh::TriMesh;

/// Parse an OBJ file's bytes.
pub(crate) fn read(path: &Path, data: &[u8]) -> Result<TriMesh, ReadError> {
    let mut vertices: Vec<[f64; 3]> = Vec::with_capacity(data.len() / 64);
    let mut faces: Vec<[u32; 3]> = Vec::with_capacity(data.len() / 32);
    // Positive indices not yet defined when their face was read: (line, index as written).
    let mut pending: Vec<(usize, i64)> = Vec::new();
    let mut polygon: Vec<u32> = Vec::with_capacity(8);

    for (line, raw) in Lines::new(data) {
        let mut toks = tokens(strip_comment(raw));
        let at = Location::Line(line);
        match toks.next() {
            Some(b"v") => {
                let p = read_point(&mut toks, path, at, |k| format!("a 'v' record needs 3 coordinates, found {k}; fix or delete this line"))?;
                if vertices.len() >= u32::MAX as usize {
                    return Err(parse_error(
                        path,
                        at,
                        "more than 4294967295 vertices".into(),
                    ));
                }
                vertices.push(p);
            }
            Some(b"f") => {
                polygon.clear();
                for tok in toks {
                    let head = tok.split(|&b| b == b'/').next().unwrap_or(tok);
                    let index = parse_i64(head).ok_or_else(|| {
                        parse_error(
                            path,
                            at,
                            format!(
                                "'{}' is not a vertex index (expected 'a', 'a/b', 'a/b/c' or \
                                 'a//c'); fix this face",
                                show(tok)
                            ),
                        )
                    })?;
                    let n = vertices.len() as i64;
                    let resolved = match index {
                        i if i > 0 => i - 1,
                        i if i < 0 => n + i,
                        _ => -1,
                    };
                    if resolved < 0 || resolved > i64::from(u32::MAX - 1) {
                        return Err(ReadError::IndexOutOfRange {
                            path: path.to_path_buf(),
                            at,
                            index,
                            n_vertices: vertices.len(),
                        });
                    }
                    if resolved >= n {
                        pending.push((line, index));
                    }
                    polygon.push(resolved as u32);
                }
                if polygon.len() < 3 {
                    return Err(parse_error(
                        path,
                        at,
                        format!(
                            "a face needs at least 3 vertices, this one has {}; delete this line",
                            polygon.len()
                        ),
                    ));
                }
                fan(&polygon, &mut faces);
            }
            _ => {}
        }
    }
    if let Some(&(line, index)) = pending
        .iter()
        .find(|&&(_, index)| index > vertices.len() as i64)
    {
        return Err(ReadError::IndexOutOfRange {
            path: path.to_path_buf(),
            at: Location::Line(line),
            index,
            n_vertices: vertices.len(),
        });
    }
    Ok(TriMesh::new(vertices, faces))
}

/// Write OBJ (1-based indices), with a `vt` line per vertex and `f v/vt` faces when `extra`
/// has texture coordinates. The mesh and `extra` have been checked by the caller.
pub(crate) fn write(w: &mut dyn Write, mesh: &TriMesh, extra: &VertexProperties) -> std::io::Result<()> {
    writeln!(w, "# written by capmesh")?;
    writeln!(w, "# V={} F={}", mesh.n_vertices(), mesh.n_faces())?;
    for p in &mesh.vertices {
        writeln!(w, "v {:?} {:?} {:?}", p[0], p[1], p[2])?;
    }
    if let Some(uv) = &extra.uv {
        for t in uv {
            writeln!(w, "vt {:?} {:?}", t[0], t[1])?;
        }
        for f in &mesh.faces {
            let [a, b, c] = f.map(|v| v + 1);
            writeln!(w, "f {a}/{a} {b}/{b} {c}/{c}")?;
        }
        return Ok(());
    }
    for f in &mesh.faces {
        writeln!(w, "f {} {} {}", f[0] + 1, f[1] + 1, f[2] + 1)?;
    }
    Ok(())
}
