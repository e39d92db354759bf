//! One GIFTI `DataArray`: its attributes (intent, data type, dimensions, encoding, byte order,
//! indexing order) and the decoding of its `Data` element into numbers.
//!
//! Encodings: `ASCII` (whitespace-separated numbers), `Base64Binary` (raw values in the given
//! byte order, base64-encoded; whitespace inside is ignored) and `GZipBase64Binary` (the same,
//! zlib- or gzip-compressed before base64). The legacy names `GIFTI_ENCODING_*` and
//! `GIFTI_ENDIAN_*` that older gifticlib versions wrote are accepted. `ExternalFileBinary` is
//! refused. Column-major arrays are reordered to row-major.

use std::io::Read;
use std::path::Path;

use base64::engine::general_purpose::{GeneralPurpose, PAD_INDIFFERENT};
use base64::engine::Engine;

use super::super::error::{Location, ReadError};
use super::super::parse_error;
use super::super::text::show;

/// Standard alphabet; padding optional (some writers omit it).
const BASE64: GeneralPurpose = GeneralPurpose::new(&base64::alphabet::STANDARD, PAD_INDIFFERENT);

/// A NIfTI data type as GIFTI names it (`NIFTI_TYPE_FLOAT32`, ...).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum DataType {
    U8,
    I8,
    U16,
    I16,
    U32,
    I32,
    U64,
    I64,
    F32,
    F64,
}

impl DataType {
    fn parse(name: &str) -> Option<DataType> {
        Some(match name.strip_prefix("NIFTI_TYPE_")? {
            "UINT8" => DataType::U8,
            "INT8" => DataType::I8,
            "UINT16" => DataType::U16,
            "INT16" => DataType::I16,
            "UINT32" => DataType::U32,
            "INT32" => DataType::I32,
            "UINT64" => DataType::U64,
            "INT64" => DataType::I64,
            "FLOAT32" => DataType::F32,
            "FLOAT64" => DataType::F64,
            _ => return None,
        })
    }

    /// Bytes per value.
    fn size(self) -> usize {
        match self {
            DataType::U8 | DataType::I8 => 1,
            DataType::U16 | DataType::I16 => 2,
            DataType::U32 | DataType::I32 | DataType::F32 => 4,
            DataType::U64 | DataType::I64 | DataType::F64 => 8,
        }
    }

    pub(crate) fn is_float(self) -> bool {
        matches!(self, DataType::F32 | DataType::F64)
    }

    /// One value from its bytes (`bytes.len() == self.size()`).
    fn value(self, bytes: &[u8], big: bool) -> Number {
        let mut b = [0u8; 8];
        let n = self.size();
        b[..n].copy_from_slice(bytes);
        if big {
            b[..n].reverse();
        }
        let (b2, b4) = ([b[0], b[1]], [b[0], b[1], b[2], b[3]]);
        match self {
            DataType::U8 => Number::Int(i64::from(b[0])),
            DataType::I8 => Number::Int(i64::from(b[0] as i8)),
            DataType::U16 => Number::Int(i64::from(u16::from_le_bytes(b2))),
            DataType::I16 => Number::Int(i64::from(i16::from_le_bytes(b2))),
            DataType::U32 => Number::Int(i64::from(u32::from_le_bytes(b4))),
            DataType::I32 => Number::Int(i64::from(i32::from_le_bytes(b4))),
            // Values past i64::MAX saturate; they are refused later as indices or labels.
            DataType::U64 => Number::Int(i64::try_from(u64::from_le_bytes(b)).unwrap_or(i64::MAX)),
            DataType::I64 => Number::Int(i64::from_le_bytes(b)),
            DataType::F32 => Number::Float(f64::from(f32::from_le_bytes(b4))),
            DataType::F64 => Number::Float(f64::from_le_bytes(b)),
        }
    }
}

enum Number {
    Int(i64),
    Float(f64),
}

/// How the `Data` element's text encodes the values.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Encoding {
    Ascii,
    Base64,
    GzipBase64,
}

/// The decoded values of an array, row-major.
pub(crate) enum Values {
    /// From a floating-point data type.
    Float(Vec<f64>),
    /// From an integer data type.
    Int(Vec<i64>),
}

impl Values {
    pub(crate) fn len(&self) -> usize {
        match self {
            Values::Float(v) => v.len(),
            Values::Int(v) => v.len(),
        }
    }
}

/// A `DataArray` element with its attributes checked.
pub(crate) struct Array<'a, 'input> {
    pub node: roxmltree::Node<'a, 'input>,
    /// `NIFTI_INTENT_POINTSET`, ... (as written).
    pub intent: &'a str,
    pub data_type: DataType,
    /// `Dim0`, `Dim1`, ...
    pub dims: Vec<usize>,
    /// 1-based line of the `DataArray` element.
    pub line: usize,
    encoding: Encoding,
    big_endian: bool,
    column_major: bool,
}

/// 1-based line of a node.
pub(crate) fn line_of(node: roxmltree::Node) -> usize {
    node.document().text_pos_at(node.range().start).row as usize
}

