//! Writing a GIFTI surface: a `NIFTI_INTENT_POINTSET` array (coordinates, `FLOAT32` by default
//! as the GIFTI standard lists, or `FLOAT64`) and a `NIFTI_INTENT_TRIANGLE` array (`INT32`),
//! row-major, in the chosen encoding and byte order. `GZipBase64Binary` data are
//! zlib-compressed, as gifticlib, nibabel and Connectome Workbench write them.

use std::io::Write;

use base64::engine::general_purpose::STANDARD;
use base64::engine::Engine;

use crate::mesh::TriMesh;

/// How a GIFTI array's values are stored in the XML.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum GiftiEncoding {
    /// Decimal numbers (largest, readable).
    Ascii,
    /// Raw values, base64-encoded.
    Base64Binary,
    /// Raw values, zlib-compressed, base64-encoded (smallest; the default).
    #[default]
    GzipBase64Binary,
}

/// The floating-point type of the written coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum GiftiFloat {
    /// `NIFTI_TYPE_FLOAT32`, the type every GIFTI reader takes (the default; coordinates are
    /// rounded to 32-bit floats).
    #[default]
    Float32,
    /// `NIFTI_TYPE_FLOAT64`: full precision (nibabel reads it; some tools read only float32).
    Float64,
}

/// Byte order of binary-encoded values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Endian {
    /// Little endian (the default; what x86 and ARM tools write).
    #[default]
    Little,
    /// Big endian.
    Big,
}

/// Options of the GIFTI writer. Defaults: [`GiftiEncoding::GzipBase64Binary`],
/// [`GiftiFloat::Float32`], [`Endian::Little`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[non_exhaustive]
pub struct GiftiOptions {
    /// How the values are stored.
    pub encoding: GiftiEncoding,
    /// The coordinates' type.
    pub coordinates: GiftiFloat,
    /// The byte order of binary encodings (ASCII has none).
    pub endian: Endian,
}

impl GiftiOptions {
    /// Set [`GiftiOptions::encoding`].
    pub fn with_encoding(mut self, encoding: GiftiEncoding) -> Self {
        self.encoding = encoding;
        self
    }

    /// Set [`GiftiOptions::coordinates`].
    pub fn with_coordinates(mut self, coordinates: GiftiFloat) -> Self {
        self.coordinates = coordinates;
        self
    }

    /// Set [`GiftiOptions::endian`].
    pub fn with_endian(mut self, endian: Endian) -> Self {
        self.endian = endian;
        self
    }
}

/// Write a GIFTI surface. The mesh has been checked by the caller (indices, finiteness, and
/// the float32 range and int32 counts).
pub(crate) fn write(w: &mut dyn Write, mesh: &TriMesh, options: &GiftiOptions) -> std::io::Result<()> {
    writeln!(w, r#"<?xml version="1.0" encoding="UTF-8"?>"#)?;
    writeln!(w, r#"<!DOCTYPE GIFTI SYSTEM "http://www.nitrc.org/frs/download.php/115/gifti.dtd">"#)?;
    writeln!(w, r#"<GIFTI Version="1.0" NumberOfDataArrays="2">"#)?;
    writeln!(w, "  <MetaData/>\n  <LabelTable/>")?;

    let big = options.endian == Endian::Big;
    let (type_name, size) = match options.coordinates {
        GiftiFloat::Float32 => ("NIFTI_TYPE_FLOAT32", 4),
        GiftiFloat::Float64 => ("NIFTI_TYPE_FLOAT64", 8),
    };
    header(w, "NIFTI_INTENT_POINTSET", type_name, mesh.n_vertices(), options)?;
    writeln!(w, "    <MetaData/>")?;
    writeln!(w, "    <CoordinateSystemTransformMatrix>")?;
    writeln!(w, "      <DataSpace><![CDATA[NIFTI_XFORM_UNKNOWN]]></DataSpace>")?;
    writeln!(w, "      <TransformedSpace><![CDATA[NIFTI_XFORM_UNKNOWN]]></TransformedSpace>")?;
    writeln!(w, "      <MatrixData>1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1</MatrixData>")?;
    writeln!(w, "    </CoordinateSystemTransformMatrix>")?;
    if options.encoding == GiftiEncoding::Ascii {
        write!(w, "    <Data>")?;
        for p in &mesh.vertices {
            match options.coordinates {
                GiftiFloat::Float32 => writeln!(w, "{:?} {:?} {:?}", p[0] as f32, p[1] as f32, p[2] as f32)?,
                GiftiFloat::Float64 => writeln!(w, "{:?} {:?} {:?}", p[0], p[1], p[2])?,
            }
        }
    } else {
        let mut raw = Vec::with_capacity(mesh.n_vertices() * 3 * size);
        for x in mesh.vertices.iter().flatten() {
            match (options.coordinates, big) {
                (GiftiFloat::Float32, false) => raw.extend_from_slice(&(*x as f32).to_le_bytes()),
                (GiftiFloat::Float32, true) => raw.extend_from_slice(&(*x as f32).to_be_bytes()),
                (GiftiFloat::Float64, false) => raw.extend_from_slice(&x.to_le_bytes()),
                (GiftiFloat::Float64, true) => raw.extend_from_slice(&x.to_be_bytes()),
            }
        }
        binary_data(w, &raw, options)?;
    }
    writeln!(w, "</Data>\n  </DataArray>")?;

    header(w, "NIFTI_INTENT_TRIANGLE", "NIFTI_TYPE_INT32", mesh.n_faces(), options)?;
    writeln!(w, "    <MetaData/>")?;
    if options.encoding == GiftiEncoding::Ascii {
        write!(w, "    <Data>")?;
        for f in &mesh.faces {
            writeln!(w, "{} {} {}", f[0], f[1], f[2])?;
        }
    } else {
        let mut raw = Vec::with_capacity(mesh.n_faces() * 12);
        for &i in mesh.faces.iter().flatten() {
            let i = i as i32;
            raw.extend_from_slice(&if big { i.to_be_bytes() } else { i.to_le_bytes() });
        }
        binary_data(w, &raw, options)?;
    }
    writeln!(w, "</Data>\n  </DataArray>")?;
    writeln!(w, "</GIFTI>")
}

fn header(w: &mut dyn Write, intent: &str, data_type: &str, rows: usize, options: &GiftiOptions) -> std::io::Result<()> {
    let encoding = match options.encoding {
        GiftiEncoding::Ascii => "ASCII",
        GiftiEncoding::Base64Binary => "Base64Binary",
        GiftiEncoding::GzipBase64Binary => "GZipBase64Binary",
    };
    let endian = match options.endian {
        Endian::Little => "LittleEndian",
        Endian::Big => "BigEndian",
    };
    writeln!(
        w,
        r#"  <DataArray Intent="{intent}" DataType="{data_type}" ArrayIndexingOrder="RowMajorOrder" Dimensionality="2" Dim0="{rows}" Dim1="3" Encoding="{encoding}" Endian="{endian}" ExternalFileName="" ExternalFileOffset="">"#
    )
}

/// `<Data>` content of a binary encoding (without the tags).
pub(super) fn binary_data(w: &mut dyn Write, raw: &[u8], options: &GiftiOptions) -> std::io::Result<()> {
    write!(w, "    <Data>")?;
    let text = if options.encoding == GiftiEncoding::GzipBase64Binary {
        let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::default());
        z.write_all(raw)?;
        STANDARD.encode(z.finish()?)
    } else {
        STANDARD.encode(raw)
    };
    w.write_all(text.as_bytes())
}
