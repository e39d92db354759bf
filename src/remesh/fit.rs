//! Least-squares vertex placement (ours, beyond the paper's Sec. 4.2): each remesh vertex moved
//! along its normal so that the flat faces follow the input surface in the mean, instead of
//! touching it at the vertices only.
//!
//! A remesh whose vertices lie on a curved surface has faces that are chords of it: on a convex
//! patch every face lies inside, up to its sagitta `~ kappa h^2 / 8` at the centre. Moving each
//! vertex by `t_i` along its normal `n_i` and minimising the squared distance, measured along
//! each face's normal `n_f`, between the face and the surface points the inverse map gives for
//! points of the face,
//!
//! `sum_f sum_s w_s ( (p_s - sum_j b_sj x_j) . n_f - sum_j b_sj (n_j . n_f) t_j )^2 + mu sum_i A_i t_i^2`
//! (plus the area term below)
//!
//! puts the faces across the surface rather than inside it: in one dimension the mean
//! distance of a parabola's chord, `h^2 / 6` of the curvature, falls to `h^2 / 16`. The
//! samples `s` of a face are points of its planar triangle in the map's plane (the map gives
//! each remesh vertex's planar point), lifted by [`InverseMap::locate_plane`]: the surface
//! patch the face stands for, with no closest-point search. The normal equations are a
//! mass-matrix-like SPD system, solved by Jacobi-preconditioned conjugate gradients.
//!
//! Moving along the normals changes the faces' areas where the curvature changes (a crest
//! out, the fold beside it in): a second term, `AREA_WEIGHT` times the squared area changes of
//! the faces (linear in the offsets) less their mean relative change, makes uneven changes dear
//! and a uniform one (a sphere's) free; the area equalization then runs again towards each
//! face's area before the fit, each vertex moving in the plane and carrying its offset. The
//! vertices of faces that cross another face once fitted, where the remesh before the fit had
//! fewer crossing faces, or whose smallest angle fell below 15 degrees, go back where they were.
//! A remesh sized by covered areas is fitted without the area term and the equalization
//! ([`FitInput::keep_areas`]): its chord areas are not what it equalizes. docs/method.md
//! section 22.

use crate::cap::InverseMap;
use crate::linalg::jacobi_cg2;
use super::locate::LastFaces;
use crate::mesh::geometry::{add, cross, dot, face_areas, norm, sub};
use crate::mesh::TriMesh;
use crate::metrics::angles::face_angle_range;
use crate::metrics::self_intersection::self_intersecting_faces;
use crate::refine::area_refine::{refine_towards, RefineOptions};
use rayon::prelude::*;

/// Barycentric coordinates of the samples of a face: the centroid, the three points halfway
/// between it and the corners' side, and the three edge midpoints (the face's chord error is
/// close to a quadratic, which the midpoints and the centroid see).
const SAMPLES: [[f64; 3]; 7] = [
    [1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0],
    [2.0 / 3.0, 1.0 / 6.0, 1.0 / 6.0],
    [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0],
    [1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0],
    [0.5, 0.5, 0.0],
    [0.0, 0.5, 0.5],
    [0.5, 0.0, 0.5],
];

/// Weight `mu` of the offsets' own size (relative to the data term's diagonal, which is about
/// half the vertex's area): keeps a vertex whose faces give no sample (next to a closed
/// surface's merged bottom vertex) in place, and shrinks the others by about 2%.
const SHRINK: f64 = 0.01;

/// Largest distance between a face's point and its sample's surface point, relative to the
/// face's longest edge, for the sample to count: a lifted point farther away stands for another
/// part of the surface (a face whose planar triangle spans a fold of the map).
const FAR: f64 = 0.5;

/// Relative residual of the conjugate gradients, and their most iterations.
const TOLERANCE: f64 = 1e-8;
const MAX_ITERATIONS: usize = 200;

/// Weight of the faces' area changes against the distances (both per unit area; the area
/// change of a face, less the mean relative change, counted as if spread over an equilateral
/// face's edge): the offsets that only move the faces across the surface are cheap, those that
/// would change areas unevenly (a crest out, the fold next to it in) dear. With 0 the area
/// equalization after the fit had to move the vertices far in the plane on the brains (mean
/// smallest angle 48.4 -> 47.0 on the 12k brain); with 1 it stays above 48 and the
/// distances keep most of their fall (left ventricle at 5000 faces: 1.47e-4 with 0, 1.57e-4
/// with 1, 1.92e-4 with 10 of the diagonal).
const AREA_WEIGHT: f64 = 2.309_401_076_758_503;

/// Largest offset, relative to the vertex's mean edge (an equilateral ring of its area).
const MAX_OFFSET: f64 = 0.3;

