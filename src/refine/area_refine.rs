//! Face-level area refinement of the final map (ours; the paper stops at the centroid map).
//!
//! The transport map is exact in vertex masses (paper Sec. 2.2, Eq. 11) but a vertex mass is
//! shared by several faces: on a coarse or irregular mesh the per-face area distortion of the
//! centroid map stays at a few tenths, and the fold repair adds to it. This step lowers the
//! paper's per-face measure itself (Sec. 4, `d_area(T) = log` of the normalised area ratio)
//! by nonlinear Gauss-Seidel (vertices in colour classes that share no face, each class in
//! parallel): each free vertex takes a damped Gauss-Newton step on
//! `sum_{T at v} d_area(T)^2`, with areas measured on the domain (cap or disk), accepted only
//! when every incident face stays positively oriented in the plane and the local sum falls.
//! A fold-free map therefore stays fold-free, and the boundary (fixed vertices) never moves.
//! The parameterization over-relaxes the steps (nonlinear SOR, [`RefineOptions`]), and
//! vertices whose neighbourhood has stopped moving are left still (an active set,
//! [`RefineOptions::active_move`]).

use super::area_local::{ClassOrder, LocalProblem, Step};
use crate::mesh::geometry::{signed_area_2d, triangle_area};
use rayon::prelude::*;

/// What the refinement did.
#[derive(Debug, Clone, Copy, Default, serde::Serialize)]
pub struct AreaRefineReport {
    /// Sweeps made.
    pub sweeps: usize,
    /// Vertex steps taken over all sweeps (at most sweeps times the free vertices; fewer when
    /// vertices were left still, see [`RefineOptions::active_move`]).
    pub vertex_steps: usize,
    /// Mean `|d_area|` before and after.
    pub mean_abs_before: f64,
    /// See `mean_abs_before`.
    pub mean_abs_after: f64,
}

/// Sweeps of the parameterization's refinement by default.
pub const DEFAULT_SWEEPS: usize = 30;

/// How many sweeps, and how far each step goes. Build them from [`RefineOptions::default`] with
/// the `with_*` setters: new options may be added without notice.
#[derive(Debug, Clone, Copy)]
#[non_exhaustive]
pub struct RefineOptions {
    /// Sweeps at most. Default [`DEFAULT_SWEEPS`].
    pub sweeps: usize,
    /// The first trial of each vertex's line search is `omega` times the Gauss-Newton step
    /// (then halved until the local sum falls). Default 1.3: 30 sweeps at 1.3 reach about what 50
    /// plain sweeps do on the shared meshes; at 1.5 the MEG helmet's angles degrade. 1 is plain
    /// Gauss-Seidel.
    pub over_relaxation: f64,
    /// A vertex is stepped in a sweep only when its own last step, or the last step of a
    /// vertex it shares a face with, moved by at least this fraction of that vertex's
    /// shortest planar edge: its local problem has not changed beyond that since it last
    /// moved (every vertex is stepped in the first sweep). Default [`ACTIVE_MOVE`]; 0 steps
    /// every vertex in every sweep.
    pub active_move: f64,
}

impl Default for RefineOptions {
    fn default() -> Self {
        Self { sweeps: DEFAULT_SWEEPS, over_relaxation: 1.3, active_move: ACTIVE_MOVE }
    }
}

impl RefineOptions {
    /// Set [`RefineOptions::sweeps`].
    pub fn with_sweeps(mut self, sweeps: usize) -> Self {
        self.sweeps = sweeps;
        self
    }

    /// Set [`RefineOptions::over_relaxation`] (1: plain Gauss-Seidel).
    pub fn with_over_relaxation(mut self, over_relaxation: f64) -> Self {
        self.over_relaxation = over_relaxation;
        self
    }

    /// Set [`RefineOptions::active_move`] (0: step every vertex in every sweep).
    pub fn with_active_move(mut self, active_move: f64) -> Self {
        self.active_move = active_move;
        self
    }

