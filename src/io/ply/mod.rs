//! PLY, ASCII and binary (little and big endian).
//!
//! Reads the `vertex` element's `x`, `y`, `z` (any scalar type) and the `face` element's
//! `vertex_indices` (or `vertex_index`) list (any integer count and index types), skipping
//! every other property and element, lists included; [`read_vertex_properties`] also reads
//! named scalar vertex properties (`quality`, `red`, ...: what `remesh --attribute NAME`
//! carries). Polygons are fan-triangulated. Writes
//! `double` coordinates, `uchar`/`int` index lists and, when given, `float` vertex
//! properties (`texture_u`/`texture_v`, named attributes: [`VertexProperties`]).

mod header;
mod source;

use std::io::Write;
use std::path::Path;

use self::header::{Element, Encoding, Property, Scalar};
use self::source::{AsciiSource, BinarySource, Source, ValueError};
use super::error::{Location, ReadError};
use super::{fan, parse_error};
use super::{AttributeData, VertexAttribute, VertexProperties};
use crate::mesh::TriMesh;

/// What a property means to us.
#[derive(Clone, Copy)]
enum Role {
    Coordinate(usize),
    /// The `k`-th vertex property asked for by [`read_vertex_properties`].
    Extra(usize),
    Indices,
    Skip,
}

fn unsupported(path: &Path, message: String) -> ReadError {
    ReadError::UnsupportedPly {
        path: path.to_path_buf(),
        message,
    }
}

/// Roles of the vertex element's properties (`x`, `y`, `z` must be scalars).
fn vertex_roles(path: &Path, element: &Element) -> Result<Vec<Role>, ReadError> {
    let mut roles = vec![Role::Skip; element.properties.len()];
    for (k, axis) in ["x", "y", "z"].into_iter().enumerate() {
        let i = element
            .properties
            .iter()
            .position(|p| p.name() == axis.as_bytes())
            .ok_or_else(|| {
                unsupported(path, format!("the vertex element has no '{axis}' property"))
            })?;
        if !matches!(element.properties[i], Property::Scalar { .. }) {
            return Err(unsupported(path, "a vertex coordinate is a list".into()));
        }
        roles[i] = Role::Coordinate(k);
    }
    Ok(roles)
}

/// Roles of the face element's properties (one integer index list).
fn face_roles(path: &Path, element: &Element) -> Result<Vec<Role>, ReadError> {
    let mut roles = vec![Role::Skip; element.properties.len()];
    let i = element
        .properties
        .iter()
        .position(|p| matches!(p.name(), b"vertex_indices" | b"vertex_index"))
        .ok_or_else(|| unsupported(path, "the face element has no 'vertex_indices' list".into()))?;
    match element.properties[i] {
        Property::List { item, .. } if item.is_integer() => roles[i] = Role::Indices,
        _ => {
            return Err(unsupported(
                path,
                "the face 'vertex_indices' property is not a list of integers".into(),
            ))
        }
    }
    Ok(roles)
}

/// Parse a PLY file's bytes.
pub(crate) fn read(path: &Path, data: &[u8]) -> Result<TriMesh, ReadError> {
    read_with(path, data, &[]).map(|(mesh, _)| mesh)
}

/// The vertex properties named `names` of a PLY file (each a scalar property of the `vertex`
/// element), one value per vertex each, with the mesh; the property's type says how the
/// remesh carries it: floating-point values and the colour channels (`red`, `green`, `blue`,
/// `alpha`) are [`AttributeData::Scalar`] (interpolated), other integers
/// [`AttributeData::Label`] (the nearest corner's value).
pub(crate) fn read_vertex_properties(path: &Path, data: &[u8], names: &[&str]) -> Result<(TriMesh, Vec<VertexAttribute>), ReadError> {
    let (mesh, extras) = read_with(path, data, names)?;
    let mut attributes = Vec::with_capacity(extras.len());
    for (name, (ty, values)) in names.iter().zip(extras) {
        let colour = ["red", "green", "blue", "alpha"].contains(name);
        let data = if ty.is_integer() && !colour {
            let mut labels = Vec::with_capacity(values.len());
            for (v, x) in values.iter().enumerate() {
                let label = i32::try_from(*x as i64).map_err(|_| {
                    unsupported(path, format!("vertex {v}'s '{name}' = {x} does not fit a 32-bit label"))
                })?;
                labels.push(label);
            }
            AttributeData::Label(labels)
        } else {
            AttributeData::Scalar(values.iter().map(|&x| x as f32).collect())
        };
        attributes.push(VertexAttribute { name: name.to_string(), data, label_table: Vec::new() });
    }
    Ok((mesh, attributes))
}