/// Rounds of putting the vertices of faces that cross, or became thin, after the fit back
/// where they were (then all of them).
const UNCROSS_ROUNDS: usize = 3;

/// A face whose smallest angle the fit takes below this (degrees, the bar of issue 26) and
/// below its own before the fit has its vertices put back.
const THIN_DEG: f64 = 15.0;
/// What the least-squares vertex placement did ([`Placement::Fitted`](super::Placement::Fitted); docs/method.md section 22).
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct FitReport {
    /// Whether the vertices were moved (false: on the input surface, [`Placement::OnSurface`](super::Placement::OnSurface)).
    pub fitted: bool,
    /// Samples lifted and used (seven per face but next to a vertex without a planar point).
    pub samples: usize,
    /// Root mean square of the samples' distances along their faces' normals, on the surface
    /// (area-weighted; absolute units).
    pub rms_before: f64,
    /// The same once fitted and equalized, sampled again (the fit's own measure; the report's
    /// `quality` measures closest-point distances).
    pub rms_after: f64,
    /// The largest offset, relative to the mean edge length.
    pub max_offset_relative: f64,
    /// Conjugate-gradient iterations.
    pub iterations: usize,
    /// Vertices put back where they were before the fit because their faces crossed others or
    /// became thin once fitted (all of them when that was not enough).
    pub put_back: usize,
}

/// A remesh to fit: its faces, which vertices have a point of the map's plane, which stay
/// where they are (the rim, the bottom), and the sweeps of the area equalization after the
/// fit (0: none), which keeps each face's area on the surface before the fit.
pub(crate) struct FitInput<'a> {
    pub faces: &'a [[u32; 3]],
    pub has_plane: &'a [bool],
    pub fixed: &'a [bool],
    pub sweeps: usize,
    /// Whether the faces' chord areas are kept (the area term and the sweeps): not for a
    /// remesh sized by covered areas, whose chord areas are not what it equalizes
    /// (docs/method.md section 22, "Sized remeshes").
    pub keep_areas: bool,
}

/// Per face sampled: its unit normal, each sample's weight (area / samples) and signed
/// distance along the normal from the face to the surface (None: not lifted, or too far).
type FaceSamples = Option<([f64; 3], f64, [Option<f64>; 7])>;

/// Sample every face of the remesh (see [`SAMPLES`]) against the surface of `inverse`.
fn sample_faces(inverse: &InverseMap, positions: &[[f64; 3]], planar: &[[f64; 2]], input: &FitInput) -> Vec<FaceSamples> {
    input
        .faces
        .par_iter()
        .map(|f| {
            if f.iter().any(|&v| !input.has_plane[v as usize]) {
                return None;
            }
            let [a, b, c] = f.map(|v| positions[v as usize]);
            let m = cross(sub(b, a), sub(c, a));
            let double_area = norm(m);
            if !(double_area > 0.0) {
                return None;
            }
            let unit = m.map(|x| x / double_area);
            let longest = [sub(b, a), sub(c, b), sub(a, c)].iter().map(|&e| norm(e)).fold(0.0, f64::max);
            let q = f.map(|v| planar[v as usize]);
            let mut hint = None;
            let distances = SAMPLES.map(|w| {
                let at = [0, 1].map(|k| w[0] * q[0][k] + w[1] * q[1][k] + w[2] * q[2][k]);
                let (point, face) = inverse.locate_plane_near(at, hint)?;
                hint = Some(face);
                let on_face: [f64; 3] = std::array::from_fn(|k| w[0] * a[k] + w[1] * b[k] + w[2] * c[k]);
                let d = sub(point.position, on_face);
                (norm(d) <= FAR * longest).then(|| dot(d, unit))
            });
            Some((unit, double_area / 2.0 / SAMPLES.len() as f64, distances))
        })
        .collect()
}

/// Area-weighted root mean square of the sampled distances, and how many samples.
fn rms(sampled: &[FaceSamples]) -> (f64, usize) {
    let (mut sum, mut weights, mut count) = (0.0, 0.0, 0);
    for (_, w, d) in sampled.iter().flatten() {
        for d in d.iter().flatten() {
            sum += w * d * d;
            weights += w;
            count += 1;
        }
    }
    (if weights > 0.0 { (sum / weights).sqrt() } else { 0.0 }, count)
}

