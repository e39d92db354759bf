//! Shaded renderings of a mesh in one colour: the input, the remesh with its edges, the
//! harmonic reconstruction.

use super::encode::write_png;
use super::raster::Scene;
use super::views::three_views;
use super::FigureError;
use crate::mesh::TriMesh;
use std::path::{Path, PathBuf};

/// Colour of the input surface.
pub const INPUT_COLOUR: [u8; 3] = [205, 190, 160];
/// Colour of a remesh.
pub const REMESH_COLOUR: [u8; 3] = [150, 185, 215];
/// Colour of a harmonic reconstruction.
pub const RECONSTRUCTION_COLOUR: [u8; 3] = [170, 205, 160];

/// Write the three views of `mesh` in `colour` (outlined faces with `edges`) to
/// `dir/stem.png`; returns the file and its size.
pub fn write_shaded(mesh: &TriMesh, colour: [u8; 3], edges: bool, title: &str, dir: &Path, stem: &str, size: u32) -> Result<(PathBuf, (u32, u32)), FigureError> {
    let path = dir.join(format!("{stem}.png"));
    let colours = move |_: usize| colour;
    let scene = Scene { vertices: &mesh.vertices, faces: &mesh.faces, colours: &colours, edges };
    let image = three_views(&scene, title, size, &format!("{stem}.png"))?;
    write_png(&image, &path)?;
    Ok((path, (image.width, image.height)))
}