impl<'a, 'input> Array<'a, 'input> {
    /// Read and check a `DataArray` element's attributes.
    pub(crate) fn new(path: &Path, node: roxmltree::Node<'a, 'input>) -> Result<Self, ReadError> {
        let line = line_of(node);
        let at = Location::Line(line);
        let unsupported = |message: String| ReadError::UnsupportedGifti {
            path: path.to_path_buf(),
            at,
            message,
        };
        let attr = |name: &str| -> Result<&'a str, ReadError> {
            node.attribute(name).map(str::trim).ok_or_else(|| {
                parse_error(
                    path,
                    at,
                    format!("the DataArray has no '{name}' attribute; the file is corrupt, export it again"),
                )
            })
        };
        let intent = node.attribute("Intent").map(str::trim).unwrap_or("NIFTI_INTENT_NONE");
        let type_name = attr("DataType")?;
        let data_type = DataType::parse(type_name)
            .ok_or_else(|| unsupported(format!("data type '{}'", show(type_name.as_bytes()))))?;
        let count = |name: &str| -> Result<usize, ReadError> {
            let text = attr(name)?;
            text.parse::<usize>().map_err(|_| {
                parse_error(
                    path,
                    at,
                    format!(
                        "'{name}' is '{}', not a count; the file is corrupt, export it again",
                        show(text.as_bytes())
                    ),
                )
            })
        };
        let dimensionality = count("Dimensionality")?;
        if !(1..=6).contains(&dimensionality) {
            return Err(parse_error(
                path,
                at,
                format!("Dimensionality is {dimensionality}; GIFTI arrays have 1 to 6 dimensions, the file is corrupt"),
            ));
        }
        let dims = (0..dimensionality)
            .map(|k| count(&format!("Dim{k}")))
            .collect::<Result<Vec<_>, _>>()?;
        let encoding = match attr("Encoding")? {
            "ASCII" | "GIFTI_ENCODING_ASCII" => Encoding::Ascii,
            "Base64Binary" | "GIFTI_ENCODING_B64BIN" => Encoding::Base64,
            "GZipBase64Binary" | "GIFTI_ENCODING_B64GZ" => Encoding::GzipBase64,
            "ExternalFileBinary" | "GIFTI_ENCODING_EXTBIN" => {
                return Err(unsupported(
                    "the data are in an external file (ExternalFileBinary)".into(),
                ))
            }
            other => {
                return Err(unsupported(format!("encoding '{}'", show(other.as_bytes()))))
            }
        };
        // ASCII data have no byte order, whatever the attribute says.
        let big_endian = match (node.attribute("Endian").map(str::trim), encoding) {
            (Some("BigEndian" | "GIFTI_ENDIAN_BIG"), _) => true,
            (Some("LittleEndian" | "GIFTI_ENDIAN_LITTLE"), _) | (_, Encoding::Ascii) => false,
            (None, _) => return Err(unsupported("no byte order ('Endian') for binary data".into())),
            (Some(other), _) => {
                return Err(unsupported(format!("byte order '{}'", show(other.as_bytes()))))
            }
        };
        let column_major = match node.attribute("ArrayIndexingOrder").map(str::trim) {
            Some("ColumnMajorOrder") => true,
            Some("RowMajorOrder") | None => false,
            Some(other) => {
                return Err(unsupported(format!("indexing order '{}'", show(other.as_bytes()))))
            }
        };
        Ok(Array {
            node,
            intent,
            data_type,
            dims,
            line,
            encoding,
            big_endian,
            column_major,
        })
    }

    /// The value of the array's `MetaData` entry `key`, if any.
    pub(crate) fn meta(&self, key: &str) -> Option<String> {
        let meta = self.node.children().find(|n| n.has_tag_name("MetaData"))?;
        meta.children().filter(|n| n.has_tag_name("MD")).find_map(|md| {
            let field = |tag: &str| md.children().find(|n| n.has_tag_name(tag)).and_then(|n| n.text());
            (field("Name")?.trim() == key).then(|| field("Value").unwrap_or("").trim().to_string())
        })
    }

    /// Decode the `Data` element into `dims` values, row-major.
    pub(crate) fn decode(&self, path: &Path) -> Result<Values, ReadError> {
        let data = self.node.children().find(|n| n.has_tag_name("Data"));
        let line = data.map_or(self.line, line_of);
        let err = |message: String| parse_error(path, Location::Line(line), message);
        let text = data.and_then(|d| d.text()).unwrap_or("");
        let n = self.dims.iter().try_fold(1usize, |a, &d| a.checked_mul(d));
        let n = n
            .filter(|&n| n.checked_mul(8).is_some())
            .ok_or_else(|| err(format!("the dimensions {:?} are too large; the file is corrupt", self.dims)))?;
        let what = || format!("{} values ({})", n, self.dims.iter().map(|d| d.to_string()).collect::<Vec<_>>().join(" x "));
        let values = match self.encoding {
            Encoding::Ascii => self.decode_ascii(text, n, &err, &what)?,
            Encoding::Base64 | Encoding::GzipBase64 => {
                let compact: Vec<u8> = text.bytes().filter(|b| !b.is_ascii_whitespace()).collect();
                let raw = BASE64.decode(&compact).map_err(|e| {
                    err(format!("the base64 data is corrupt ({e}); the file is damaged, export it again"))
                })?;
                let expected = n * self.data_type.size();
                let bytes = if self.encoding == Encoding::GzipBase64 {
                    inflate(&raw, expected).map_err(|e| {
                        err(format!("the compressed data is corrupt ({e}); the file is damaged, export it again"))
                    })?
                } else {
                    raw
                };
                if bytes.len() != expected {
                    return Err(err(format!(
                        "the data hold {} bytes but the array announces {} of {} bytes each ({} bytes); \
                         the file is truncated or corrupt, export it again",
                        bytes.len(),
                        what(),
                        self.data_type.size(),
                        expected
                    )));
                }
                self.decode_binary(&bytes)
            }
        };
        Ok(if self.column_major && self.dims.len() > 1 {
            reorder_column_major(values, &self.dims)
        } else {
            values
        })
    }

    fn decode_ascii(
        &self,
        text: &str,
        n: usize,
        err: &dyn Fn(String) -> ReadError,
        what: &dyn Fn() -> String,
    ) -> Result<Values, ReadError> {
        let mut tokens = text.split_ascii_whitespace();
        let capacity = n.min(text.len() / 2 + 1);
        let bad = |t: &str, kind: &str| {
            err(format!(
                "'{}' is not {kind} ({} array); fix or export the file again",
                show(t.as_bytes()),
                if self.data_type.is_float() { "a floating-point" } else { "an integer" }
            ))
        };
        let short = |found: usize| {
            err(format!(
                "the ASCII data hold {found} values but the array announces {}; the file is \
                 truncated or corrupt, export it again",
                what()
            ))
        };
        let values = if self.data_type.is_float() {
            let mut v = Vec::with_capacity(capacity);
            for k in 0..n {
                let t = tokens.next().ok_or_else(|| short(k))?;
                // A FLOAT32 array's decimals are float32 values (as every GIFTI reader takes them).
                let x = if self.data_type == DataType::F32 {
                    t.parse::<f32>().map(f64::from)
                } else {
                    t.parse::<f64>()
                };
                v.push(x.map_err(|_| bad(t, "a number"))?);
            }
            Values::Float(v)
        } else {
            let mut v = Vec::with_capacity(capacity);
            for k in 0..n {
                let t = tokens.next().ok_or_else(|| short(k))?;
                v.push(t.parse::<i64>().map_err(|_| bad(t, "an integer"))?);
            }
            Values::Int(v)
        };
        if tokens.next().is_some() {
            return Err(err(format!(
                "the ASCII data hold more values than the {} the array announces; fix the \
                 dimensions or export the file again",
                what()
            )));
        }
        Ok(values)
    }

    fn decode_binary(&self, bytes: &[u8]) -> Values {
        let (ty, big) = (self.data_type, self.big_endian);
        let chunks = bytes.chunks_exact(ty.size());
        if ty.is_float() {
            Values::Float(
                chunks
                    .map(|c| match ty.value(c, big) {
                        Number::Float(x) => x,
                        Number::Int(i) => i as f64,
                    })
                    .collect(),
            )
        } else {
            Values::Int(
                chunks
                    .map(|c| match ty.value(c, big) {
                        Number::Int(i) => i,
                        Number::Float(x) => x as i64,
                    })
                    .collect(),
            )
        }
    }
}

