//! The triangle mesh type shared by every stage.

/// An indexed triangle mesh: vertex positions and faces as vertex-index triples.
///
/// Faces are counter-clockwise seen from outside (for closed surfaces) or from the side the
/// normal points to. Nothing here is checked: see [`crate::mesh::validate()`] for that.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TriMesh {
    /// Vertex positions.
    pub vertices: Vec<[f64; 3]>,
    /// Faces as indices into `vertices`.
    pub faces: Vec<[u32; 3]>,
}

impl TriMesh {
    /// A mesh from positions and faces (no checks).
    pub fn new(vertices: Vec<[f64; 3]>, faces: Vec<[u32; 3]>) -> Self {
        Self { vertices, faces }
    }

    /// Number of vertices.
    pub fn n_vertices(&self) -> usize {
        self.vertices.len()
    }

    /// Number of faces.
    pub fn n_faces(&self) -> usize {
        self.faces.len()
    }

    /// The three corner positions of face `f`.
    pub fn face_points(&self, f: usize) -> [[f64; 3]; 3] {
        let [a, b, c] = self.faces[f];
        [
            self.vertices[a as usize],
            self.vertices[b as usize],
            self.vertices[c as usize],
        ]
    }

    /// Axis-aligned bounding box `(min, max)`; `None` for an empty mesh.
    pub fn bounding_box(&self) -> Option<([f64; 3], [f64; 3])> {
        let first = *self.vertices.first()?;
        let mut lo = first;
        let mut hi = first;
        for p in &self.vertices {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        Some((lo, hi))
    }

    /// Length of the bounding-box diagonal (0 for an empty mesh).
    pub fn bounding_box_diagonal(&self) -> f64 {
        match self.bounding_box() {
            Some((lo, hi)) => crate::mesh::geometry::norm(crate::mesh::geometry::sub(hi, lo)),
            None => 0.0,
        }
    }

    /// Reverse the orientation of every face.
    pub fn flip_orientation(&mut self) {
        for f in &mut self.faces {
            f.swap(1, 2);
        }
    }
}
