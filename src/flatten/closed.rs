//! Initial flattening of a closed genus-0 surface (paper Sec. 3.2.1): puncture the most
//! regular quadrilateral at the bottom, map the rest onto the unit disk with its four corners
//! on the circle by stretch energy minimisation, then rebuild the map with Beltrami coefficient
//! `lambda * mu` (quasi-conformal composition). `lambda = 0` gives the conformal map with those
//! corners (angles kept, strong area compression); `lambda = 1` keeps the equiareal stretch
//! energy map. The paper's default is `lambda = 0.2`.

use super::beltrami::{beltrami_coefficients, linear_beltrami_solver_with};
use super::harmonic::{count_flipped, harmonic_extension_with};
use super::puncture::{choose_puncture, Puncture, PunctureOptions};
use super::stretch_energy::{stretch_energy_map_with, StretchOptions, StretchReport};
use super::{pin, FlattenError};
use crate::linalg::{cotangent_weights, SpdSolver};
use crate::mesh::geometry::{norm, sub};
use crate::mesh::topology::edge_faces;
use crate::mesh::{MeshError, TriMesh};
use std::f64::consts::PI;

/// The paper's balancing factor between the stretch-energy map and the conformal map.
pub const DEFAULT_LAMBDA: f64 = 0.2;

/// Options of the closed-surface flattening. Build them from [`ClosedFlattenOptions::default`]
/// with the `with_*` setters: new options may be added without notice.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct ClosedFlattenOptions {
    /// Quasi-conformal composition factor in `[0, 1]`. Default [`DEFAULT_LAMBDA`] (0.2).
    pub lambda: f64,
    /// Puncture options. Default [`PunctureOptions::default`].
    pub puncture: PunctureOptions,
    /// Stretch energy options. Default [`StretchOptions::default`].
    pub stretch: StretchOptions,
    /// Solve the two coordinates' right-hand sides of the large systems on separate threads
    /// ([`SpdSolver::set_parallel_columns`]). Default `true`; [`crate::param::PunctureEnd::Best`]
    /// sets it to `false` while both ends flatten at once.
    pub parallel_solves: bool,
}

impl Default for ClosedFlattenOptions {
    fn default() -> Self {
        Self { lambda: DEFAULT_LAMBDA, puncture: PunctureOptions::default(), stretch: StretchOptions::default(), parallel_solves: true }
    }
}

impl ClosedFlattenOptions {
    /// Set [`ClosedFlattenOptions::lambda`] (in `[0, 1]`).
    pub fn with_lambda(mut self, lambda: f64) -> Self {
        self.lambda = lambda;
        self
    }

    /// Set [`ClosedFlattenOptions::puncture`].
    pub fn with_puncture(mut self, puncture: PunctureOptions) -> Self {
        self.puncture = puncture;
        self
    }

    /// Set [`ClosedFlattenOptions::stretch`].
    pub fn with_stretch(mut self, stretch: StretchOptions) -> Self {
        self.stretch = stretch;
        self
    }

    /// Set [`ClosedFlattenOptions::parallel_solves`].
    pub fn with_parallel_solves(mut self, parallel_solves: bool) -> Self {
        self.parallel_solves = parallel_solves;
        self
    }
}

/// A punctured closed surface flattened onto the unit disk.
#[derive(Debug, Clone)]
pub struct ClosedFlattening {
    /// The punctured quadrilateral.
    pub puncture: Puncture,
    /// The faces left after the puncture (a topological disk), in input order.
    pub faces: Vec<[u32; 3]>,
    /// Planar positions of every vertex; the quad's corners lie on the unit circle.
    pub uv: Vec<[f64; 2]>,
    /// What was done.
    pub report: ClosedFlattenReport,
}

/// What the closed-surface flattening did.
#[derive(Debug, Clone, serde::Serialize)]
pub struct ClosedFlattenReport {
    /// Stretch energy minimisation.
    pub stretch: StretchReport,
    /// Composition factor used.
    pub lambda: f64,
    /// Folded faces in the composed map.
    pub flipped_faces: usize,
}

