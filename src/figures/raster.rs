//! A small z-buffer rasterizer for the shaded views: orthographic projection along one of
//! three fixed directions, flat Lambert shading of each face (two-sided, so inward- and
//! outward-oriented meshes look the same), optional dark edges, 2x2 supersampling. Single
//! threaded and in a fixed order, so the same mesh gives the same pixels.

use super::encode::RgbImage;
use crate::mesh::geometry::{cross, dot, norm, sub};

/// One fixed orthographic view: screen axes `right` and `up`, and `toward` (from the object
/// to the viewer) as the depth axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    /// Name shown over the view.
    pub name: &'static str,
    /// Screen x axis in model coordinates.
    pub right: [f64; 3],
    /// Screen y axis in model coordinates.
    pub up: [f64; 3],
    /// From the object towards the viewer.
    pub toward: [f64; 3],
}

/// The three views of every rendering: from the front (-Y), from the side (+X) and from the
/// top (+Z); a cap `Z >= Z*` is seen from the top as a disk.
pub const VIEWS: [View; 3] = [
    View { name: "front (-Y)", right: [1.0, 0.0, 0.0], up: [0.0, 0.0, 1.0], toward: [0.0, -1.0, 0.0] },
    View { name: "side (+X)", right: [0.0, 1.0, 0.0], up: [0.0, 0.0, 1.0], toward: [1.0, 0.0, 0.0] },
    View { name: "top (+Z)", right: [1.0, 0.0, 0.0], up: [0.0, 1.0, 0.0], toward: [0.0, 0.0, 1.0] },
];

/// Background of the views.
pub const BACKGROUND: [u8; 3] = [255, 255, 255];

/// Colour of the edges drawn with [`Scene::edges`].
const EDGE_COLOUR: [f64; 3] = [40.0, 40.0, 40.0];

/// Supersampling factor per axis.
const SUPERSAMPLE: u32 = 2;

/// Share of the light that does not depend on the face's orientation.
const AMBIENT: f64 = 0.3;

/// Shading steps between black and full light.
const SHADES: f64 = 24.0;

/// What to draw: positions, faces, one colour per face, and whether to outline the faces.
pub struct Scene<'a> {
    /// Vertex positions.
    pub vertices: &'a [[f64; 3]],
    /// Triangles (faces with an index out of range are skipped).
    pub faces: &'a [[u32; 3]],
    /// Base colour of each face (before shading).
    pub colours: &'a dyn Fn(usize) -> [u8; 3],
    /// Outline every face (edge width about one pixel).
    pub edges: bool,
}

/// The framing shared by the three views: the bounding box's centre and the largest distance
/// of a vertex from it, so that the object has the same size in every view.
#[derive(Debug, Clone, Copy)]
pub struct Frame {
    /// Centre of the bounding box.
    pub centre: [f64; 3],
    /// Largest distance of a vertex from the centre (at least a tiny positive number).
    pub radius: f64,
}

impl Frame {
    /// The frame of the finite vertices used by `faces`; `None` when there is none.
    pub fn of(vertices: &[[f64; 3]], faces: &[[u32; 3]]) -> Option<Self> {
        let used = || faces.iter().flatten().filter_map(|&v| vertices.get(v as usize)).filter(|p| p.iter().all(|c| c.is_finite()));
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for p in used() {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        if !lo[0].is_finite() {
            return None;
        }
        let centre = [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])];
        let radius = used().map(|p| norm(sub(*p, centre))).fold(0.0, f64::max);
        Some(Self { centre, radius: if radius > 0.0 { radius } else { 1.0 } })
    }
}

