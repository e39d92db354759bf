//! Face sizing of the remesh (ours; the paper's remesh is uniform, Sec. 4.2): equal chord
//! areas, equal covered surface areas (a uniform vertex density on the surface), or a density
//! that grows with the surface's smoothed mean curvature, so that curved parts get smaller
//! faces at the same face count.
//!
//! A chord of length `h` on a surface of curvature `k` leaves it by about `k h^2 / 8`;
//! faces of equal error would have `h ~ k^(-1/2)`, a vertex density proportional to `k`.
//! `--sizing curvature=S` blends the two: density `1 + S k L`, with `L` the uniform remesh's
//! edge length (so `k L` is the curvature at the remesh's scale), normalised to mean 1 over
//! the surface's area so that the face count stays what was asked. The curvature is the
//! root mean square of the principal curvatures, `sqrt(2 H^2 - K)`, with the cotangent
//! Laplacian's mean curvature `H = |Delta x| / 2` and the angle defect's Gaussian curvature
//! `K` (Meyer et al. 2003, barycentric areas), smoothed over the remesh's scale by averaging
//! with the one-ring: a saddle, where `H` vanishes, is as curved as a sphere of its radii.

use crate::linalg::laplacian::cotangent_weights;
use crate::mesh::geometry::{angle_sums, norm, sub, vertex_areas};
use crate::mesh::topology::{is_boundary_vertex, vertex_neighbors};
use crate::mesh::TriMesh;

/// How the remesh's faces are sized.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Sizing {
    /// Equal areas: the paper's goal. The default.
    #[default]
    Uniform,
    /// Equal surface areas covered through the map (`remesh::shape::covered`): a uniform
    /// vertex density on the surface, as centroidal Voronoi and ACVD remeshers give. A face
    /// that bridges a fold or a thin edge finer than itself keeps its share of vertices there,
    /// so the remesh lies closer to the input, and its chord areas are less equal
    /// (docs/method.md, "Remesh sizing").
    Surface,
    /// Density `1 + strength * k * L` (see the module docs); `strength` finite and > 0.
    Curvature {
        /// The weight of the curvature term (`DEFAULT_CURVATURE_STRENGTH` on the command
        /// line): on the shared meshes 3 lowered the sampled surface distance by up to 36%
        /// where 1 lowered it by up to 21% (docs/method.md, "Remesh sizing").
        strength: f64,
    },
}

/// The curvature strength of `--sizing curvature` without a value.
pub const DEFAULT_CURVATURE_STRENGTH: f64 = 3.0;

impl Sizing {
    /// Whether the remesh's faces are measured by the surface they cover rather than by their
    /// chords (every sizing but [`Sizing::Uniform`]; `remesh::shape::covered`).
    pub(crate) fn by_covered(self) -> bool {
        self != Sizing::Uniform
    }
}

impl std::str::FromStr for Sizing {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let bad = || format!("unknown sizing {s:?}: use uniform (default), surface, curvature or curvature=S with S a number > 0 (e.g. curvature=2)");
        match s.split_once('=') {
            None if s == "uniform" => Ok(Sizing::Uniform),
            None if s == "surface" => Ok(Sizing::Surface),
            None if s == "curvature" => Ok(Sizing::Curvature { strength: DEFAULT_CURVATURE_STRENGTH }),
            Some(("curvature", v)) => match v.parse::<f64>() {
                Ok(x) if x.is_finite() && x > 0.0 => Ok(Sizing::Curvature { strength: x }),
                _ => Err(bad()),
            },
            _ => Err(bad()),
        }
    }
}

impl std::fmt::Display for Sizing {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Sizing::Uniform => write!(f, "uniform"),
            Sizing::Surface => write!(f, "surface"),
            Sizing::Curvature { strength } => write!(f, "curvature={strength}"),
        }
    }
}

