//! The PLY header: format, elements and their properties.

use std::path::Path;

use crate::io::error::{Location, ReadError};
use crate::io::parse_error;
use crate::io::text::{show, tokens};

/// A PLY scalar type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn parse(name: &[u8]) -> Option<Scalar> {
        Some(match name {
            b"char" | b"int8" => Scalar::I8,
            b"uchar" | b"uint8" => Scalar::U8,
            b"short" | b"int16" => Scalar::I16,
            b"ushort" | b"uint16" => Scalar::U16,
            b"int" | b"int32" => Scalar::I32,
            b"uint" | b"uint32" => Scalar::U32,
            b"float" | b"float32" => Scalar::F32,
            b"double" | b"float64" => Scalar::F64,
            _ => return None,
        })
    }

    /// Size in bytes in binary PLY.
    pub(crate) fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    pub(crate) fn is_integer(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }
}

/// A property of an element.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum Property {
    /// One value.
    Scalar { name: Vec<u8>, ty: Scalar },
    /// A count followed by that many values.
    List {
        name: Vec<u8>,
        count: Scalar,
        item: Scalar,
    },
}

impl Property {
    pub(crate) fn name(&self) -> &[u8] {
        match self {
            Property::Scalar { name, .. } | Property::List { name, .. } => name,
        }
    }
}

/// An element declaration.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Element {
    pub(crate) name: Vec<u8>,
    pub(crate) count: u64,
    pub(crate) properties: Vec<Property>,
}

/// How the data section is stored.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Encoding {
    Ascii,
    BinaryLittleEndian,
    BinaryBigEndian,
}

/// A parsed header.
#[derive(Debug, Clone)]
pub(crate) struct Header {
    pub(crate) encoding: Encoding,
    pub(crate) elements: Vec<Element>,
    /// Byte offset where the data starts.
    pub(crate) data_start: usize,
    /// Number of header lines (the data's first line is `header_lines + 1`).
    pub(crate) header_lines: usize,
}

/// Parse the header; the data starts right after the `end_header` line's `\n` (or `\r\n`).
pub(crate) fn parse(path: &Path, data: &[u8]) -> Result<Header, ReadError> {
    let unsupported = |message: String| ReadError::UnsupportedPly {
        path: path.to_path_buf(),
        message,
    };
    let mut pos = 0usize;
    let mut line_no = 0usize;
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    loop {
        let rest = &data[pos..];
        let Some(nl) = rest.iter().position(|&b| b == b'\n') else {
            let message = if line_no == 0 && !rest.starts_with(b"ply") {
                "not a PLY file: the first line must be 'ply'".to_string()
            } else {
                "the header has no 'end_header' line: the file is truncated or not a PLY file"
                    .to_string()
            };
            return Err(parse_error(path, Location::Line(line_no + 1), message));
        };
        let raw = &rest[..nl];
        let line = raw.strip_suffix(b"\r").unwrap_or(raw);
        pos += nl + 1;
        line_no += 1;
        let at = Location::Line(line_no);
        let toks: Vec<&[u8]> = tokens(line).collect();
        if line_no == 1 {
            if toks.as_slice() != [b"ply"] {
                return Err(parse_error(
                    path,
                    at,
                    "not a PLY file: the first line must be 'ply'".into(),
                ));
            }
            continue;
        }
        match toks.first().copied() {
            None | Some(b"comment") | Some(b"obj_info") => {}
            Some(b"format") => {
                encoding = Some(match toks.get(1).copied() {
                    Some(b"ascii") => Encoding::Ascii,
                    Some(b"binary_little_endian") => Encoding::BinaryLittleEndian,
                    Some(b"binary_big_endian") => Encoding::BinaryBigEndian,
                    other => {
                        return Err(unsupported(format!(
                            "unknown format '{}' on line {line_no}",
                            show(other.unwrap_or(b""))
                        )))
                    }
                });
            }
            Some(b"element") => {
                let (Some(name), Some(count)) = (toks.get(1), toks.get(2)) else {
                    return Err(parse_error(
                        path,
                        at,
                        "expected 'element <name> <count>'".into(),
                    ));
                };
                let count = std::str::from_utf8(count)
                    .ok()
                    .and_then(|s| s.parse::<u64>().ok())
                    .ok_or_else(|| {
                        parse_error(
                            path,
                            at,
                            format!("'{}' is not a valid element count", show(count)),
                        )
                    })?;
                elements.push(Element {
                    name: name.to_vec(),
                    count,
                    properties: Vec::new(),
                });
            }
            Some(b"property") => {
                let Some(element) = elements.last_mut() else {
                    return Err(parse_error(
                        path,
                        at,
                        "'property' before any 'element'".into(),
                    ));
                };
                let ty = |tok: Option<&&[u8]>| -> Result<Scalar, ReadError> {
                    let tok = tok.copied().unwrap_or(b"");
                    Scalar::parse(tok).ok_or_else(|| {
                        unsupported(format!(
                            "unknown property type '{}' on line {line_no}",
                            show(tok)
                        ))
                    })
                };
                let property = if toks.get(1).copied() == Some(b"list") {
                    let (count, item) = (ty(toks.get(2))?, ty(toks.get(3))?);
                    let name = toks.get(4).ok_or_else(|| {
                        parse_error(
                            path,
                            at,
                            "expected 'property list <count type> <item type> <name>'".into(),
                        )
                    })?;
                    if !count.is_integer() {
                        return Err(unsupported(format!(
                            "the list '{}' has a floating-point count type",
                            show(name)
                        )));
                    }
                    Property::List {
                        name: name.to_vec(),
                        count,
                        item,
                    }
                } else {
                    let name = toks.get(2).ok_or_else(|| {
                        parse_error(path, at, "expected 'property <type> <name>'".into())
                    })?;
                    Property::Scalar {
                        name: name.to_vec(),
                        ty: ty(toks.get(1))?,
                    }
                };
                element.properties.push(property);
            }
            Some(b"end_header") => break,
            Some(other) => {
                return Err(parse_error(
                    path,
                    at,
                    format!("unknown header keyword '{}'", show(other)),
                ))
            }
        }
    }
    let encoding = encoding.ok_or_else(|| {
        parse_error(
            path,
            Location::Line(2),
            "the header has no 'format' line (ascii, binary_little_endian or binary_big_endian)"
                .into(),
        )
    })?;
    Ok(Header {
        encoding,
        elements,
        data_start: pos,
        header_lines: line_no,
    })
}