    /// `sweeps` of plain (not over-relaxed) Gauss-Seidel.
    pub fn plain(sweeps: usize) -> Self {
        Self { sweeps, over_relaxation: 1.0, ..Default::default() }
    }
}

/// Default of [`RefineOptions::active_move`]: a step of `1e-4` of the shortest edge changes
/// the areas of the vertex's faces by about `2e-4` of themselves, a few percent of the
/// smallest mean `|d_area|` the maps reach (0.005 on the synthetic ellipsoids). On large,
/// nearly equiareal maps most vertices stop moving after a few sweeps and are skipped (the
/// 100k ellipsoid: a fifth of the vertex steps, the same mean `|d_area|` to 0.2%); maps
/// further from equiareal keep nearly every vertex moving. Larger thresholds left the large
/// maps measurably less equiareal.
pub const ACTIVE_MOVE: f64 = 1e-4;

/// Stop when a sweep lowers `sum d_area^2` by less than this fraction.
const TOLERANCE: f64 = 1e-4;

/// Do nothing (or stop) once the mean `|d_area|` is below this: a 0.1% mean area error is
/// below anything a remesh or a shape measure can show, and the sweeps converge slowly
/// (50 more sweeps take the synthetic 100k disk only from 0.00055 to 0.00053).
pub const GOOD_ENOUGH: f64 = 1e-3;

/// Refine the planar positions `plane` of the surface `(vertices, faces)` for
/// `options.sweeps` sweeps at most; `lift` maps a planar point to the domain where areas are
/// measured.
pub fn refine_areas(
    plane: &mut [[f64; 2]],
    vertices: &[[f64; 3]],
    faces: &[[u32; 3]],
    fixed: &[bool],
    lift: &(dyn Fn([f64; 2]) -> [f64; 3] + Sync),
    options: RefineOptions,
) -> AreaRefineReport {
    let source: Vec<f64> = faces.iter().map(|f| triangle_area(vertices[f[0] as usize], vertices[f[1] as usize], vertices[f[2] as usize])).collect();
    let mut lifted: Vec<[f64; 3]> = plane.iter().map(|&p| lift(p)).collect();
    refine_towards(plane, &mut lifted, &source, faces, fixed, &|_, p| lift(p), options)
}

/// The lift of [`refine_towards`]: `lift(v, p)` is the domain point of the planar point `p`,
/// asked while vertex `v` moves (its finite differences and trial steps), so that a lift by
/// point location can start from where `v`'s last point was (the remesh's equalization);
/// the answer must not depend on `v`.
pub type VertexLift<'a> = dyn Fn(usize, [f64; 2]) -> [f64; 3] + Sync + 'a;