impl serde::Serialize for Sizing {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

/// Smallest radius of curvature counted, in remesh edge lengths.
const MIN_RADIUS: f64 = 0.25;

/// Most one-ring averaging passes of the curvature.
const MAX_SMOOTHING_PASSES: usize = 50;

/// Each vertex's unsigned mean curvature `|Delta x| / 2` (barycentric areas); boundary
/// vertices, whose Laplacian measures the boundary's turn rather than the surface's, take
/// the mean of their interior neighbours.
pub(crate) fn mean_curvature(mesh: &TriMesh) -> Vec<f64> {
    let n = mesh.n_vertices();
    let weights = cotangent_weights(&mesh.vertices, &mesh.faces);
    let area = vertex_areas(&mesh.vertices, &mesh.faces);
    let boundary = is_boundary_vertex(mesh);
    let mut lap = vec![[0.0f64; 3]; n];
    for (&(i, j), &w) in weights.edges.iter().zip(&weights.weights) {
        let d = sub(mesh.vertices[j as usize], mesh.vertices[i as usize]);
        for k in 0..3 {
            lap[i as usize][k] += w * d[k];
            lap[j as usize][k] -= w * d[k];
        }
    }
    let mut h: Vec<f64> = (0..n).map(|v| if area[v] > 0.0 && !boundary[v] { 0.5 * norm(lap[v]) / area[v] } else { f64::NAN }).collect();
    // Boundary vertices: the mean of their finite neighbours (twice, for corners).
    for _ in 0..2 {
        let mut sum = vec![(0.0f64, 0u32); n];
        for &(i, j) in &weights.edges {
            for (a, b) in [(i, j), (j, i)] {
                if h[a as usize].is_nan() && h[b as usize].is_finite() {
                    sum[a as usize].0 += h[b as usize];
                    sum[a as usize].1 += 1;
                }
            }
        }
        for v in 0..n {
            if h[v].is_nan() && sum[v].1 > 0 {
                h[v] = sum[v].0 / sum[v].1 as f64;
            }
        }
    }
    h.iter().map(|&x| if x.is_finite() { x } else { 0.0 }).collect()
}

/// Each vertex's root-mean-square principal curvature `sqrt((k1^2 + k2^2) / 2) =
/// sqrt(2 H^2 - K)`: the mean curvature `H` of [`mean_curvature`], the Gaussian curvature `K`
/// by the angle defect over the barycentric area (0 on the boundary).
pub(crate) fn rms_curvature(mesh: &TriMesh) -> Vec<f64> {
    let h = mean_curvature(mesh);
    let area = vertex_areas(&mesh.vertices, &mesh.faces);
    let boundary = is_boundary_vertex(mesh);
    let angle = angle_sums(&mesh.vertices, &mesh.faces);
    (0..mesh.n_vertices())
        .map(|v| {
            let gauss = if boundary[v] || !(area[v] > 0.0) { 0.0 } else { (2.0 * std::f64::consts::PI - angle[v]) / area[v] };
            (2.0 * h[v] * h[v] - gauss).max(0.0).sqrt()
        })
        .collect()
}

/// The relative vertex density of `sizing` at each input vertex (mean 1 over the surface's
/// area), for a remesh of `faces` faces; `None` (uniform) but for [`Sizing::Curvature`].
pub(crate) fn vertex_density(mesh: &TriMesh, sizing: Sizing, faces: usize) -> Option<Vec<f64>> {
    let Sizing::Curvature { strength } = sizing else { return None };
    let n = mesh.n_vertices();
    let area = vertex_areas(&mesh.vertices, &mesh.faces);
    let total: f64 = area.iter().sum();
    let neighbours = vertex_neighbors(mesh);
    if !(total > 0.0) || faces == 0 {
        return None;
    }
    // The uniform remesh's edge length (equilateral faces), and the input's mean edge.
    let remesh_edge = (4.0 * total / faces as f64 / 3f64.sqrt()).sqrt();
    let input_edge = (4.0 * total / mesh.n_faces().max(1) as f64 / 3f64.sqrt()).sqrt();
    // One-ring averaging spreads over about sqrt(passes) input edges: smooth to the remesh's.
    let passes = ((remesh_edge / input_edge).powi(2).ceil() as usize).clamp(1, MAX_SMOOTHING_PASSES);
    // Curvature above 1 / (MIN_RADIUS L) is noise or a degenerate face at the remesh's
    // scale (zero-area faces give unbounded cotangents).
    let k_max = 1.0 / (MIN_RADIUS * remesh_edge);
    let mut k: Vec<f64> = rms_curvature(mesh).into_iter().map(|x| x.min(k_max)).collect();
    for _ in 0..passes {
        k = (0..n)
            .map(|v| {
                let ring = &neighbours[v];
                if ring.is_empty() {
                    return k[v];
                }
                let mean = ring.iter().map(|&u| k[u as usize]).sum::<f64>() / ring.len() as f64;
                0.5 * (k[v] + mean)
            })
            .collect();
    }
    let mut rho: Vec<f64> = k.iter().map(|&x| 1.0 + strength * x * remesh_edge).collect();
    let mean = rho.iter().zip(&area).map(|(r, a)| r * a).sum::<f64>() / total;
    for r in rho.iter_mut() {
        *r /= mean;
    }
    Some(rho)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes::icosphere;

    /// At the centre of the saddle `z = (x^2 - y^2) / 2` the principal curvatures are 1 and
    /// -1: the mean curvature vanishes, the root-mean-square curvature is 1.
    #[test]
    fn a_saddle_is_curved_though_its_mean_curvature_vanishes() {
        let (k, h) = (20usize, 0.01);
        let mut vertices = Vec::new();
        for j in 0..=k {
            for i in 0..=k {
                let (x, y) = ((i as f64 - k as f64 / 2.0) * h, (j as f64 - k as f64 / 2.0) * h);
                vertices.push([x, y, 0.5 * (x * x - y * y)]);
            }
        }
        let at = |i: usize, j: usize| (j * (k + 1) + i) as u32;
        let mut faces = Vec::new();
        for j in 0..k {
            for i in 0..k {
                faces.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                faces.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        let mesh = TriMesh { vertices, faces };
        let centre = at(k / 2, k / 2) as usize;
        let (mean, rms) = (mean_curvature(&mesh)[centre], rms_curvature(&mesh)[centre]);
        assert!(mean < 0.01, "mean curvature {mean}");
        assert!((rms - 1.0).abs() < 0.02, "rms curvature {rms}");
    }

    /// On a sphere of radius R the mean curvature is 1/R everywhere (to discretisation error),
    /// so the curvature density is uniform (to 1% after smoothing).
    #[test]
    fn a_sphere_has_curvature_one_over_its_radius_and_uniform_density() {
        let mut mesh = icosphere(4);
        for p in mesh.vertices.iter_mut() {
            *p = p.map(|c| 3.0 * c);
        }
        let h = mean_curvature(&mesh);
        // Barycentric areas are off at the twelve valence-5 vertices (up to 15% there).
        for &x in &h {
            assert!((x - 1.0 / 3.0).abs() < 0.15 / 3.0, "{x}");
        }
        let mean = h.iter().sum::<f64>() / h.len() as f64;
        assert!((mean - 1.0 / 3.0).abs() < 0.005 / 3.0, "{mean}");
        // Umbilic: the root-mean-square curvature is the mean curvature.
        let rms = rms_curvature(&mesh);
        let mean_rms = rms.iter().sum::<f64>() / rms.len() as f64;
        assert!((mean_rms - 1.0 / 3.0).abs() < 0.02 / 3.0, "{mean_rms}");
        let rho = vertex_density(&mesh, Sizing::Curvature { strength: 2.0 }, 500).unwrap();
        for &r in &rho {
            assert!((r - 1.0).abs() < 0.01, "{r}");
        }
        assert!(vertex_density(&mesh, Sizing::Uniform, 500).is_none());
        assert!(vertex_density(&mesh, Sizing::Surface, 500).is_none());
    }

    #[test]
    fn sizing_parses_and_prints() {
        assert_eq!("uniform".parse::<Sizing>().unwrap(), Sizing::Uniform);
        assert_eq!("surface".parse::<Sizing>().unwrap(), Sizing::Surface);
        assert_eq!("curvature".parse::<Sizing>().unwrap(), Sizing::Curvature { strength: DEFAULT_CURVATURE_STRENGTH });
        assert_eq!("curvature=2.5".parse::<Sizing>().unwrap(), Sizing::Curvature { strength: 2.5 });
        for bad in ["curvature=0", "curvature=-1", "curvature=nan", "curv", "surface=1", ""] {
            assert!(bad.parse::<Sizing>().unwrap_err().contains("curvature=S"), "{bad}");
        }
        assert_eq!(Sizing::Curvature { strength: 2.5 }.to_string(), "curvature=2.5");
        assert_eq!(Sizing::Surface.to_string(), "surface");
        assert!(Sizing::Surface.by_covered() && !Sizing::Uniform.by_covered());
    }
}
