//! The charts (histograms and curves) drawn by plotters: one drawing routine per chart, run on
//! the bitmap backend for the PNG and on the SVG backend for the SVG, so both show the same.

use super::encode::{write_file, write_png, RgbImage};
use super::{font, FigureError};
use plotters::backend::{BitMapBackend, RGBPixel, SVGBackend};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// A chart that can be drawn on any plotters backend.
pub trait Chart {
    /// Draw onto `root` (already filled white); an error is plotters' message.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String>;
}

/// Draw `chart` as `dir/stem.png` (and `dir/stem.svg` with `svg`) of `size` pixels; returns
/// the files written.
pub fn write_chart<C: Chart>(chart: &C, dir: &Path, stem: &str, size: (u32, u32), svg: bool) -> Result<(PathBuf, Option<PathBuf>), FigureError> {
    font::ensure()?;
    if !(160..=8192).contains(&size.0) || !(120..=8192).contains(&size.1) {
        return Err(FigureError::Empty { figure: format!("{stem}.png"), why: format!("a chart of {} x {} px: choose 160 x 120 to 8192 x 8192 px", size.0, size.1) });
    }
    let png_path = dir.join(format!("{stem}.png"));
    let name = format!("{stem}.png");
    let mut image = RgbImage::filled(size.0, size.1, [255, 255, 255]);
    {
        let backend = BitMapBackend::<RGBPixel>::with_buffer_and_format(&mut image.pixels, size).map_err(|e| FigureError::draw(&name, e))?;
        let root = backend.into_drawing_area();
        chart.draw(&root).map_err(|e| FigureError::draw(&name, e))?;
        root.present().map_err(|e| FigureError::draw(&name, e))?;
    }
    write_png(&image, &png_path)?;
    let svg_path = if svg {
        let path = dir.join(format!("{stem}.svg"));
        let name = format!("{stem}.svg");
        let mut text = String::new();
        {
            let root = SVGBackend::with_string(&mut text, size).into_drawing_area();
            root.fill(&WHITE).map_err(|e| FigureError::draw(&name, e))?;
            chart.draw(&root).map_err(|e| FigureError::draw(&name, e))?;
            root.present().map_err(|e| FigureError::draw(&name, e))?;
        }
        write_file(&path, text.as_bytes())?;
        Some(path)
    } else {
        None
    };
    Ok((png_path, svg_path))
}

/// Plotters' error as text.
pub fn text(e: impl std::fmt::Display) -> String {
    e.to_string()
}
