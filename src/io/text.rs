//! Hand-written tokenising for the text formats: lines (any of `\n`, `\r\n`, `\r`), ASCII
//! whitespace separated tokens, `#` comments, and number parsing with `str::parse`.

use std::path::Path;

use super::error::{Location, ReadError};
use super::parse_error;

/// Lines of a byte buffer with their 1-based numbers; line terminators are removed.
pub(crate) struct Lines<'a> {
    data: &'a [u8],
    pos: usize,
    line: usize,
}

impl<'a> Lines<'a> {
    pub(crate) fn new(data: &'a [u8]) -> Self {
        Self {
            data,
            pos: 0,
            line: 0,
        }
    }

    /// Number of the line returned last (0 before the first).
    pub(crate) fn line(&self) -> usize {
        self.line
    }
}

impl<'a> Iterator for Lines<'a> {
    type Item = (usize, &'a [u8]);

    fn next(&mut self) -> Option<Self::Item> {
        if self.pos >= self.data.len() {
            return None;
        }
        let rest = &self.data[self.pos..];
        let end = rest
            .iter()
            .position(|&b| b == b'\n' || b == b'\r')
            .unwrap_or(rest.len());
        let mut advance = end;
        if end < rest.len() {
            advance += 1;
            if rest[end] == b'\r' && rest.get(end + 1) == Some(&b'\n') {
                advance += 1;
            }
        }
        self.pos += advance;
        self.line += 1;
        Some((self.line, &rest[..end]))
    }
}

/// `line` up to (not including) the first `#`.
#[inline]
pub(crate) fn strip_comment(line: &[u8]) -> &[u8] {
    match line.iter().position(|&b| b == b'#') {
        Some(i) => &line[..i],
        None => line,
    }
}

/// Whitespace-separated tokens of a line.
#[inline]
pub(crate) fn tokens(line: &[u8]) -> impl Iterator<Item = &[u8]> {
    line.split(|b| b.is_ascii_whitespace())
        .filter(|t| !t.is_empty())
}

/// `true` when `line` has no token.
#[inline]
pub(crate) fn is_blank(line: &[u8]) -> bool {
    line.iter().all(|b| b.is_ascii_whitespace())
}

/// Parse a floating-point token (accepts what `f64::from_str` accepts, incl. `nan`, `inf`).
#[inline]
pub(crate) fn parse_f64(token: &[u8]) -> Option<f64> {
    std::str::from_utf8(token).ok()?.parse().ok()
}

/// Parse an integer token.
#[inline]
pub(crate) fn parse_i64(token: &[u8]) -> Option<i64> {
    std::str::from_utf8(token).ok()?.parse().ok()
}

/// A token for an error message: lossy UTF-8, at most 40 characters.
pub(crate) fn show(token: &[u8]) -> String {
    let s = String::from_utf8_lossy(token);
    let mut out: String = s.chars().take(40).collect();
    if s.chars().count() > 40 {
        out.push_str("...");
    }
    out
}

/// A vertex's three finite coordinates, the next tokens of line `at` of `path` (OBJ, OFF and
/// ASCII STL): `missing(k)` says what to do when only `k` are there; a token that is not a
/// number and a NaN or infinite coordinate are refused with the line named.
pub(crate) fn read_point<'a>(toks: &mut impl Iterator<Item = &'a [u8]>, path: &Path, at: Location, missing: impl Fn(usize) -> String) -> Result<[f64; 3], ReadError> {
    let mut p = [0.0; 3];
    for (k, c) in p.iter_mut().enumerate() {
        let tok = toks.next().ok_or_else(|| parse_error(path, at, missing(k)))?;
        *c = parse_f64(tok).ok_or_else(|| parse_error(path, at, format!("'{}' is not a number; fix this vertex", show(tok))))?;
    }
    if !p.iter().all(|x| x.is_finite()) {
        return Err(ReadError::NonFinite { path: path.to_path_buf(), at });
    }
    Ok(p)
}
