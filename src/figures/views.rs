//! Three shaded views of one mesh side by side ([`super::raster::VIEWS`]), with a title and
//! the views' names above them.

use super::encode::RgbImage;
use super::raster::{render, Frame, Scene, BACKGROUND, VIEWS};
use super::text::{draw_texts, Anchor, Label};
use super::FigureError;

/// Height of the strip over the views: the title, then the views' names.
pub const HEADER: u32 = 44;

/// Largest side of one view in pixels.
pub const MAX_VIEW_SIZE: u32 = 4096;

/// The three views of `scene`, each `size` pixels square, under `title`: an image of
/// `3 * size` x `size + HEADER` pixels.
pub fn three_views(scene: &Scene<'_>, title: &str, size: u32, figure: &str) -> Result<RgbImage, FigureError> {
    let frame = Frame::of(scene.vertices, scene.faces).ok_or_else(|| FigureError::Empty { figure: figure.to_string(), why: "the mesh has no face with finite corners".into() })?;
    if !(16..=MAX_VIEW_SIZE).contains(&size) {
        return Err(FigureError::Empty { figure: figure.to_string(), why: format!("views of {size} px: choose 16 to {MAX_VIEW_SIZE} px") });
    }
    let mut out = RgbImage::filled(3 * size, size + HEADER, BACKGROUND);
    let mut labels = vec![Label::new(title, (8, 7), 16, Anchor::TopLeft)];
    for (i, view) in VIEWS.iter().enumerate() {
        out.paste(&render(scene, view, &frame, size), i as u32 * size, HEADER);
        labels.push(Label::new(view.name, ((i as u32 * size + size / 2) as i32, 27), 13, Anchor::TopCentre));
    }
    draw_texts(&mut out, &labels, figure)?;
    Ok(out)
}