/// Render `scene` seen along `view` into a `size` x `size` image, the frame's sphere filling
/// 92% of it.
pub fn render(scene: &Scene<'_>, view: &View, frame: &Frame, size: u32) -> RgbImage {
    let n = size * SUPERSAMPLE;
    let nf = f64::from(n);
    let scale = 0.46 * nf / frame.radius;
    let project = |p: [f64; 3]| {
        let d = sub(p, frame.centre);
        [0.5 * nf + scale * dot(d, view.right), 0.5 * nf - scale * dot(d, view.up), dot(d, view.toward)]
    };
    let light = unit([view.toward[0] + 0.35 * view.up[0] - 0.25 * view.right[0], view.toward[1] + 0.35 * view.up[1] - 0.25 * view.right[1], view.toward[2] + 0.35 * view.up[2] - 0.25 * view.right[2]]);
    let mut colour = vec![BACKGROUND.map(f64::from); (n * n) as usize];
    let mut depth = vec![f64::NEG_INFINITY; (n * n) as usize];
    let edge_width = 0.75 * f64::from(SUPERSAMPLE);
    for (f, face) in scene.faces.iter().enumerate() {
        let Some(p) = corners(scene.vertices, face) else { continue };
        let normal = cross(sub(p[1], p[0]), sub(p[2], p[0]));
        let len = norm(normal);
        if !(len > 0.0) {
            continue;
        }
        // In steps of 1 / SHADES: smooth enough to read the shape, and fewer distinct colours
        // keep the PNG small.
        let shade = ((AMBIENT + (1.0 - AMBIENT) * (dot(normal, light) / len).abs()) * SHADES).round() / SHADES;
        let base = (scene.colours)(f).map(|c| f64::from(c) * shade);
        let q = p.map(project);
        let area2 = (q[1][0] - q[0][0]) * (q[2][1] - q[0][1]) - (q[1][1] - q[0][1]) * (q[2][0] - q[0][0]);
        if area2 == 0.0 || !area2.is_finite() {
            continue;
        }
        // Edge lengths on screen, opposite each corner.
        let edge_len = [0usize, 1, 2].map(|i| {
            let (a, b) = (q[(i + 1) % 3], q[(i + 2) % 3]);
            (b[0] - a[0]).hypot(b[1] - a[1])
        });
        let x0 = q.iter().map(|c| c[0]).fold(f64::INFINITY, f64::min).floor().max(0.0) as u32;
        let x1 = (q.iter().map(|c| c[0]).fold(f64::NEG_INFINITY, f64::max).ceil().min(nf - 1.0)).max(-1.0);
        let y0 = q.iter().map(|c| c[1]).fold(f64::INFINITY, f64::min).floor().max(0.0) as u32;
        let y1 = (q.iter().map(|c| c[1]).fold(f64::NEG_INFINITY, f64::max).ceil().min(nf - 1.0)).max(-1.0);
        if x1 < 0.0 || y1 < 0.0 {
            continue;
        }
        for y in y0..=(y1 as u32) {
            for x in x0..=(x1 as u32) {
                let (px, py) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
                // Barycentric weights from the sub-triangles' signed areas.
                let w = [0usize, 1, 2].map(|i| {
                    let (a, b) = (q[(i + 1) % 3], q[(i + 2) % 3]);
                    ((b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0])) / area2
                });
                if w.iter().any(|&wi| wi < 0.0) {
                    continue;
                }
                let z = w[0] * q[0][2] + w[1] * q[1][2] + w[2] * q[2][2];
                let at = (y * n + x) as usize;
                if z <= depth[at] {
                    continue;
                }
                depth[at] = z;
                // Distance to the nearest edge in (supersampled) pixels.
                let near_edge = scene.edges && (0..3).any(|i| w[i] * area2.abs() / edge_len[i] < edge_width);
                colour[at] = if near_edge { EDGE_COLOUR } else { base };
            }
        }
    }
    downsample(&colour, n, size)
}

/// The three corners of `face`, `None` when an index is out of range or a coordinate not
/// finite.
fn corners(vertices: &[[f64; 3]], face: &[u32; 3]) -> Option<[[f64; 3]; 3]> {
    let p = [vertices.get(face[0] as usize)?, vertices.get(face[1] as usize)?, vertices.get(face[2] as usize)?];
    p.iter().all(|c| c.iter().all(|x| x.is_finite())).then(|| [*p[0], *p[1], *p[2]])
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let l = norm(v);
    [v[0] / l, v[1] / l, v[2] / l]
}

/// Average each `SUPERSAMPLE` x `SUPERSAMPLE` block of the `n` x `n` image.
fn downsample(colour: &[[f64; 3]], n: u32, size: u32) -> RgbImage {
    let mut pixels = Vec::with_capacity(3 * (size * size) as usize);
    let s = SUPERSAMPLE;
    let weight = 1.0 / f64::from(s * s);
    for y in 0..size {
        for x in 0..size {
            let mut sum = [0.0; 3];
            for dy in 0..s {
                for dx in 0..s {
                    let c = colour[((y * s + dy) * n + x * s + dx) as usize];
                    for k in 0..3 {
                        sum[k] += c[k];
                    }
                }
            }
            pixels.extend(sum.map(|c| (c * weight).round().clamp(0.0, 255.0) as u8));
        }
    }
    RgbImage { width: size, height: size, pixels }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearer_face_hides_the_farther_one() {
        // Two parallel squares seen from the top: the upper one (red) must win everywhere.
        let v = vec![
            [-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [1.0, 1.0, 0.0], [-1.0, 1.0, 0.0],
            [-1.0, -1.0, 1.0], [1.0, -1.0, 1.0], [1.0, 1.0, 1.0], [-1.0, 1.0, 1.0],
        ];
        let f = vec![[4, 5, 6], [4, 6, 7], [0, 1, 2], [0, 2, 3]];
        let colours = |f: usize| if f < 2 { [255, 0, 0] } else { [0, 0, 255] };
        let scene = Scene { vertices: &v, faces: &f, colours: &colours, edges: false };
        let frame = Frame::of(&v, &f).unwrap();
        let img = render(&scene, &VIEWS[2], &frame, 40);
        let centre = 3 * (20 * 40 + 20) as usize;
        let px = &img.pixels[centre..centre + 3];
        assert!(px[0] > 150 && px[2] == 0, "{px:?}");
        // Seen from the front both are edge-on: nothing but background.
        let img = render(&scene, &VIEWS[0], &frame, 40);
        assert!(img.pixels.chunks(3).all(|p| p == BACKGROUND), "edge-on squares drew pixels");
    }
}
