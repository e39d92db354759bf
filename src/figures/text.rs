//! Text over an RGB image (view names, titles, colour-bar labels), drawn by plotters with
//! the bundled font.

use super::encode::RgbImage;
use super::{font, FigureError};
use plotters::backend::{BitMapBackend, RGBPixel};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Where a label's position is on the label.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Anchor {
    /// The label's top-left corner.
    TopLeft,
    /// The middle of its left side.
    MiddleLeft,
    /// The middle of its top side.
    TopCentre,
}

/// One line of text.
#[derive(Debug, Clone)]
pub struct Label {
    text: String,
    at: (i32, i32),
    size: u32,
    anchor: Anchor,
}

impl Label {
    /// `text` at `at` (pixels), `size` pixels high.
    pub fn new(text: &str, at: (i32, i32), size: u32, anchor: Anchor) -> Self {
        Self { text: text.to_string(), at, size, anchor }
    }
}

/// Draw `labels` in dark grey onto `image`.
pub fn draw_texts(image: &mut RgbImage, labels: &[Label], figure: &str) -> Result<(), FigureError> {
    font::ensure()?;
    let (w, h) = (image.width, image.height);
    let backend = BitMapBackend::<RGBPixel>::with_buffer_and_format(&mut image.pixels, (w, h)).map_err(|e| FigureError::draw(figure, e))?;
    let root = backend.into_drawing_area();
    for l in labels {
        let pos = match l.anchor {
            Anchor::TopLeft => Pos::new(HPos::Left, VPos::Top),
            Anchor::MiddleLeft => Pos::new(HPos::Left, VPos::Center),
            Anchor::TopCentre => Pos::new(HPos::Center, VPos::Top),
        };
        let style = TextStyle::from((font::FAMILY, l.size).into_font()).color(&RGBColor(30, 30, 30)).pos(pos);
        root.draw_text(&l.text, &style, l.at).map_err(|e| FigureError::draw(figure, e))?;
    }
    root.present().map_err(|e| FigureError::draw(figure, e))?;
    Ok(())
}
