//! The map on its cap (paper Fig. 4-5, middle column): the input's faces at their cap
//! positions, coloured by their area distortion `d_area`, with a colour bar.

use super::colormap::{diverging, symmetric_range, with_colour_bar, NO_VALUE};
use super::encode::write_png;
use super::raster::Scene;
use super::views::three_views;
use super::FigureError;
use crate::cap::CapMap;
use crate::mesh::TriMesh;
use std::path::{Path, PathBuf};

/// Write the cap coloured by `d_area` to `dir/stem.png`; returns the file and its size.
pub fn write_cap(mesh: &TriMesh, map: &CapMap, dir: &Path, stem: &str, size: u32) -> Result<(PathBuf, (u32, u32)), FigureError> {
    let name = format!("{stem}.png");
    let path = dir.join(&name);
    let d = &map.face_area_distortion;
    let range = symmetric_range(d);
    let colours = |f: usize| d.get(f).map_or(NO_VALUE, |&v| diverging(v / range));
    let scene = Scene { vertices: &map.cap, faces: &mesh.faces, colours: &colours, edges: false };
    let title = match map.report.z_star {
        Some(z) => format!("the map on its cap Z >= Z* = {z:.4}, coloured by d_area"),
        None => "the map on its domain, coloured by d_area".to_string(),
    };
    let views = three_views(&scene, &title, size, &name)?;
    let image = with_colour_bar(&views, range, "d_area", &name)?;
    write_png(&image, &path)?;
    Ok((path, (image.width, image.height)))
}
