//! [`InverseMap`]: the inverse `f^-1` of a [`CapMap`] as an object (paper Sec. 4.2): where on
//! the input surface a point of the cap lies, and, the other way, which cap point a surface
//! point (a face and barycentric coordinates) maps to.
//!
//! The map is piecewise linear in the stereographic plane: a cap point goes to the plane
//! ([`stereographic`]), is located among the planar images of the input's faces (the
//! remesh's [`Locator`], built once here) and takes the barycentric combination of the face's
//! corners. A closed surface's punctured quad maps to the cap's flat bottom disk `Z = Z*`;
//! bottom points are located in the `(X, Y)` plane after the radial scaling of the disk onto
//! the quad's polygon that the remesh's pull-back uses. The planar disk domain (`Disk`) is its
//! own plane. Points off the cap (off the sphere, below `Z*`, outside the bottom disk) are
//! `None`, never guessed; points on the cap between the rim circle and the polygon inscribed
//! in it go to the nearest point of the surface's boundary.

use std::borrow::Cow;

use super::stereographic::{inverse_stereographic, stereographic};
use super::CapMap;
use crate::mesh::TriMesh;
use crate::remesh::locate::Locator;
use crate::remesh::pullback::{onto_polygon, polygon_by_angle, polygon_radius, surrounds_origin};
use rayon::prelude::*;

/// Why an [`InverseMap`] could not be built or a surface point could not be mapped.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InverseMapError {
    /// The map was computed for a mesh with another vertex count.
    #[error("the map has {map} vertices but the mesh has {mesh}: pass the mesh the map was computed from")]
    VertexCount {
        /// Vertices of the map.
        map: usize,
        /// Vertices of the mesh.
        mesh: usize,
    },
    /// The mesh has no face outside the punctured quad.
    #[error("the mesh has no face to locate points in")]
    NoFaces,
    /// A face index beyond the mesh's faces.
    #[error("face {face} does not exist: the mesh has {faces} faces")]
    FaceOutOfRange {
        /// The face asked for.
        face: usize,
        /// Faces of the mesh.
        faces: usize,
    },
    /// Barycentric coordinates that are not finite, negative or do not sum to 1.
    #[error("barycentric coordinates {0:?} are not a point of the face: they must be finite, >= 0 and sum to 1")]
    Barycentric([f64; 3]),
}

/// Options of [`CapMap::inverse_with`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct InverseOptions {
    /// How far (in the cap's units: the unit sphere) a point may lie off the cap and still be
    /// located. Default `1e-9`.
    pub tolerance: f64,
}

impl Default for InverseOptions {
    fn default() -> Self {
        Self { tolerance: 1e-9 }
    }
}

impl InverseOptions {
    /// Set [`InverseOptions::tolerance`].
    pub fn with_tolerance(mut self, tolerance: f64) -> Self {
        self.tolerance = tolerance;
        self
    }
}

/// A point of the input surface: a face, the barycentric coordinates of the face's corners
/// (in the order of `mesh.faces[face]`) and the position they give.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    /// Input face index.
    pub face: usize,
    /// Weights of the face's three corners (non-negative, sum 1).
    pub barycentric: [f64; 3],
    /// The point on the surface.
    pub position: [f64; 3],
}

/// The flat bottom of a closed surface's cap: the punctured quad's faces in the `(X, Y)` plane.
struct Bottom<'a> {
    locator: Locator<'a>,
    faces: Vec<usize>,
    corners: Vec<[f64; 2]>,
    rim_radius: f64,
}

/// The inverse of a [`CapMap`] with its point location built: see the module documentation.
/// It borrows the map and the mesh ([`CapMap::inverse`]) or owns them
/// ([`CapMap::into_inverse`], an `InverseMap<'static>` for handles such as the C ABI's).
pub struct InverseMap<'a> {
    mesh: Cow<'a, TriMesh>,
    map: Cow<'a, CapMap>,
    /// Over the faces not in the punctured quad, numbered as `top_faces`.
    top: Locator<'a>,
    top_faces: Vec<usize>,
    bottom: Option<Bottom<'a>>,
    /// `Z*` of a spherical cap, `None` for the planar disk.
    z_star: Option<f64>,
    /// Radius of the planar disk domain (the farthest planar point).
    disk_radius: f64,
    tolerance: f64,
}

