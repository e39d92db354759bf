//! STL, ASCII and binary. Facets are a triangle soup: vertices with bit-identical positions are
//! welded into an indexed mesh (`-0.0` and `0.0` are the same), and facets that then use a
//! vertex twice (zero-area slivers with two identical corners) are dropped.
//!
//! Binary vs ASCII: a file whose size is exactly `84 + 50 n` (with `n` the triangle count at
//! byte 80) is binary even if it starts with `solid`; otherwise a file starting with `solid`
//! that is plain text is ASCII; otherwise it is binary, and too short for its count means it
//! was truncated. Written as binary (32-bit floats, so coordinates lose precision).

use std::io::Write;
use std::path::Path;

use super::error::{Location, ReadError};
use super::text::{read_point, show, tokens, Lines};
use super::{fan, parse_error};
use crate::mesh::fasthash::FastMap;
use crate::mesh::geometry::{cross, norm, sub};
use crate::mesh::TriMesh;

/// Welds bit-identical positions into indexed vertices, in order of first appearance.
struct Welder {
    index: FastMap<[u64; 3], u32>,
    vertices: Vec<[f64; 3]>,
}

impl Welder {
    fn with_capacity(n: usize) -> Self {
        let mut index = FastMap::default();
        index.reserve(n);
        Self {
            index,
            vertices: Vec::with_capacity(n),
        }
    }

    fn id(&mut self, p: [f64; 3]) -> u32 {
        let key = p.map(|x| if x == 0.0 { 0 } else { x.to_bits() });
        let next = self.vertices.len() as u32;
        let id = *self.index.entry(key).or_insert(next);
        if id == next {
            self.vertices.push(p);
        }
        id
    }
}

/// Add a polygon of positions; triangles that use a welded vertex twice are dropped.
fn add_facet(welder: &mut Welder, corners: &[[f64; 3]], faces: &mut Vec<[u32; 3]>) {
    let ids: Vec<u32> = corners.iter().map(|&p| welder.id(p)).collect();
    let start = faces.len();
    fan(&ids, faces);
    let mut k = start;
    while k < faces.len() {
        let [a, b, c] = faces[k];
        if a == b || b == c || a == c {
            faces.swap_remove(k);
        } else {
            k += 1;
        }
    }
}

/// Is this plain text (ASCII printable and whitespace only)?
fn looks_like_text(data: &[u8]) -> bool {
    data.iter()
        .all(|&b| b == b'\t' || b == b'\n' || b == b'\r' || b == 0x0c || (0x20..0x7f).contains(&b))
}

fn starts_with_solid(data: &[u8]) -> bool {
    let start = data
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .unwrap_or(data.len());
    data[start..]
        .get(..5)
        .is_some_and(|s| s.eq_ignore_ascii_case(b"solid"))
}

/// Parse an STL file's bytes (ASCII or binary).
pub(crate) fn read(path: &Path, data: &[u8]) -> Result<TriMesh, ReadError> {
    if data.len() >= 84 {
        let n = u32::from_le_bytes([data[80], data[81], data[82], data[83]]);
        let expected = 84 + 50 * u64::from(n);
        if expected == data.len() as u64 {
            return read_binary(path, data, n);
        }
        if starts_with_solid(data) && looks_like_text(data) {
            return read_ascii(path, data);
        }
        if expected > data.len() as u64 {
            return Err(ReadError::Truncated {
                path: path.to_path_buf(),
                what: format!("bytes (binary STL header announces {n} triangles)"),
                expected,
                found: data.len() as u64,
            });
        }
        // Longer than announced: some writers pad; read the announced triangles.
        return read_binary(path, data, n);
    }
    if starts_with_solid(data) && looks_like_text(data) {
        return read_ascii(path, data);
    }
    Err(ReadError::Truncated {
        path: path.to_path_buf(),
        what: "bytes (a binary STL needs an 84-byte header)".into(),
        expected: 84,
        found: data.len() as u64,
    })
}