/// Vertex properties read besides the positions: each one's type and values.
type ExtraProperties = Vec<(Scalar, Vec<f64>)>;

/// Parse a PLY file's bytes, also reading the vertex properties `extra` (their types and
/// values, in that order).
fn read_with(path: &Path, data: &[u8], extra: &[&str]) -> Result<(TriMesh, ExtraProperties), ReadError> {
    let header = header::parse(path, data)?;
    let vertex = header.elements.iter().position(|e| e.name == b"vertex");
    let face = header.elements.iter().position(|e| e.name == b"face");
    if face.is_none() && header.elements.iter().any(|e| e.name == b"tristrips") {
        return Err(unsupported(
            path,
            "triangle strips ('tristrips') are not supported".into(),
        ));
    }
    let mut roles: Vec<Vec<Role>> = header
        .elements
        .iter()
        .map(|e| vec![Role::Skip; e.properties.len()])
        .collect();
    if let Some(v) = vertex {
        if header.elements[v].count > u64::from(u32::MAX) {
            return Err(unsupported(path, "more than 4294967295 vertices".into()));
        }
        roles[v] = vertex_roles(path, &header.elements[v])?;
    }
    let mut extra_types = Vec::with_capacity(extra.len());
    for (k, name) in extra.iter().enumerate() {
        let element = vertex.map(|v| &header.elements[v]);
        let found = element.and_then(|e| e.properties.iter().position(|p| p.name() == name.as_bytes()));
        let (Some(v), Some(i)) = (vertex, found) else {
            let available: Vec<String> = element
                .map(|e| e.properties.iter().map(|p| String::from_utf8_lossy(p.name()).into_owned()).collect())
                .unwrap_or_default();
            return Err(ReadError::NoPlyProperty { path: path.to_path_buf(), name: name.to_string(), available: available.join(", ") });
        };
        match header.elements[v].properties[i] {
            Property::Scalar { ty, .. } if matches!(roles[v][i], Role::Skip) => {
                roles[v][i] = Role::Extra(k);
                extra_types.push(ty);
            }
            Property::Scalar { .. } => {
                return Err(unsupported(path, format!("the vertex property '{name}' is a coordinate or named twice; name another one")))
            }
            Property::List { .. } => {
                return Err(unsupported(path, format!("the vertex property '{name}' is a list, not one value per vertex")))
            }
        }
    }
    if let Some(f) = face {
        roles[f] = face_roles(path, &header.elements[f])?;
    }
    let (mesh, values) = match header.encoding {
        Encoding::Ascii => {
            let mut src = AsciiSource::new(data, header.data_start, header.header_lines + 1);
            read_data(path, &header.elements, &roles, vertex, face, &mut src)
        }
        Encoding::BinaryLittleEndian | Encoding::BinaryBigEndian => {
            let big = header.encoding == Encoding::BinaryBigEndian;
            let mut src = BinarySource::new(data, header.data_start, big);
            read_data(path, &header.elements, &roles, vertex, face, &mut src)
        }
    }?;
    Ok((mesh, extra_types.into_iter().zip(values).collect()))
}