/// The refinement itself: move the free vertices of `plane` so that the areas of the lifted
/// faces (`lifted[v] = lift(v, plane[v])`, kept up to date; fixed vertices may carry any
/// position) become proportional to `target` areas. Planar faces keep the orientation of
/// the majority (positive or negative) they start with.
pub fn refine_towards(
    plane: &mut [[f64; 2]],
    lifted: &mut [[f64; 3]],
    target: &[f64],
    faces: &[[u32; 3]],
    fixed: &[bool],
    lift: &VertexLift,
    options: RefineOptions,
) -> AreaRefineReport {
    let n = plane.len();
    let source = target;
    let source_total: f64 = source.iter().sum();
    // The orientation the moving faces keep: that of most faces with a free vertex. Faces of
    // fixed vertices only do not count: the flat bottom of a closed surface's cap mesh
    // projects onto the same planar disk as the cap, reversed, and an area sum over all faces
    // came out with the wrong sign on some meshes (12k brain remesh: no vertex could move).
    let free_signs = faces
        .iter()
        .filter(|f| f.iter().any(|&v| !fixed[v as usize]))
        .map(|f| signed_area_2d(plane[f[0] as usize], plane[f[1] as usize], plane[f[2] as usize]).signum())
        .sum::<f64>();
    let orientation = if free_signs < 0.0 { -1.0 } else { 1.0 };
    let image_area = |lifted: &[[f64; 3]], f: &[u32; 3]| triangle_area(lifted[f[0] as usize], lifted[f[1] as usize], lifted[f[2] as usize]);
    // Total image area, mean |d_area| and sum of d_area^2 of `faces` on `lifted`; each face's
    // area and logarithm once, in parallel (it ran once per sweep on one thread, a fifth of
    // each sweep on the hand), summed in face order so that the stopping test does not
    // depend on the threads' split.
    let measure = |faces: &[[u32; 3]], lifted: &[[f64; 3]]| -> (f64, f64, f64) {
        let areas: Vec<f64> = faces.par_iter().map(|f| image_area(lifted, f)).collect();
        let total: f64 = areas.iter().sum();
        let terms: Vec<(f64, f64)> = areas
            .par_iter()
            .zip(source)
            .map(|(&a, &s)| {
                let d = ((a / total) / (s / source_total)).ln();
                if d.is_finite() { (d.abs(), d * d) } else { (0.0, 0.0) }
            })
            .collect();
        let (sum_abs, sum_sq) = terms.iter().fold((0.0, 0.0), |x, y| (x.0 + y.0, x.1 + y.1));
        (total, sum_abs / faces.len().max(1) as f64, sum_sq)
    };
    let (mut total, before, mut energy) = measure(faces, lifted);
    let mut report = AreaRefineReport { mean_abs_before: before, mean_abs_after: before, sweeps: 0, vertex_steps: 0 };
    if faces.is_empty() || !total.is_finite() || total <= 0.0 || before < GOOD_ENOUGH {
        return report;
    }
    let ln_source: Vec<f64> = source.iter().map(|&s| if s > 0.0 { s.ln() } else { f64::NAN }).collect();
    let classes = ClassOrder::new(n, faces, fixed, &ln_source);
    let (faces, wedges) = (&classes.faces, &classes.wedges);
    // The sweeps work on copies in class order (see [`ClassOrder`]); the lift is asked with
    // the vertices' own numbers.
    let mut class_plane: Vec<[f64; 2]> = classes.order.iter().map(|&v| plane[v]).collect();
    let mut class_lifted: Vec<[f64; 3]> = classes.order.iter().map(|&v| lifted[v]).collect();
    let class_lift = |i: usize, p: [f64; 2]| lift(classes.order[i], p);
    // The last step of each vertex (class positions), in its shortest planar edges.
    let mut moved = vec![0.0f64; n];
    let threshold = options.active_move;
    for sweep in 0..options.sweeps {
        // log of the target share of each face's image area: d = ln(a) - offset[t].
        let offset_total = total.ln() - source_total.ln();
        let local = LocalProblem { offset: offset_total, orientation, lift: &class_lift, over_relaxation: options.over_relaxation };
        // Vertices of one colour share no face, so their steps are independent: each phase
        // computes them in parallel from the current positions, then applies them. This is
        // Gauss-Seidel in colour order. Whether a vertex is stepped reads the moves of
        // other classes only, so it does not depend on the threads' split either.
        for class in &classes.ranges {
            let active = |i: usize| {
                sweep == 0 || moved[i] >= threshold || wedges.at(i).iter().any(|w| moved[w.a as usize] >= threshold || moved[w.b as usize] >= threshold)
            };
            let moves: Vec<(usize, Option<Step>)> = class
                .clone()
                .into_par_iter()
                .map_init(Vec::new, |scratch, i| (i, if active(i) { local.step(i, wedges.at(i), &class_plane, &class_lifted, scratch) } else { None }))
                .collect();
            for (i, step) in moves {
                moved[i] = match step {
                    Some(Step { plane, lifted, relative_move }) => {
                        class_plane[i] = plane;
                        class_lifted[i] = lifted;
                        report.vertex_steps += 1;
                        relative_move
                    }
                    None => 0.0,
                };
            }
        }
        let (t, mean_abs, e) = measure(faces, &class_lifted);
        report.sweeps = sweep + 1;
        let decrease = (energy - e) / energy.max(f64::MIN_POSITIVE);
        total = t;
        energy = e;
        if decrease < TOLERANCE || mean_abs < GOOD_ENOUGH {
            break;
        }
    }
    report.mean_abs_after = measure(faces, &class_lifted).1;
    for (i, &v) in classes.order.iter().enumerate() {
        plane[v] = class_plane[i];
        lifted[v] = class_lifted[i];
    }
    report
}

