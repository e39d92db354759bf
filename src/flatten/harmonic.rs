//! Harmonic extension with Dirichlet boundary values: solve `L_II x_I = -L_IB x_B` for both
//! coordinates with the cotangent Laplacian.
//!
//! Cotangent weights can be negative on obtuse meshes, and then the harmonic map may fold. The
//! extension is therefore first tried with the exact weights; if any face comes out flipped,
//! it is redone with the weights clamped to a small positive floor, a Tutte embedding with
//! near-conformal weights, which is bijective onto the convex disk (Tutte 1963, Floater 2003).

use super::FlattenError;
use crate::linalg::{CotanWeights, SpdSolver};
use crate::mesh::geometry::folded_faces;

/// Which weights the harmonic extension ended up using.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub enum HarmonicWeights {
    /// Exact cotangent weights.
    Cotangent,
    /// Cotangent weights clamped to a positive floor (the exact ones folded the map).
    ClampedCotangent,
}

/// Number of faces with non-positive signed area in the planar map `uv`.
pub fn count_flipped(uv: &[[f64; 2]], faces: &[[u32; 3]]) -> usize {
    folded_faces(uv, faces).len()
}

/// Extend the boundary positions `fixed` (vertex, position) harmonically to all vertices.
pub fn harmonic_extension(
    n_vertices: usize,
    faces: &[[u32; 3]],
    weights: &CotanWeights,
    fixed: &[(u32, [f64; 2])],
) -> Result<(Vec<[f64; 2]>, HarmonicWeights), FlattenError> {
    harmonic_extension_with(n_vertices, faces, weights, fixed, &mut SpdSolver::new())
}

/// [`harmonic_extension`] with `solver`, whose symbolic factorization the later systems on
/// the same free vertices (stretch energy, Beltrami) reuse.
pub(crate) fn harmonic_extension_with(
    n_vertices: usize,
    faces: &[[u32; 3]],
    weights: &CotanWeights,
    fixed: &[(u32, [f64; 2])],
    solver: &mut SpdSolver,
) -> Result<(Vec<[f64; 2]>, HarmonicWeights), FlattenError> {
    let uv = solve(n_vertices, weights, fixed, |w| w, solver)?;
    if count_flipped(&uv, faces) == 0 {
        return Ok((uv, HarmonicWeights::Cotangent));
    }
    let mean = weights.weights.iter().map(|w| w.abs()).sum::<f64>() / weights.weights.len().max(1) as f64;
    let floor = 1e-3 * mean;
    let uv = solve(n_vertices, weights, fixed, |w| w.max(floor), solver)?;
    Ok((uv, HarmonicWeights::ClampedCotangent))
}

fn solve(
    n_vertices: usize,
    weights: &CotanWeights,
    fixed: &[(u32, [f64; 2])],
    map: impl Fn(f64) -> f64 + Copy,
    solver: &mut SpdSolver,
) -> Result<Vec<[f64; 2]>, FlattenError> {
    let mut uv = vec![[0.0; 2]; n_vertices];
    let mut is_fixed = vec![false; n_vertices];
    for &(v, p) in fixed {
        uv[v as usize] = p;
        is_fixed[v as usize] = true;
    }
    let mut index = vec![None; n_vertices];
    let mut n_free = 0;
    for v in 0..n_vertices {
        if !is_fixed[v] {
            index[v] = Some(n_free);
            n_free += 1;
        }
    }
    if n_free == 0 {
        return Ok(uv);
    }
    let lap = weights.restricted_laplacian(&index, n_free, map).assemble("harmonic map")?;
    let mut rhs = vec![vec![0.0; n_free], vec![0.0; n_free]];
    for (&(i, j), &w) in weights.edges.iter().zip(&weights.weights) {
        let w = map(w);
        for (a, b) in [(i, j), (j, i)] {
            if let (Some(ia), true) = (index[a as usize], is_fixed[b as usize]) {
                rhs[0][ia] += w * uv[b as usize][0];
                rhs[1][ia] += w * uv[b as usize][1];
            }
        }
    }
    solver.factor(&lap, "harmonic map")?;
    solver.solve_in_place(&mut rhs, "harmonic map")?;
    for v in 0..n_vertices {
        if let Some(i) = index[v] {
            uv[v] = [rhs[0][i], rhs[1][i]];
        }
    }
    Ok(uv)
}