/// Read one element instance; `on_coordinate` / `on_indices` receive the values we keep.
fn read_instance<S: Source>(
    src: &mut S,
    element: &Element,
    roles: &[Role],
    xyz: &mut [f64; 3],
    extras: &mut [f64],
    polygon: &mut Vec<i64>,
) -> Result<(), ValueError> {
    for (property, role) in element.properties.iter().zip(roles) {
        match (property, role) {
            (Property::Scalar { ty, .. }, Role::Coordinate(k)) => xyz[*k] = src.real(*ty)?,
            (Property::Scalar { ty, .. }, Role::Extra(k)) => extras[*k] = src.real(*ty)?,
            (Property::Scalar { ty, .. }, _) => src.skip(*ty, 1)?,
            (Property::List { count, item, .. }, role) => {
                let n = src.integer(*count)?;
                let n = u64::try_from(n)
                    .map_err(|_| ValueError::Bad(format!("negative list length {n}")))?;
                if n > src.remaining() as u64 {
                    return Err(ValueError::Eof);
                }
                if matches!(role, Role::Indices) {
                    polygon.clear();
                    for _ in 0..n {
                        polygon.push(src.integer(*item)?);
                    }
                } else {
                    src.skip(*item, n)?;
                }
            }
        }
    }
    Ok(())
}

fn read_data<S: Source>(
    path: &Path,
    elements: &[Element],
    roles: &[Vec<Role>],
    vertex: Option<usize>,
    face: Option<usize>,
    src: &mut S,
) -> Result<(TriMesh, Vec<Vec<f64>>), ReadError> {
    let n_extra = roles.iter().flatten().filter(|r| matches!(r, Role::Extra(_))).count();
    let mut extra_values: Vec<Vec<f64>> = vec![Vec::new(); n_extra];
    let mut extras = vec![0.0; n_extra];
    let mut vertices: Vec<[f64; 3]> = Vec::new();
    let mut faces: Vec<[u32; 3]> = Vec::new();
    let mut vertices_read = false;
    // Indices not below the vertex count known when their face was read.
    let mut pending: Vec<(Location, i64)> = Vec::new();
    let mut polygon: Vec<i64> = Vec::new();
    let mut indices: Vec<u32> = Vec::new();

    for (e, element) in elements.iter().enumerate() {
        let name = String::from_utf8_lossy(&element.name).into_owned();
        let what = match Some(e) {
            x if x == vertex => "vertices".to_string(),
            x if x == face => "faces".to_string(),
            _ => format!("'{name}' elements"),
        };
        let cap = (element.count.min(src.remaining() as u64 / 3)) as usize;
        if Some(e) == vertex {
            vertices.reserve(cap);
        } else if Some(e) == face {
            faces.reserve(cap);
        }
        if element.properties.is_empty() {
            continue; // nothing to read, however many instances are announced
        }
        for i in 0..element.count {
            let at = src.location();
            let mut xyz = [0.0; 3];
            polygon.clear();
            read_instance(src, element, &roles[e], &mut xyz, &mut extras, &mut polygon).map_err(
                |err| match err {
                    ValueError::Eof => ReadError::Truncated {
                        path: path.to_path_buf(),
                        what: what.clone(),
                        expected: element.count,
                        found: i,
                    },
                    ValueError::Bad(message) => parse_error(
                        path,
                        src.location(),
                        format!("{message} (in {name} {i}); the file is corrupt, export it again"),
                    ),
                },
            )?;
            if Some(e) == vertex {
                if !xyz.iter().all(|x| x.is_finite()) {
                    return Err(ReadError::NonFinite {
                        path: path.to_path_buf(),
                        at,
                    });
                }
                vertices.push(xyz);
                for (values, &x) in extra_values.iter_mut().zip(&extras) {
                    values.push(x);
                }
            } else if Some(e) == face {
                if polygon.len() < 3 {
                    return Err(parse_error(
                        path,
                        at,
                        format!(
                            "face {i} has {} vertices, a face needs at least 3; delete it",
                            polygon.len()
                        ),
                    ));
                }
                indices.clear();
                for &index in &polygon {
                    if index < 0 || index >= i64::from(u32::MAX) {
                        return Err(ReadError::IndexOutOfRange {
                            path: path.to_path_buf(),
                            at,
                            index,
                            n_vertices: vertices.len(),
                        });
                    }
                    if !vertices_read || index >= vertices.len() as i64 {
                        pending.push((at, index));
                    }
                    indices.push(index as u32);
                }
                fan(&indices, &mut faces);
            }
        }
        if Some(e) == vertex {
            vertices_read = true;
        }
    }
    if let Some(&(at, index)) = pending.iter().find(|&&(_, i)| i >= vertices.len() as i64) {
        return Err(ReadError::IndexOutOfRange {
            path: path.to_path_buf(),
            at,
            index,
            n_vertices: vertices.len(),
        });
    }
    Ok((TriMesh::new(vertices, faces), extra_values))
}

