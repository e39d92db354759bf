//! Reading PLY values from the data section, ASCII (tokens, any layout) or binary (either
//! byte order), with bounds checks everywhere.

use super::header::Scalar;
use crate::io::error::Location;
use crate::io::text::{parse_f64, parse_i64, show};

/// Why a value could not be read.
pub(crate) enum ValueError {
    /// The data ended.
    Eof,
    /// The value is malformed (message).
    Bad(String),
}

/// A stream of PLY values.
pub(crate) trait Source {
    /// A value as `f64` (any type).
    fn real(&mut self, ty: Scalar) -> Result<f64, ValueError>;
    /// An integer value (`ty` must be an integer type).
    fn integer(&mut self, ty: Scalar) -> Result<i64, ValueError>;
    /// Skip `n` values of type `ty`.
    fn skip(&mut self, ty: Scalar, n: u64) -> Result<(), ValueError>;
    /// Where the next value starts.
    fn location(&self) -> Location;
    /// Bytes left (an upper bound on the number of values left).
    fn remaining(&self) -> usize;
}

/// ASCII data: whitespace-separated tokens, line numbers tracked.
pub(crate) struct AsciiSource<'a> {
    data: &'a [u8],
    pos: usize,
    line: usize,
}

impl<'a> AsciiSource<'a> {
    pub(crate) fn new(data: &'a [u8], start: usize, first_line: usize) -> Self {
        Self {
            data,
            pos: start.min(data.len()),
            line: first_line,
        }
    }

    fn token(&mut self) -> Result<&'a [u8], ValueError> {
        while let Some(&b) = self.data.get(self.pos) {
            if !b.is_ascii_whitespace() {
                break;
            }
            if b == b'\n' {
                self.line += 1;
            }
            self.pos += 1;
        }
        let start = self.pos;
        while self
            .data
            .get(self.pos)
            .is_some_and(|b| !b.is_ascii_whitespace())
        {
            self.pos += 1;
        }
        if start == self.pos {
            Err(ValueError::Eof)
        } else {
            Ok(&self.data[start..self.pos])
        }
    }
}

impl Source for AsciiSource<'_> {
    fn real(&mut self, _ty: Scalar) -> Result<f64, ValueError> {
        let tok = self.token()?;
        parse_f64(tok).ok_or_else(|| ValueError::Bad(format!("'{}' is not a number", show(tok))))
    }

    fn integer(&mut self, _ty: Scalar) -> Result<i64, ValueError> {
        let tok = self.token()?;
        parse_i64(tok).ok_or_else(|| ValueError::Bad(format!("'{}' is not an integer", show(tok))))
    }

    fn skip(&mut self, _ty: Scalar, n: u64) -> Result<(), ValueError> {
        for _ in 0..n {
            self.token()?;
        }
        Ok(())
    }

    fn location(&self) -> Location {
        // The line of the next token: count the newlines in the whitespace ahead.
        let mut line = self.line;
        for &b in &self.data[self.pos..] {
            if !b.is_ascii_whitespace() {
                break;
            }
            if b == b'\n' {
                line += 1;
            }
        }
        Location::Line(line)
    }

    fn remaining(&self) -> usize {
        self.data.len() - self.pos
    }
}

/// Binary data in either byte order.
pub(crate) struct BinarySource<'a> {
    data: &'a [u8],
    pos: usize,
    big_endian: bool,
}

impl<'a> BinarySource<'a> {
    pub(crate) fn new(data: &'a [u8], start: usize, big_endian: bool) -> Self {
        Self {
            data,
            pos: start.min(data.len()),
            big_endian,
        }
    }

    fn bytes<const N: usize>(&mut self) -> Result<[u8; N], ValueError> {
        let end = self.pos.checked_add(N).ok_or(ValueError::Eof)?;
        let slice = self.data.get(self.pos..end).ok_or(ValueError::Eof)?;
        let mut out = [0u8; N];
        out.copy_from_slice(slice);
        if self.big_endian {
            out.reverse();
        }
        self.pos = end;
        Ok(out)
    }

    /// Reads a value: integers exactly as `i64`, floats as `f64`.
    fn value(&mut self, ty: Scalar) -> Result<Value, ValueError> {
        Ok(match ty {
            Scalar::I8 => Value::Int(i64::from(i8::from_le_bytes(self.bytes()?))),
            Scalar::U8 => Value::Int(i64::from(u8::from_le_bytes(self.bytes()?))),
            Scalar::I16 => Value::Int(i64::from(i16::from_le_bytes(self.bytes()?))),
            Scalar::U16 => Value::Int(i64::from(u16::from_le_bytes(self.bytes()?))),
            Scalar::I32 => Value::Int(i64::from(i32::from_le_bytes(self.bytes()?))),
            Scalar::U32 => Value::Int(i64::from(u32::from_le_bytes(self.bytes()?))),
            Scalar::F32 => Value::Real(f64::from(f32::from_le_bytes(self.bytes()?))),
            Scalar::F64 => Value::Real(f64::from_le_bytes(self.bytes()?)),
        })
    }
}

enum Value {
    Int(i64),
    Real(f64),
}

impl Source for BinarySource<'_> {
    fn real(&mut self, ty: Scalar) -> Result<f64, ValueError> {
        Ok(match self.value(ty)? {
            Value::Int(i) => i as f64,
            Value::Real(x) => x,
        })
    }

    fn integer(&mut self, ty: Scalar) -> Result<i64, ValueError> {
        match self.value(ty)? {
            Value::Int(i) => Ok(i),
            Value::Real(_) => Err(ValueError::Bad("expected an integer type".into())),
        }
    }

    fn skip(&mut self, ty: Scalar, n: u64) -> Result<(), ValueError> {
        let len = (ty.size() as u64).checked_mul(n).ok_or(ValueError::Eof)?;
        let left = (self.data.len() - self.pos) as u64;
        if len > left {
            self.pos = self.data.len();
            return Err(ValueError::Eof);
        }
        self.pos += len as usize;
        Ok(())
    }

    fn location(&self) -> Location {
        Location::Byte(self.pos as u64)
    }

    fn remaining(&self) -> usize {
        self.data.len() - self.pos
    }
}