/// Decompress zlib (or gzip) data, refusing more than `expected` bytes (+1 to detect excess).
fn inflate(raw: &[u8], expected: usize) -> std::io::Result<Vec<u8>> {
    let limit = expected as u64 + 1;
    let mut out = Vec::with_capacity(expected.min(raw.len().saturating_mul(8)));
    if raw.starts_with(&[0x1f, 0x8b]) {
        flate2::read::MultiGzDecoder::new(raw).take(limit).read_to_end(&mut out)?;
    } else {
        flate2::read::ZlibDecoder::new(raw).take(limit).read_to_end(&mut out)?;
    }
    Ok(out)
}

/// Column-major `d0 x d1 x ...` values to row-major.
fn reorder_column_major(values: Values, dims: &[usize]) -> Values {
    let n = values.len();
    // Row-major strides and column-major strides of the same shape.
    let mut row = vec![1usize; dims.len()];
    let mut col = vec![1usize; dims.len()];
    for k in (0..dims.len() - 1).rev() {
        row[k] = row[k + 1] * dims[k + 1];
    }
    for k in 1..dims.len() {
        col[k] = col[k - 1] * dims[k - 1];
    }
    let source = |r: usize| {
        let mut rest = r;
        let mut c = 0;
        for k in 0..dims.len() {
            let i = rest / row[k];
            rest %= row[k];
            c += i * col[k];
        }
        c
    };
    match values {
        Values::Float(v) => Values::Float((0..n).map(|r| v[source(r)]).collect()),
        Values::Int(v) => Values::Int((0..n).map(|r| v[source(r)]).collect()),
    }
}