fn write_header(w: &mut dyn Write, mesh: &TriMesh, extra: &VertexProperties, format: &str) -> std::io::Result<()> {
    let index_type = if mesh.n_vertices() > i32::MAX as usize {
        "uint"
    } else {
        "int"
    };
    write!(
        w,
        "ply\nformat {format} 1.0\ncomment written by capmesh\nelement vertex {}\n\
         property double x\nproperty double y\nproperty double z\n",
        mesh.n_vertices()
    )?;
    if extra.uv.is_some() {
        write!(w, "property float texture_u\nproperty float texture_v\n")?;
    }
    for (name, _) in &extra.scalars {
        writeln!(w, "property float {name}")?;
    }
    write!(w, "element face {}\nproperty list uchar {index_type} vertex_indices\nend_header\n", mesh.n_faces())
}

/// The extra values of vertex `v` in property order: `u`, `v`, then the scalars.
fn extras_of(extra: &VertexProperties, v: usize, out: &mut Vec<f32>) {
    out.clear();
    if let Some(uv) = &extra.uv {
        out.extend([uv[v][0] as f32, uv[v][1] as f32]);
    }
    out.extend(extra.scalars.iter().map(|(_, values)| values[v]));
}

/// Write binary little-endian PLY with the vertex properties `extra`. The mesh and `extra`
/// have been checked by the caller.
pub(crate) fn write_binary(w: &mut dyn Write, mesh: &TriMesh, extra: &VertexProperties) -> std::io::Result<()> {
    write_header(w, mesh, extra, "binary_little_endian")?;
    let mut buf = Vec::with_capacity(64);
    let mut values = Vec::new();
    for (v, p) in mesh.vertices.iter().enumerate() {
        buf.clear();
        for x in p {
            buf.extend_from_slice(&x.to_le_bytes());
        }
        extras_of(extra, v, &mut values);
        for x in &values {
            buf.extend_from_slice(&x.to_le_bytes());
        }
        w.write_all(&buf)?;
    }
    let mut rec = [0u8; 13];
    rec[0] = 3;
    for f in &mesh.faces {
        for k in 0..3 {
            rec[1 + 4 * k..5 + 4 * k].copy_from_slice(&f[k].to_le_bytes());
        }
        w.write_all(&rec)?;
    }
    Ok(())
}

/// Write ASCII PLY with the vertex properties `extra`. The mesh and `extra` have been checked
/// by the caller.
pub(crate) fn write_ascii(w: &mut dyn Write, mesh: &TriMesh, extra: &VertexProperties) -> std::io::Result<()> {
    write_header(w, mesh, extra, "ascii")?;
    let mut values = Vec::new();
    for (v, p) in mesh.vertices.iter().enumerate() {
        write!(w, "{:?} {:?} {:?}", p[0], p[1], p[2])?;
        extras_of(extra, v, &mut values);
        for x in &values {
            write!(w, " {x:?}")?;
        }
        writeln!(w)?;
    }
    for f in &mesh.faces {
        writeln!(w, "3 {} {} {}", f[0], f[1], f[2])?;
    }
    Ok(())
}