/// Flatten a closed genus-0 `mesh` (outward or inward oriented: faces are used as given, the
/// planar map is positively oriented either way).
pub fn flatten_closed(mesh: &TriMesh, options: &ClosedFlattenOptions) -> Result<ClosedFlattening, FlattenError> {
    if !(0.0..=1.0).contains(&options.lambda) {
        return Err(FlattenError::LambdaOutOfRange { lambda: options.lambda });
    }
    let edges: Vec<(u32, u32, usize, usize)> = edge_faces(mesh)
        .map_err(|e: MeshError| FlattenError::Mesh(e.to_string()))?
        .into_iter()
        .filter_map(|e| Some((e.a, e.b, e.left? as usize, e.right? as usize)))
        .collect();
    let puncture = choose_puncture(&mesh.vertices, &mesh.faces, &edges, &options.puncture).ok_or(FlattenError::NoPuncture)?;
    let faces: Vec<[u32; 3]> = mesh
        .faces
        .iter()
        .enumerate()
        .filter(|(i, _)| *i != puncture.faces[0] && *i != puncture.faces[1])
        .map(|(_, f)| *f)
        .collect();
    // Quad corners on the unit circle by arc length.
    let fixed = on_circle_by_arc_length(&mesh.vertices, &puncture.quad);
    let (uv, report) = stretch_then_beltrami(&mesh.vertices, &faces, &fixed, options)?;
    Ok(ClosedFlattening { puncture, faces, uv, report })
}

/// The composite initial map of an open disk: stretch energy minimisation onto the unit disk
/// with the boundary placed by arc length, then the quasi-conformal composition with
/// `lambda * mu`, boundary held. This is the closed-surface recipe of the paper (Sec. 3.2.1)
/// applied to an open surface; it avoids the exponential compression of conformal maps on
/// elongated or branching surfaces (a strip of aspect ratio `a` is squeezed by about
/// `exp(pi a)` at its ends).
pub fn composite_disk_map(
    vertices: &[[f64; 3]],
    faces: &[[u32; 3]],
    boundary: &[u32],
    options: &ClosedFlattenOptions,
) -> Result<(Vec<[f64; 2]>, ClosedFlattenReport), FlattenError> {
    if !(0.0..=1.0).contains(&options.lambda) {
        return Err(FlattenError::LambdaOutOfRange { lambda: options.lambda });
    }
    let m = boundary.len();
    if m < 3 {
        return Err(FlattenError::BoundaryTooShort { len: m });
    }
    let fixed = on_circle_by_arc_length(vertices, boundary);
    stretch_then_beltrami(vertices, faces, &fixed, options)
}

/// The recipe both [`flatten_closed`] and [`composite_disk_map`] follow once the `fixed`
/// vertices are placed: harmonic initial map, stretch energy minimisation, then the linear
/// Beltrami solve with `lambda * mu`. The three systems have the same free vertices and
/// edges, so they share one symbolic factorization.
fn stretch_then_beltrami(
    vertices: &[[f64; 3]],
    faces: &[[u32; 3]],
    fixed: &[(u32, [f64; 2])],
    options: &ClosedFlattenOptions,
) -> Result<(Vec<[f64; 2]>, ClosedFlattenReport), FlattenError> {
    let weights = cotangent_weights(vertices, faces);
    let mut solver = SpdSolver::new();
    solver.set_parallel_columns(options.parallel_solves);
    let (initial, _) = harmonic_extension_with(vertices.len(), faces, &weights, fixed, &mut solver)?;
    // The later systems share the harmonic map's pattern: when many factorizations will use
    // it and AMD filled more than a planar dissection usually does, order them by nested
    // dissection on the map if that fills less.
    if options.stretch.planned_factorizations() + 1 >= DISSECTION_OFFER_FACTORIZATIONS {
        let mut positions = initial.clone();
        let (is_fixed, _, n_free) = pin(&mut positions, fixed);
        let n = n_free as f64;
        if solver.factor_entries().is_some_and(|e| e as f64 > DISSECTION_FILL * n * n.max(2.0).log2()) {
            let free: Vec<[f64; 2]> = positions.into_iter().zip(&is_fixed).filter(|(_, &f)| !f).map(|(p, _)| p).collect();
            solver.offer_positions(&free, "stretch energy")?;
        }
    }
    let (sem, stretch) = stretch_energy_map_with(vertices, faces, fixed, &initial, &options.stretch, &mut solver)?;
    let mu: Vec<[f64; 2]> = beltrami_coefficients(vertices, faces, &sem)
        .into_iter()
        .map(|m| scaled_coefficient(m, options.lambda))
        .collect();
    let uv = linear_beltrami_solver_with(vertices, faces, &mu, fixed, &mut solver)?;
    let flipped_faces = count_flipped(&uv, faces);
    Ok((uv, ClosedFlattenReport { stretch, lambda: options.lambda, flipped_faces }))
}