/// Unit area-weighted vertex normals, each vertex's area (a third of its faces'), and the
/// mean edge length.
fn normals_and_areas(positions: &[[f64; 3]], faces: &[[u32; 3]]) -> (Vec<[f64; 3]>, Vec<f64>, f64) {
    let mut normals = vec![[0.0; 3]; positions.len()];
    let mut area = vec![0.0; positions.len()];
    let mut edges = 0.0;
    for f in faces {
        let [a, b, c] = f.map(|v| positions[v as usize]);
        let m = cross(sub(b, a), sub(c, a));
        for &v in f {
            for k in 0..3 {
                normals[v as usize][k] += m[k];
            }
            area[v as usize] += norm(m) / 6.0;
        }
        edges += norm(sub(b, a)) + norm(sub(c, b)) + norm(sub(a, c));
    }
    for m in &mut normals {
        let l = norm(*m);
        if l > 0.0 {
            *m = m.map(|x| x / l);
        }
    }
    (normals, area, edges / (3 * faces.len().max(1)) as f64)
}

/// The offsets along `normals` that minimise the sampled distances (module docs), and the
/// conjugate gradients' iterations.
fn solve_offsets(positions: &[[f64; 3]], faces: &[[u32; 3]], sampled: &[FaceSamples], normals: &[[f64; 3]], vertex_area: &[f64], area_weight: f64) -> (Vec<f64>, usize) {
    let n = normals.len();
    let shrink: Vec<f64> = vertex_area.iter().map(|a| SHRINK * a).collect();
    let mut diagonal = shrink.clone();
    let mut rhs = vec![[0.0; 2]; n];
    // Per face the 3 x 3 block sum_s w b_j b_k c_j c_k, c_j = n_j . n_f.
    let mut blocks: Vec<(usize, [[f64; 3]; 3])> = Vec::with_capacity(faces.len());
    let mut uniform = vec![0.0; n];
    let mut area_square_sum = 0.0;
    for (t, entry) in sampled.iter().enumerate() {
        let Some((unit, weight, distances)) = entry else { continue };
        let f = faces[t];
        let c = f.map(|v| dot(normals[v as usize], *unit));
        let mut block = [[0.0; 3]; 3];
        for (w, d) in SAMPLES.iter().zip(distances) {
            let Some(d) = *d else { continue };
            for j in 0..3 {
                rhs[f[j] as usize][0] += weight * w[j] * c[j] * d;
                for k in 0..3 {
                    block[j][k] += weight * w[j] * w[k] * c[j] * c[k];
                }
            }
        }
        // The area term: the face's area change, linear in the offsets (gradient of the area
        // with respect to corner j: half the normal crossed with the opposite edge).
        if area_weight > 0.0 {
            let g: [f64; 3] = std::array::from_fn(|j| {
                let e = sub(positions[f[(j + 2) % 3] as usize], positions[f[(j + 1) % 3] as usize]);
                0.5 * dot(cross(*unit, e), normals[f[j] as usize])
            });
            let area = 0.5 * norm(cross(sub(positions[f[1] as usize], positions[f[0] as usize]), sub(positions[f[2] as usize], positions[f[0] as usize])));
            area_square_sum += area * area;
            for j in 0..3 {
                uniform[f[j] as usize] += area * g[j];
                for k in 0..3 {
                    block[j][k] += area_weight * g[j] * g[k];
                }
            }
        }
        for j in 0..3 {
            diagonal[f[j] as usize] += block[j][j];
        }
        blocks.push((t, block));
    }
    let apply = |x: &[[f64; 2]], y: &mut [[f64; 2]]| {
        for (i, yi) in y.iter_mut().enumerate() {
            *yi = [shrink[i] * x[i][0], 0.0];
        }
        for (t, block) in &blocks {
            let f = faces[*t];
            for j in 0..3 {
                y[f[j] as usize][0] += (0..3).map(|k| block[j][k] * x[f[k] as usize][0]).sum::<f64>();
            }
        }
        if area_square_sum > 0.0 {
            let along: f64 = uniform.iter().zip(x).map(|(a, x)| a * x[0]).sum::<f64>() * area_weight / area_square_sum;
            for (yi, a) in y.iter_mut().zip(&uniform) {
                yi[0] -= along * a;
            }
        }
    };
    // The second column is unused (zero right-hand side: solved at once).
    let mut offsets = vec![[0.0; 2]; n];
    let outcome = jacobi_cg2(apply, &diagonal, &rhs, &mut offsets, TOLERANCE, MAX_ITERATIONS);
    (offsets.into_iter().map(|o| o[0]).collect(), outcome.iterations)
}