#[cfg(test)]
mod tests {
    use super::super::area_local::Wedges;
    use super::*;
    use crate::mesh::geometry::dot;
    use crate::cap::{inverse_stereographic, stereographic};
    use crate::mesh::geometry::folded_faces;
    use crate::mesh::shapes::{spherical_cap, spherical_cap_sectors};
    use crate::mesh::topology::is_boundary_vertex;

    /// The cap's stereographic image with each free vertex `v` moved by `amplitude` in the
    /// direction of angle `v * turn` (a deterministic high-frequency jitter).
    fn jittered_plane(cap: &crate::mesh::TriMesh, fixed: &[bool], turn: f64, amplitude: f64) -> Vec<[f64; 2]> {
        let mut plane: Vec<[f64; 2]> = cap.vertices.iter().map(|&p| stereographic(p)).collect();
        for (v, p) in plane.iter_mut().enumerate() {
            if !fixed[v] {
                let t = v as f64 * turn;
                p[0] += amplitude * t.sin();
                p[1] += amplitude * t.cos();
            }
        }
        plane
    }

    #[test]
    fn residual_jacobian_matches_central_differences() {
        let cap = spherical_cap(-0.3, 8, spherical_cap_sectors(-0.3, 8));
        let fixed = is_boundary_vertex(&cap);
        let plane = jittered_plane(&cap, &fixed, 1.7, 0.02);
        let lift = |q: [f64; 2]| inverse_stereographic(q);
        let lifted: Vec<[f64; 3]> = plane.iter().map(|&p| lift(p)).collect();
        let ln_source: Vec<f64> = cap.faces.iter().map(|f| triangle_area(cap.vertices[f[0] as usize], cap.vertices[f[1] as usize], cap.vertices[f[2] as usize]).ln()).collect();
        let vertex_lift = |_: usize, q: [f64; 2]| lift(q);
        let local = LocalProblem { offset: 0.1, orientation: 1.0, lift: &vertex_lift, over_relaxation: 1.0 };
        let wedges = Wedges::new(plane.len(), &cap.faces, &ln_source);
        let mut checked = 0;
        let mut linear = Vec::new();
        let residuals_at = |p: [f64; 2], v: usize| -> Vec<f64> {
            let (mut q, mut l) = (plane.clone(), lifted.clone());
            q[v] = p;
            l[v] = lift(p);
            let mut out = Vec::new();
            local.linearize(v, wedges.at(v), &q, &l, &mut out).expect("oriented");
            out.iter().map(|f| f.residual).collect()
        };
        for v in (0..plane.len()).filter(|&v| !fixed[v]).step_by(7) {
            let incident = wedges.at(v);
            assert_eq!(incident.len(), cap.faces.iter().filter(|f| f.contains(&(v as u32))).count());
            let (energy, shortest) = local.linearize(v, incident, &plane, &lifted, &mut linear).expect("linearize");
            assert!((energy - linear.iter().map(|f| f.residual * f.residual).sum::<f64>()).abs() < 1e-15);
            // The step's planar Jacobian, as `step` forms it.
            let dl = local.lift_jacobian(v, plane[v], lifted[v], 1e-6 * shortest);
            let jac: Vec<[f64; 2]> = linear.iter().map(|f| [dot(f.gradient, dl[0]), dot(f.gradient, dl[1])]).collect();
            let h = 1e-5 * shortest;
            for k in 0..2 {
                let (mut p, mut m) = (plane[v], plane[v]);
                p[k] += h;
                m[k] -= h;
                let (plus, minus) = (residuals_at(p, v), residuals_at(m, v));
                for (j, (a, b)) in plus.iter().zip(&minus).enumerate() {
                    let fd = (a - b) / (2.0 * h);
                    let scale = jac.iter().map(|g| g[0].abs().max(g[1].abs())).fold(0.0, f64::max);
                    assert!((jac[j][k] - fd).abs() < 1e-4 * scale, "vertex {v} face {j} dir {k}: {} vs {fd}", jac[j][k]);
                }
            }
            checked += 1;
        }
        assert!(checked > 10);
    }