/// Factorizations of the flattening's shared pattern (stretch-energy iterations that factor,
/// and the Beltrami solve) from which the harmonic map's nested dissection is offered
/// ([`SpdSolver::offer_positions`]): its analysis pays only over many factorizations. With
/// every stretch iteration factoring (`factored_iterations = usize::MAX`: 11) the 164k
/// ellipsoid's offer was kept and paid; the default closed schedule factors every other
/// iteration ([`super::stretch_energy::StretchOptions::refactor_period`]: 5 planned, 6 with
/// the Beltrami solve), below this, where the offer gained nothing. Open surfaces factor 3
/// ([`crate::param::OpenOptions::factored_iterations`]), and on the hand, the 101k and the
/// 1M disk AMD had the smaller factor anyway.
const DISSECTION_OFFER_FACTORIZATIONS: usize = 8;

/// The offer is made only when AMD's factor has more than this many entries per
/// `n log2 n` unknowns: the dissection's factor had 4.5-4.9 on every mesh measured, AMD's
/// 3.1 to 5.65 (the 164k ellipsoid, numbered by icosphere subdivision). Below it the
/// dissection's analysis (two of them at once for [`crate::param::PunctureEnd::Best`]) only
/// costs time.
const DISSECTION_FILL: f64 = 4.5;

/// `lambda * mu`, pulled back inside the unit disk where the stretch energy map folded a face
/// (`|mu| >= 1`), so the Beltrami system stays elliptic.
fn scaled_coefficient(mu: [f64; 2], lambda: f64) -> [f64; 2] {
    let m = [lambda * mu[0], lambda * mu[1]];
    let norm = (m[0] * m[0] + m[1] * m[1]).sqrt();
    if norm < MAX_MU {
        m
    } else {
        [m[0] * MAX_MU / norm, m[1] * MAX_MU / norm]
    }
}

/// Largest `|mu|` handed to the Beltrami solver.
const MAX_MU: f64 = 0.95;

/// The vertices of a closed loop placed on the unit circle at angles proportional to the
/// loop's arc length.
pub fn on_circle_by_arc_length(vertices: &[[f64; 3]], boundary: &[u32]) -> Vec<(u32, [f64; 2])> {
    let m = boundary.len();
    let sides: Vec<f64> = (0..m).map(|k| norm(sub(vertices[boundary[(k + 1) % m] as usize], vertices[boundary[k] as usize]))).collect();
    let total: f64 = sides.iter().sum();
    let mut acc = 0.0;
    let mut fixed = Vec::with_capacity(m);
    for k in 0..m {
        let t = if total > 0.0 { 2.0 * PI * acc / total } else { 2.0 * PI * k as f64 / m as f64 };
        fixed.push((boundary[k], [t.cos(), t.sin()]));
        acc += sides[k];
    }
    fixed
}