/// Move the vertices of the remesh (`positions` on the surface of `inverse`, `planar` their
/// points of the map's plane) along their normals to fit the surface in the least-squares
/// sense of the module docs, equalize the areas again with the offsets carried, and put back
/// onto the surface the vertices of faces that cross once fitted. `planar` and `positions` are
/// updated; the surface points of the vertices are returned in `on_surface`.
pub(crate) fn fit_to_surface(inverse: &InverseMap, input: &FitInput, planar: &mut [[f64; 2]], positions: &mut [[f64; 3]], on_surface: &mut Vec<[f64; 3]>) -> FitReport {
    let faces = input.faces;
    let target = face_areas(positions, faces);
    let sampled = sample_faces(inverse, positions, planar, input);
    let (rms_before, _) = rms(&sampled);
    let (normals, vertex_area, mean_edge) = normals_and_areas(positions, faces);
    let area_weight = if input.keep_areas { AREA_WEIGHT } else { 0.0 };
    let (mut offsets, iterations) = solve_offsets(positions, faces, &sampled, &normals, &vertex_area, area_weight);
    for (o, a) in offsets.iter_mut().zip(&vertex_area) {
        let edge = (4.0 * a / 3f64.sqrt()).sqrt();
        *o = o.clamp(-MAX_OFFSET * edge, MAX_OFFSET * edge);
    }
    let offset_of = |v: usize| normals[v].map(|x| x * offsets[v]);
    // The equalization moves a vertex in the plane and puts it at the surface point plus its
    // offset; each vertex's lifts start from its last face.
    let last_face = LastFaces::new(planar.len());
    let surface_point = |v: usize, q: [f64; 2]| -> Option<[f64; 3]> {
        let (p, face) = inverse.locate_plane_near(q, last_face.get(v))?;
        last_face.set(v, face);
        Some(p.position)
    };
    let lift = |v: usize, q: [f64; 2]| -> [f64; 3] { surface_point(v, q).map_or([f64::NAN; 3], |p| add(p, offset_of(v))) };
    let before_planar = planar.to_vec();
    let stays: Vec<bool> = (0..planar.len()).map(|v| input.fixed[v] || !input.has_plane[v]).collect();
    let mut fitted: Vec<[f64; 3]> = positions.iter().enumerate().map(|(v, &p)| if stays[v] { p } else { add(p, offset_of(v)) }).collect();
    if input.keep_areas && input.sweeps > 0 {
        refine_towards(planar, &mut fitted, &target, faces, &stays, &lift, RefineOptions::plain(input.sweeps));
    }
    // The vertices' surface points after the equalization (the stayed ones where they were).
    *on_surface = (0..planar.len()).into_par_iter().map(|v| if stays[v] { positions[v] } else { surface_point(v, planar[v]).unwrap_or(positions[v]) }).collect();
    // Faces that cross once fitted where the remesh before the fit had fewer, and faces whose
    // smallest angle the fit took below THIN_DEG: the vertices of those faces go back to where
    // they were, and all of them if that is not enough.
    let crossing_before = self_intersecting_faces(&TriMesh::new(positions.to_vec(), faces.to_vec())).len();
    let smallest = |x: &[[f64; 3]]| -> Vec<f64> { faces.par_iter().map(|f| face_angle_range(x[f[0] as usize], x[f[1] as usize], x[f[2] as usize]).0).collect() };
    let smallest_before = smallest(positions);
    let mut back = vec![false; planar.len()];
    for round in 0..=UNCROSS_ROUNDS {
        let crossing = self_intersecting_faces(&TriMesh::new(fitted.clone(), faces.to_vec()));
        let crossing: Vec<u32> = if crossing.len() > crossing_before { crossing } else { Vec::new() };
        let thin = smallest(&fitted).iter().zip(&smallest_before).enumerate().filter(|(_, (&a, &b))| a < THIN_DEG && a < b).map(|(t, _)| t as u32).collect::<Vec<u32>>();
        if crossing.is_empty() && thin.is_empty() {
            break;
        }
        let all = round == UNCROSS_ROUNDS;
        let vertices: Vec<usize> = if all { (0..planar.len()).collect() } else { crossing.iter().chain(&thin).flat_map(|&t| faces[t as usize]).map(|v| v as usize).collect() };
        for v in vertices {
            back[v] = true;
            fitted[v] = positions[v];
            on_surface[v] = positions[v];
            planar[v] = before_planar[v];
        }
        if all {
            break;
        }
    }
    positions.copy_from_slice(&fitted);
    let (rms_after, samples) = rms(&sample_faces(inverse, positions, planar, input));
    let largest = offsets.iter().enumerate().filter(|&(v, _)| !stays[v] && !back[v]).map(|(_, o)| o.abs()).fold(0.0, f64::max);
    FitReport {
        fitted: true,
        samples,
        rms_before,
        rms_after,
        max_offset_relative: if mean_edge > 0.0 { largest / mean_edge } else { 0.0 },
        iterations,
        put_back: back.iter().filter(|&&b| b).count(),
    }
}