fn read_binary(path: &Path, data: &[u8], n: u32) -> Result<TriMesh, ReadError> {
    let n = n as usize;
    let mut welder = Welder::with_capacity(n / 2 + 3);
    let mut faces = Vec::with_capacity(n);
    let f32_at = |o: usize| {
        f64::from(f32::from_le_bytes([
            data[o],
            data[o + 1],
            data[o + 2],
            data[o + 3],
        ]))
    };
    for t in 0..n {
        let base = 84 + 50 * t;
        let mut corners = [[0.0; 3]; 3];
        for (k, c) in corners.iter_mut().enumerate() {
            let o = base + 12 + 12 * k;
            *c = [f32_at(o), f32_at(o + 4), f32_at(o + 8)];
            if !c.iter().all(|x| x.is_finite()) {
                return Err(ReadError::NonFinite {
                    path: path.to_path_buf(),
                    at: Location::Byte(o as u64),
                });
            }
        }
        add_facet(&mut welder, &corners, &mut faces);
    }
    Ok(TriMesh::new(welder.vertices, faces))
}

fn read_ascii(path: &Path, data: &[u8]) -> Result<TriMesh, ReadError> {
    let mut welder = Welder::with_capacity(data.len() / 200 + 3);
    let mut faces = Vec::with_capacity(data.len() / 250);
    let mut corners: Vec<[f64; 3]> = Vec::with_capacity(4);
    let mut facet_start: Option<usize> = None;
    let mut lines = Lines::new(data);
    for (line, raw) in lines.by_ref() {
        let at = Location::Line(line);
        let mut toks = tokens(raw);
        let Some(key) = toks.next() else { continue };
        let is = |word: &[u8]| key.eq_ignore_ascii_case(word);
        if is(b"facet") {
            if facet_start.is_some() {
                return Err(parse_error(
                    path,
                    at,
                    "'facet' inside a facet: an 'endfacet' is missing".into(),
                ));
            }
            facet_start = Some(line);
            corners.clear();
        } else if is(b"vertex") {
            if facet_start.is_none() {
                return Err(parse_error(path, at, "'vertex' outside a facet".into()));
            }
            let p = read_point(&mut toks, path, at, |k| format!("a vertex needs 3 coordinates, found {k}"))?;
            corners.push(p);
        } else if is(b"endfacet") {
            if facet_start.take().is_none() {
                return Err(parse_error(path, at, "'endfacet' without 'facet'".into()));
            }
            if corners.len() < 3 {
                return Err(parse_error(
                    path,
                    at,
                    format!("a facet needs 3 vertices, this one has {}", corners.len()),
                ));
            }
            add_facet(&mut welder, &corners, &mut faces);
        } else if is(b"solid") || is(b"endsolid") || is(b"outer") || is(b"endloop") {
        } else {
            return Err(parse_error(
                path,
                at,
                format!("unexpected '{}' in an ASCII STL file", show(key)),
            ));
        }
    }
    if let Some(start) = facet_start {
        return Err(parse_error(
            path,
            Location::Line(lines.line()),
            format!("the file ends inside the facet that starts at line {start}: it is truncated, export it again"),
        ));
    }
    Ok(TriMesh::new(welder.vertices, faces))
}

/// Write binary STL. The mesh has been checked by the caller (indices, finiteness, f32 range,
/// face count).
pub(crate) fn write(w: &mut dyn Write, mesh: &TriMesh) -> std::io::Result<()> {
    let mut header = [b' '; 80];
    let text = b"binary STL written by capmesh";
    header[..text.len()].copy_from_slice(text);
    w.write_all(&header)?;
    w.write_all(&(mesh.n_faces() as u32).to_le_bytes())?;
    let mut record = [0u8; 50];
    for f in &mesh.faces {
        let [a, b, c] = f.map(|v| mesh.vertices[v as usize]);
        let n = cross(sub(b, a), sub(c, a));
        let len = norm(n);
        let n = if len > 0.0 {
            n.map(|x| x / len)
        } else {
            [0.0; 3]
        };
        for (k, p) in [n, a, b, c].iter().enumerate() {
            for (j, x) in p.iter().enumerate() {
                let o = 12 * k + 4 * j;
                record[o..o + 4].copy_from_slice(&(*x as f32).to_le_bytes());
            }
        }
        w.write_all(&record)?;
    }
    Ok(())
}