impl CapMap {
    /// The inverse map on `mesh` (the mesh this map was computed from), with default
    /// [`InverseOptions`].
    pub fn inverse<'a>(&'a self, mesh: &'a TriMesh) -> Result<InverseMap<'a>, InverseMapError> {
        self.inverse_with(mesh, InverseOptions::default())
    }

    /// [`CapMap::inverse`] with options.
    pub fn inverse_with<'a>(&'a self, mesh: &'a TriMesh, options: InverseOptions) -> Result<InverseMap<'a>, InverseMapError> {
        InverseMap::build(Cow::Borrowed(mesh), Cow::Borrowed(self), options)
    }

    /// [`CapMap::inverse_with`] owning the map and the mesh: an inverse map that outlives
    /// them (the point location keeps its own copy of the planar positions).
    pub fn into_inverse(self, mesh: TriMesh, options: InverseOptions) -> Result<InverseMap<'static>, InverseMapError> {
        InverseMap::build(Cow::Owned(mesh), Cow::Owned(self), options)
    }
}

impl<'a> InverseMap<'a> {
    fn build(mesh: Cow<'a, TriMesh>, map: Cow<'a, CapMap>, options: InverseOptions) -> Result<Self, InverseMapError> {
        if map.plane.len() != mesh.n_vertices() || map.cap.len() != mesh.n_vertices() {
            return Err(InverseMapError::VertexCount { map: map.plane.len(), mesh: mesh.n_vertices() });
        }
        let mut is_bottom = vec![false; mesh.n_faces()];
        for &f in &map.bottom_faces {
            if let Some(b) = is_bottom.get_mut(f) {
                *b = true;
            }
        }
        let top_faces: Vec<usize> = (0..mesh.n_faces()).filter(|&f| !is_bottom[f]).collect();
        if top_faces.is_empty() {
            return Err(InverseMapError::NoFaces);
        }
        // A borrowed map lends its planar positions to the locator; an owned one is moved into
        // the InverseMap, so the locator keeps a copy.
        let plane: Cow<'a, [[f64; 2]]> = match &map {
            Cow::Borrowed(m) => Cow::Borrowed(&m.plane[..]),
            Cow::Owned(m) => Cow::Owned(m.plane.clone()),
        };
        let top = Locator::new(plane, top_faces.iter().map(|&f| mesh.faces[f]).collect::<Vec<_>>());
        let bottom_list: Vec<usize> = (0..mesh.n_faces()).filter(|&f| is_bottom[f]).collect();
        let bottom = (!bottom_list.is_empty()).then(|| {
            let flat: Vec<[f64; 2]> = map.cap.iter().map(|p| [p[0], p[1]]).collect();
            let faces: Vec<[u32; 3]> = bottom_list.iter().map(|&f| mesh.faces[f]).collect();
            let (corners, rim_radius) = polygon_by_angle(faces.iter().flatten().map(|&v| flat[v as usize]).collect());
            Bottom { locator: Locator::new(flat, faces), faces: bottom_list, corners, rim_radius }
        });
        let disk_radius = map.plane.iter().map(|p| p[0].hypot(p[1])).fold(0.0, f64::max);
        let z_star = map.report.z_star;
        Ok(InverseMap { mesh, map, top, top_faces, bottom, z_star, disk_radius, tolerance: options.tolerance })
    }

    /// The surface point of the cap point `x`, or `None` when `x` is off the cap (beyond
    /// [`InverseOptions::tolerance`]) or not finite.
    pub fn locate(&self, x: [f64; 3]) -> Option<SurfacePoint> {
        if !x.iter().all(|c| c.is_finite()) {
            return None;
        }
        let tol = self.tolerance;
        let Some(z_star) = self.z_star else {
            // The planar disk: its own plane.
            let r = x[0].hypot(x[1]);
            return (x[2].abs() <= tol && r <= self.disk_radius + tol).then(|| self.locate_plane([x[0], x[1]])).flatten();
        };
        let norm = (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
        if (norm - 1.0).abs() <= tol && x[2] >= z_star - tol {
            return self.locate_plane(stereographic(x));
        }
        let bottom = self.bottom.as_ref()?;
        let rim = (1.0 - z_star * z_star).max(0.0).sqrt();
        if (x[2] - z_star).abs() <= tol && x[0].hypot(x[1]) <= rim + tol {
            let q = onto_polygon([x[0], x[1]], &bottom.corners, bottom.rim_radius);
            let loc = bottom.locator.locate(q)?;
            return Some(self.point(bottom.faces[loc.face], loc.bary));
        }
        None
    }

    /// [`InverseMap::locate`] of many points, in parallel.
    pub fn locate_all(&self, points: &[[f64; 3]]) -> Vec<Option<SurfacePoint>> {
        points.par_iter().map(|&x| self.locate(x)).collect()
    }

    /// The surface point of a point of the map's plane (the disk of radius `r*` whose
    /// inverse stereographic image is the cap), among the faces outside the punctured quad;
    /// a point outside the planar image goes to the nearest point of its boundary. `None`
    /// only for a non-finite point.
    pub fn locate_plane(&self, q: [f64; 2]) -> Option<SurfacePoint> {
        self.locate_plane_near(q, None).map(|(p, _)| p)
    }

    /// [`InverseMap::locate_plane`] trying first the face `hint` (an index of the faces
    /// outside the punctured quad, as returned): the answer does not depend on it (see
    /// [`Locator::locate_near`]). Returns the point and that index.
    pub(crate) fn locate_plane_near(&self, q: [f64; 2], hint: Option<usize>) -> Option<(SurfacePoint, usize)> {
        let loc = self.top.locate_near(q, hint)?;
        Some((self.point(self.top_faces[loc.face], loc.bary), loc.face))
    }

    /// The cap point of the surface point on face `face` with barycentric coordinates
    /// `barycentric` (the forward map `f`): the combination in the plane lifted to the sphere,
    /// on the flat bottom for the punctured quad's faces, in the disk for the planar domain.
    pub fn cap_point(&self, face: usize, barycentric: [f64; 3]) -> Result<[f64; 3], InverseMapError> {
        let faces = self.mesh.n_faces();
        let corners = *self.mesh.faces.get(face).ok_or(InverseMapError::FaceOutOfRange { face, faces })?;
        let w = barycentric;
        if !w.iter().all(|b| b.is_finite() && *b >= -1e-12) || (w.iter().sum::<f64>() - 1.0).abs() > 1e-9 {
            return Err(InverseMapError::Barycentric(w));
        }
        let combine = |p: &dyn Fn(usize) -> [f64; 2]| {
            let [a, b, c] = corners.map(|v| p(v as usize));
            [0, 1].map(|k| w[0] * a[k] + w[1] * b[k] + w[2] * c[k])
        };
        if let (Some(bottom), Some(z_star)) = (self.bottom.as_ref(), self.z_star) {
            if bottom.faces.binary_search(&face).is_ok() {
                let q = combine(&|v| [self.map.cap[v][0], self.map.cap[v][1]]);
                let q = from_polygon(q, &bottom.corners, bottom.rim_radius);
                return Ok([q[0], q[1], z_star]);
            }
        }
        let q = combine(&|v| self.map.plane[v]);
        Ok(match self.z_star {
            Some(_) => inverse_stereographic(q),
            None => [q[0], q[1], 0.0],
        })
    }

    /// The surface (the mesh this map inverts).
    pub fn mesh(&self) -> &TriMesh {
        &self.mesh
    }

    /// The map this inverts.
    pub fn map(&self) -> &CapMap {
        &self.map
    }

    /// The faces outside the punctured quad (all faces of an open surface), in the numbering
    /// of `InverseMap::locate_plane_near`'s face indices.
    pub fn top_faces(&self) -> &[usize] {
        &self.top_faces
    }

    fn point(&self, face: usize, bary: [f64; 3]) -> SurfacePoint {
        let [a, b, c] = self.mesh.faces[face].map(|v| self.mesh.vertices[v as usize]);
        let w = bary;
        SurfacePoint { face, barycentric: bary, position: [0, 1, 2].map(|k| w[0] * a[k] + w[1] * b[k] + w[2] * c[k]) }
    }
}

/// The inverse of [`onto_polygon`]: a point of the polygon `corners` back to the disk of
/// radius `rim_radius` (the polygon's sides to the rim, the centre kept).
fn from_polygon(p: [f64; 2], corners: &[[f64; 2]], rim_radius: f64) -> [f64; 2] {
    let len = p[0].hypot(p[1]);
    if len == 0.0 || rim_radius <= 0.0 || !surrounds_origin(corners) {
        return p;
    }
    match polygon_radius([p[0] / len, p[1] / len], corners) {
        Some(t) if t > 0.0 => {
            let scale = rim_radius / t;
            [p[0] * scale, p[1] * scale]
        }
        _ => p,
    }
}
