//! Writing the figures: an RGB image as PNG (the `png` crate, fixed settings, so the same
//! pixels give the same bytes) and SVG text as it is.

use super::FigureError;
use std::path::Path;

/// An 8-bit RGB image, rows top to bottom.
#[derive(Debug, Clone, PartialEq)]
pub struct RgbImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `3 * width * height` bytes.
    pub pixels: Vec<u8>,
}

impl RgbImage {
    /// An image filled with `colour`.
    pub fn filled(width: u32, height: u32, colour: [u8; 3]) -> Self {
        let pixels = colour.iter().copied().cycle().take(3 * width as usize * height as usize).collect();
        Self { width, height, pixels }
    }

    /// Copy `other` into this image with its top-left corner at `(x, y)` (clipped).
    pub fn paste(&mut self, other: &RgbImage, x: u32, y: u32) {
        for row in 0..other.height.min(self.height.saturating_sub(y)) {
            let n = 3 * other.width.min(self.width.saturating_sub(x)) as usize;
            let src = 3 * (row * other.width) as usize;
            let dst = 3 * ((y + row) * self.width + x) as usize;
            self.pixels[dst..dst + n].copy_from_slice(&other.pixels[src..src + n]);
        }
    }
}

/// The PNG bytes of `image`.
pub fn png_bytes(image: &RgbImage, path: &Path) -> Result<Vec<u8>, FigureError> {
    let encode_error = |e: png::EncodingError| FigureError::Encode { path: path.to_path_buf(), message: e.to_string() };
    let mut bytes = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut bytes, image.width, image.height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::Best);
        encoder.set_filter(png::FilterType::Paeth);
        encoder.set_adaptive_filter(png::AdaptiveFilterType::Adaptive);
        let mut writer = encoder.write_header().map_err(encode_error)?;
        writer.write_image_data(&image.pixels).map_err(encode_error)?;
        writer.finish().map_err(encode_error)?;
    }
    Ok(bytes)
}

/// Write `image` to `path` as PNG.
pub fn write_png(image: &RgbImage, path: &Path) -> Result<(), FigureError> {
    let bytes = png_bytes(image, path)?;
    write_file(path, &bytes)
}

/// Write `bytes` to `path` atomically ([`crate::io::atomic`]): a stopped run leaves the
/// earlier figure or none, never a part of one.
pub fn write_file(path: &Path, bytes: &[u8]) -> Result<(), FigureError> {
    let io = |source| FigureError::Io { path: path.to_path_buf(), source };
    let mut file = crate::io::atomic::AtomicFile::create(path).map_err(io)?;
    std::io::Write::write_all(&mut file, bytes).map_err(io)?;
    file.commit().map_err(io)
}
