//! Puncture of a closed genus-0 surface (paper Sec. 3.2.1, after Giri et al. 2021): align the
//! principal axis with `Z`, then remove the two adjacent triangles near the bottom whose
//! quadrilateral is the most regular, so the rest is a topological disk.
//!
//! Candidates are the interior edges ordered by the distance of their midpoint to the bottom
//! point of the principal axis. A quadrilateral is regular enough when the ratio of its longest
//! to shortest side and of its longer to shorter diagonal are both at most
//! [`PunctureOptions::max_ratio`]; the first such candidate wins, else the most regular of the
//! first [`PunctureOptions::candidates`] (ours:) when that one's worse ratio is at most
//! [`PunctureOptions::acceptable_ratio`], else the first edge farther on, within
//! [`PunctureOptions::reach`] of the axis extent, whose quadrilateral is (or the most regular
//! there). A UV sphere's poles have only slivers around them: punctured at one (ratio 33) the
//! ellipsoid of 30k vertices mapped at mean |d_area| 16.6, whatever `lambda`.

use crate::mesh::geometry::{add, dot, norm, scale, sub, triangle_area};
use nalgebra::{Matrix3, SymmetricEigen, Vector3};

/// QR sweeps allowed to the 3x3 eigenproblem (a few suffice; a bound keeps a pathological
/// matrix from looping).
const MAX_EIGEN_ITERATIONS: usize = 100;

/// Options of the puncture. Build them from [`PunctureOptions::default`] with the `with_*`
/// setters: new options may be added without notice.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct PunctureOptions {
    /// Accept a quadrilateral whose side and diagonal ratios are at most this. Default 1.3.
    pub max_ratio: f64,
    /// How many candidate edges near the bottom to examine. Default 500.
    pub candidates: usize,
    /// When the most regular of the first candidates has a side or diagonal ratio above this,
    /// look farther from the bottom. Default 2.
    pub acceptable_ratio: f64,
    /// How far from the bottom point the farther search goes, in units of the surface's
    /// extent along its principal axis. Default 0.25.
    pub reach: f64,
    /// Puncture at the other end of the principal axis (the input's top). Default `false`.
    pub other_end: bool,
    /// The quadrilaterals to puncture, chosen already, as the edge the two faces share, at
    /// the bottom and at the top (the multilevel parameterization punctures its coarse mesh
    /// where the input was punctured). Default `None`: chosen as above.
    pub(crate) given: Option<[[u32; 2]; 2]>,
}

impl Default for PunctureOptions {
    fn default() -> Self {
        Self { max_ratio: 1.3, candidates: 500, acceptable_ratio: 2.0, reach: 0.25, other_end: false, given: None }
    }
}

impl PunctureOptions {
    /// Set [`PunctureOptions::max_ratio`].
    pub fn with_max_ratio(mut self, max_ratio: f64) -> Self {
        self.max_ratio = max_ratio;
        self
    }

    /// Set [`PunctureOptions::candidates`].
    pub fn with_candidates(mut self, candidates: usize) -> Self {
        self.candidates = candidates;
        self
    }

    /// Set [`PunctureOptions::acceptable_ratio`].
    pub fn with_acceptable_ratio(mut self, acceptable_ratio: f64) -> Self {
        self.acceptable_ratio = acceptable_ratio;
        self
    }

    /// Set [`PunctureOptions::reach`].
    pub fn with_reach(mut self, reach: f64) -> Self {
        self.reach = reach;
        self
    }

    /// Set [`PunctureOptions::other_end`].
    pub fn with_other_end(mut self, other_end: bool) -> Self {
        self.other_end = other_end;
        self
    }
}

/// The punctured quadrilateral.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Puncture {
    /// The two removed faces (indices into the input's faces).
    pub faces: [usize; 2],
    /// The quadrilateral's vertices in the order the punctured surface's boundary runs.
    pub quad: [u32; 4],
    /// Longest over shortest side.
    pub side_ratio: f64,
    /// Longer over shorter diagonal.
    pub diagonal_ratio: f64,
    /// Unit principal axis (the direction called "up").
    pub axis: [f64; 3],
}

/// Area-weighted centroid and principal axis (largest variance) of a surface: the
/// eigenvector of the largest eigenvalue of the vertex-area-weighted covariance, by nalgebra's
/// `SymmetricEigen`. The axis sign is chosen with a non-negative `Z` component (then `Y`,
/// then `X`), so an input already standing along `Z` keeps its bottom at the bottom.
pub fn principal_axis(vertices: &[[f64; 3]], faces: &[[u32; 3]]) -> ([f64; 3], [f64; 3]) {
    let mut total = 0.0;
    let mut c = Vector3::zeros();
    let mut m2 = Matrix3::zeros();
    for f in faces {
        let p = f.map(|v| vertices[v as usize]);
        let a = triangle_area(p[0], p[1], p[2]);
        total += a;
        for q in p.map(Vector3::from) {
            let w = q * (a / 3.0);
            c += w;
            m2 += w * q.transpose();
        }
    }
    if total <= 0.0 {
        return ([0.0; 3], [0.0, 0.0, 1.0]);
    }
    c *= 1.0 / total;
    let cov = m2 / total - c * c.transpose();
    let mut axis = dominant_eigenvector(cov);
    let sign = if axis[2] != 0.0 { axis[2] } else if axis[1] != 0.0 { axis[1] } else { axis[0] };
    if sign < 0.0 {
        axis = -axis;
    }
    (c.into(), axis.into())
}

