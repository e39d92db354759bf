//! Writing per-vertex data as a GIFTI data file (`.shape.gii`, `.label.gii`): one
//! `NIFTI_INTENT_SHAPE` array of `FLOAT32` values or one `NIFTI_INTENT_LABEL` array of `INT32`
//! labels with its `LabelTable`, named by its `Name` metadata, in the encoding and byte order
//! of [`GiftiOptions`] (what `capmesh remesh --attribute` writes beside a GIFTI remesh).

use std::io::Write;

use super::write::binary_data;
use super::{Endian, GiftiEncoding, GiftiOptions};
use crate::io::{AttributeData, VertexAttribute};

/// `s` with the XML special characters escaped.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// Write `attribute` as a GIFTI data file.
pub(crate) fn write_attribute(w: &mut dyn Write, attribute: &VertexAttribute, options: &GiftiOptions) -> std::io::Result<()> {
    writeln!(w, r#"<?xml version="1.0" encoding="UTF-8"?>"#)?;
    writeln!(w, r#"<!DOCTYPE GIFTI SYSTEM "http://www.nitrc.org/frs/download.php/115/gifti.dtd">"#)?;
    writeln!(w, r#"<GIFTI Version="1.0" NumberOfDataArrays="1">"#)?;
    writeln!(w, "  <MetaData/>")?;
    if attribute.label_table.is_empty() {
        writeln!(w, "  <LabelTable/>")?;
    } else {
        writeln!(w, "  <LabelTable>")?;
        for (key, name) in &attribute.label_table {
            writeln!(w, r#"    <Label Key="{key}"><![CDATA[{}]]></Label>"#, name.replace("]]>", "]]]]><![CDATA[>"))?;
        }
        writeln!(w, "  </LabelTable>")?;
    }
    let (intent, data_type) = match attribute.data {
        AttributeData::Scalar(_) => ("NIFTI_INTENT_SHAPE", "NIFTI_TYPE_FLOAT32"),
        AttributeData::Label(_) => ("NIFTI_INTENT_LABEL", "NIFTI_TYPE_INT32"),
    };
    let encoding = match options.encoding {
        GiftiEncoding::Ascii => "ASCII",
        GiftiEncoding::Base64Binary => "Base64Binary",
        GiftiEncoding::GzipBase64Binary => "GZipBase64Binary",
    };
    let big = options.endian == Endian::Big;
    let endian = if big { "BigEndian" } else { "LittleEndian" };
    writeln!(
        w,
        r#"  <DataArray Intent="{intent}" DataType="{data_type}" ArrayIndexingOrder="RowMajorOrder" Dimensionality="1" Dim0="{}" Encoding="{encoding}" Endian="{endian}" ExternalFileName="" ExternalFileOffset="">"#,
        attribute.data.len()
    )?;
    writeln!(w, r#"    <MetaData><MD><Name>Name</Name><Value>{}</Value></MD></MetaData>"#, escape(&attribute.name))?;
    if options.encoding == GiftiEncoding::Ascii {
        write!(w, "    <Data>")?;
        match &attribute.data {
            AttributeData::Scalar(v) => v.iter().try_for_each(|x| writeln!(w, "{x:?}"))?,
            AttributeData::Label(v) => v.iter().try_for_each(|x| writeln!(w, "{x}"))?,
        }
    } else {
        let raw: Vec<u8> = match &attribute.data {
            AttributeData::Scalar(v) => v.iter().flat_map(|x| if big { x.to_be_bytes() } else { x.to_le_bytes() }).collect(),
            AttributeData::Label(v) => v.iter().flat_map(|x| if big { x.to_be_bytes() } else { x.to_le_bytes() }).collect(),
        };
        binary_data(w, &raw, options)?;
    }
    writeln!(w, "</Data>\n  </DataArray>")?;
    writeln!(w, "</GIFTI>")
}