    #[test]
    fn over_relaxed_sweeps_lower_the_distortion_faster() {
        // A smooth (low-frequency) area error, the kind the transport leaves on real meshes,
        // where Gauss-Seidel is slow; the boundary circle stays put.
        let cap = spherical_cap(0.2, 24, spherical_cap_sectors(0.2, 24));
        let fixed = is_boundary_vertex(&cap);
        let mut plane: Vec<[f64; 2]> = cap.vertices.iter().map(|&p| stereographic(p)).collect();
        let rim = plane.iter().map(|p| p[0].hypot(p[1])).fold(0.0, f64::max);
        for (v, p) in plane.iter_mut().enumerate() {
            if !fixed[v] {
                let r2 = (p[0] * p[0] + p[1] * p[1]) / (rim * rim);
                let s = 1.0 + 0.3 * (1.0 - r2);
                *p = [p[0] * s, p[1] * s];
            }
        }
        let lift = |q: [f64; 2]| inverse_stereographic(q);
        let run = |options: RefineOptions| {
            let mut q = plane.clone();
            let rep = refine_areas(&mut q, &cap.vertices, &cap.faces, &fixed, &lift, options);
            assert!(folded_faces(&q, &cap.faces).is_empty());
            rep
        };
        let plain = run(RefineOptions::plain(10));
        let over = run(RefineOptions { sweeps: 10, ..Default::default() });
        assert_eq!(plain.mean_abs_before, over.mean_abs_before);
        assert!(over.mean_abs_after < 0.9 * plain.mean_abs_after, "over-relaxed {over:?}, plain {plain:?}");
    }

    #[test]
    fn perturbed_cap_map_is_restored_without_folds_and_boundary_stays() {
        // The cap's own stereographic image is exactly area preserving (d_area = 0);
        // a deterministic perturbation of the interior, then the refinement.
        let cap = spherical_cap(0.2, 12, spherical_cap_sectors(0.2, 12));
        let fixed = is_boundary_vertex(&cap);
        let mut plane = jittered_plane(&cap, &fixed, 2.399, 0.01);
        let before = plane.clone();
        assert!(folded_faces(&plane, &cap.faces).is_empty());
        let lift = |q: [f64; 2]| inverse_stereographic(q);
        let rep = refine_areas(&mut plane, &cap.vertices, &cap.faces, &fixed, &lift, RefineOptions { sweeps: 100, ..Default::default() });
        assert!(rep.mean_abs_before > 0.02, "perturbation too small: {}", rep.mean_abs_before);
        assert!(rep.mean_abs_after < 0.2 * rep.mean_abs_before, "{rep:?}");
        assert!(folded_faces(&plane, &cap.faces).is_empty());
        for v in 0..plane.len() {
            if fixed[v] {
                assert_eq!(plane[v], before[v]);
            }
        }
    }

