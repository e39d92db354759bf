//! The cotangent Laplacian (Pinkall and Polthier 1993) as a list of edge weights.
//!
//! For an interior edge `ij` with opposite angles `alpha`, `beta` the weight is
//! `(cot alpha + cot beta) / 2`; a boundary edge has one term. The matrix `L` with
//! `L_ij = -w_ij`, `L_ii = sum_j w_ij` is positive semi-definite for any mesh: it is the P1
//! finite-element stiffness matrix.

use crate::linalg::TripletList;
use crate::mesh::geometry::{cross, dot, norm, sub};

/// Cotangent weights on the undirected edges of a mesh.
#[derive(Debug, Clone, Default)]
pub struct CotanWeights {
    /// Edges `(i, j)` with `i < j`, sorted.
    pub edges: Vec<(u32, u32)>,
    /// The weight of each edge.
    pub weights: Vec<f64>,
}

/// Cotangent of the angle between `u` and `v`, bounded to `[-1e8, 1e8]` for degenerate
/// corners.
#[inline]
pub fn cot(u: [f64; 3], v: [f64; 3]) -> f64 {
    let c = norm(cross(u, v));
    let d = dot(u, v);
    if c <= 1e-8 * d.abs() {
        return 1e8 * d.signum();
    }
    d / c
}

/// Cotangent weights of every edge of the mesh `(vertices, faces)`.
pub fn cotangent_weights(vertices: &[[f64; 3]], faces: &[[u32; 3]]) -> CotanWeights {
    let mut half: Vec<(u64, f64)> = Vec::with_capacity(3 * faces.len());
    for f in faces {
        for k in 0..3 {
            let o = f[k] as usize;
            let (i, j) = (f[(k + 1) % 3], f[(k + 2) % 3]);
            let c = cot(sub(vertices[i as usize], vertices[o]), sub(vertices[j as usize], vertices[o]));
            let (a, b) = if i < j { (i, j) } else { (j, i) };
            half.push((((a as u64) << 32) | b as u64, 0.5 * c));
        }
    }
    half.sort_unstable_by_key(|h| h.0);
    let mut out = CotanWeights::default();
    for (key, w) in half {
        let e = ((key >> 32) as u32, key as u32);
        if out.edges.last() == Some(&e) {
            *out.weights.last_mut().expect("weights parallel to edges") += w;
        } else {
            out.edges.push(e);
            out.weights.push(w);
        }
    }
    out
}

impl CotanWeights {
    /// The Laplacian `L` restricted to the rows and columns where `index[v]` is `Some`, with
    /// `index` giving the compact position. Entries to excluded vertices are dropped.
    pub fn restricted_laplacian(&self, index: &[Option<usize>], dim: usize, weight: impl Fn(f64) -> f64) -> TripletList {
        let mut t = TripletList::with_capacity(dim, 4 * self.edges.len() + dim);
        let mut diag = vec![0.0; dim];
        for (&(i, j), &w) in self.edges.iter().zip(&self.weights) {
            let w = weight(w);
            let (a, b) = (index[i as usize], index[j as usize]);
            if let Some(a) = a {
                diag[a] += w;
            }
            if let Some(b) = b {
                diag[b] += w;
            }
            if let (Some(a), Some(b)) = (a, b) {
                t.push(a, b, -w);
                t.push(b, a, -w);
            }
        }
        for (a, d) in diag.into_iter().enumerate() {
            t.push(a, a, d);
        }
        t
    }
}