/// Unit eigenvector of the largest eigenvalue of the symmetric `cov`; `Z` for a matrix that
/// is not finite or does not converge (`SymmetricEigen::new` would loop or panic).
fn dominant_eigenvector(cov: Matrix3<f64>) -> Vector3<f64> {
    if !cov.iter().all(|x| x.is_finite()) {
        return Vector3::z();
    }
    let Some(eigen) = SymmetricEigen::try_new(cov, f64::EPSILON, MAX_EIGEN_ITERATIONS) else {
        return Vector3::z();
    };
    let e = eigen.eigenvectors.column(eigen.eigenvalues.imax()).into_owned();
    let n = e.norm();
    if n > 0.0 { e / n } else { Vector3::z() }
}

/// Choose the quadrilateral to puncture. `edges` lists interior edges `(a, b, f0, f1)` where
/// `f0` has the edge as `a -> b`. Returns `None` for a mesh without interior edges.
pub fn choose_puncture(
    vertices: &[[f64; 3]],
    faces: &[[u32; 3]],
    edges: &[(u32, u32, usize, usize)],
    options: &PunctureOptions,
) -> Option<Puncture> {
    let (c, axis) = principal_axis(vertices, faces);
    let axis = if options.other_end { scale(axis, -1.0) } else { axis };
    if let Some(given) = options.given {
        let [a, b] = given[options.other_end as usize];
        let edge = edges.iter().find(|e| (e.0 == a && e.1 == b) || (e.0 == b && e.1 == a))?;
        return quadrilateral(vertices, faces, *edge, axis).map(|(_, p)| p);
    }
    let heights = vertices.iter().map(|p| dot(sub(*p, c), axis));
    let (lowest, highest) = heights.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), h| (lo.min(h), hi.max(h)));
    let bottom = add(c, scale(axis, lowest));
    let mut order: Vec<(f64, usize)> = edges
        .iter()
        .enumerate()
        .map(|(i, &(a, b, _, _))| {
            let mid = scale(add(vertices[a as usize], vertices[b as usize]), 0.5);
            (norm(sub(mid, bottom)), i)
        })
        .collect();
    let k = options.candidates.min(order.len());
    if k == 0 {
        return None;
    }
    order.select_nth_unstable_by(k - 1, |x, y| x.0.total_cmp(&y.0));
    let (near, far) = order.split_at_mut(k);
    near.sort_by(|x, y| x.0.total_cmp(&y.0));
    let quad_at = |i: usize| quadrilateral(vertices, faces, edges[i], axis);
    let mut best: Option<(f64, Puncture)> = None;
    if let Some(p) = first_within(near.iter().map(|&(_, i)| quad_at(i)), options.max_ratio, &mut best) {
        return Some(p);
    }
    if best.as_ref().is_some_and(|(s, _)| *s <= options.acceptable_ratio) {
        return best.map(|(_, p)| p);
    }
    // Only poor quadrilaterals near the bottom: look farther, nearest first.
    let reach = options.reach * (highest - lowest);
    let mut farther: Vec<(f64, usize)> = far.iter().copied().filter(|&(d, _)| d <= reach).collect();
    farther.sort_by(|x, y| x.0.total_cmp(&y.0));
    if let Some(p) = first_within(farther.into_iter().map(|(_, i)| quad_at(i)), options.acceptable_ratio, &mut best) {
        return Some(p);
    }
    best.map(|(_, p)| p)
}

/// The first of the scored `candidates` whose score is at most `accept`; on the way, `best`
/// keeps the lowest-scoring one seen (the earlier one on ties).
fn first_within(candidates: impl Iterator<Item = Option<(f64, Puncture)>>, accept: f64, best: &mut Option<(f64, Puncture)>) -> Option<Puncture> {
    for (score, cand) in candidates.flatten() {
        if score <= accept {
            return Some(cand);
        }
        if !best.as_ref().is_some_and(|(s, _)| *s <= score) {
            *best = Some((score, cand));
        }
    }
    None
}

/// The quadrilateral of the two faces at the interior edge `(a, b, f0, f1)` and its score,
/// the worse of its side and diagonal ratios; `None` when it has a zero side or diagonal.
fn quadrilateral(vertices: &[[f64; 3]], faces: &[[u32; 3]], (a, b, f0, f1): (u32, u32, usize, usize), axis: [f64; 3]) -> Option<(f64, Puncture)> {
    let c0 = third(faces[f0], a, b)?;
    let c1 = third(faces[f1], a, b)?;
    // f0 = (a, b, c0) in cyclic order; f1 = (b, a, c1). The punctured surface's boundary
    // runs opposite to the removed faces' outer edges: a -> c0 -> b -> c1.
    let quad = [a, c0, b, c1];
    let p = quad.map(|v| vertices[v as usize]);
    let sides: Vec<f64> = (0..4).map(|k| norm(sub(p[(k + 1) % 4], p[k]))).collect();
    let smin = sides.iter().cloned().fold(f64::INFINITY, f64::min);
    let smax = sides.iter().cloned().fold(0.0, f64::max);
    let d1 = norm(sub(p[0], p[2]));
    let d2 = norm(sub(p[1], p[3]));
    if !(smin > 0.0 && d1.min(d2) > 0.0) {
        return None;
    }
    let side_ratio = smax / smin;
    let diagonal_ratio = d1.max(d2) / d1.min(d2);
    Some((side_ratio.max(diagonal_ratio), Puncture { faces: [f0, f1], quad, side_ratio, diagonal_ratio, axis }))
}

fn third(f: [u32; 3], a: u32, b: u32) -> Option<u32> {
    f.into_iter().find(|&v| v != a && v != b)
}