    /// A perturbation confined to a small patch of the cap: with the default
    /// [`RefineOptions::active_move`] the vertices far from it, which have nothing to do, are
    /// left still after the first sweep, and the map comes out as with every vertex stepped
    /// in every sweep.
    #[test]
    fn still_vertices_are_skipped_without_changing_the_result() {
        let cap = spherical_cap(0.2, 24, spherical_cap_sectors(0.2, 24));
        let fixed = is_boundary_vertex(&cap);
        let mut plane: Vec<[f64; 2]> = cap.vertices.iter().map(|&p| stereographic(p)).collect();
        let centre = plane[cap.faces[cap.faces.len() / 3][0] as usize];
        let rim = plane.iter().map(|p| p[0].hypot(p[1])).fold(0.0, f64::max);
        let mut perturbed = 0;
        for (v, p) in plane.iter_mut().enumerate() {
            let d = (p[0] - centre[0]).hypot(p[1] - centre[1]);
            if !fixed[v] && d < 0.12 * rim {
                let t = v as f64 * 2.399;
                p[0] += 0.01 * rim * t.sin();
                p[1] += 0.01 * rim * t.cos();
                perturbed += 1;
            }
        }
        assert!(folded_faces(&plane, &cap.faces).is_empty());
        let free = fixed.iter().filter(|&&f| !f).count();
        assert!(perturbed > 10 && perturbed < free / 10, "{perturbed} of {free} perturbed");
        let lift = |q: [f64; 2]| inverse_stereographic(q);
        let run = |active_move: f64| {
            let mut q = plane.clone();
            let rep = refine_areas(&mut q, &cap.vertices, &cap.faces, &fixed, &lift, RefineOptions { sweeps: 20, active_move, ..Default::default() });
            assert!(folded_faces(&q, &cap.faces).is_empty());
            (rep, q)
        };
        let (every, every_map) = run(0.0);
        let (active, active_map) = run(ACTIVE_MOVE);
        assert!(every.sweeps >= 5 && every.vertex_steps * 10 > every.sweeps * free * 9, "{every:?}");
        assert!(every.mean_abs_after < 0.5 * every.mean_abs_before, "{every:?}");
        assert!(active.vertex_steps < every.vertex_steps / 2, "{active:?} against {every:?}");
        assert!((active.mean_abs_after - every.mean_abs_after).abs() < 0.05 * every.mean_abs_after, "{active:?} against {every:?}");
        let largest_difference = every_map.iter().zip(&active_map).map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1])).fold(0.0, f64::max);
        assert!(largest_difference < 1e-3 * rim, "{largest_difference}");
    }

    /// The class order is a permutation whose ranges are colour classes (no two vertices of
    /// a range share a face, fixed vertices in none), and each vertex's wedges in it are its
    /// own, renumbered, in the same order.
    #[test]
    fn class_order_keeps_the_classes_and_each_vertex_wedges() {
        let cap = spherical_cap(-0.3, 8, spherical_cap_sectors(-0.3, 8));
        let fixed = is_boundary_vertex(&cap);
        let n = cap.vertices.len();
        let ln_source: Vec<f64> = (0..cap.faces.len()).map(|f| f as f64).collect();
        let classes = ClassOrder::new(n, &cap.faces, &fixed, &ln_source);
        let mut seen = vec![false; n];
        for &v in &classes.order {
            assert!(!std::mem::replace(&mut seen[v], true), "vertex {v} twice");
        }
        assert!(seen.iter().all(|&x| x));
        assert!(classes.ranges.len() >= 3);
        let free = (0..n).filter(|&v| !fixed[v]).count();
        assert_eq!(classes.ranges.iter().map(|r| r.len()).sum::<usize>(), free);
        let original = Wedges::new(n, &cap.faces, &ln_source);
        for range in &classes.ranges {
            for i in range.clone() {
                let v = classes.order[i];
                assert!(!fixed[v]);
                let (mine, theirs) = (classes.wedges.at(i), original.at(v));
                assert_eq!(mine.len(), theirs.len());
                for (m, t) in mine.iter().zip(theirs) {
                    assert_eq!([classes.order[m.a as usize], classes.order[m.b as usize]], [t.a as usize, t.b as usize]);
                    assert_eq!(m.ln_source, t.ln_source);
                    assert!(!range.contains(&(m.a as usize)) && !range.contains(&(m.b as usize)), "a face inside one class");
                }
            }
        }
    }
}
