//! Prolongation of a planar map from a decimated mesh back to every input vertex, undoing
//! the collapses of [`crate::mesh::decimate`] in reverse order (the multilevel
//! parameterization of large closed surfaces, `crate::param::multilevel`).
//!
//! Each removed vertex goes back with its star of that moment, whose other vertices are
//! placed already. It is put at the mean value coordinates of its 3-D star (Floater 2003)
//! applied to the star's planar positions, which reproduce the planar map where the star is
//! flat; when that point does not see every edge of the star's polygon, it is moved towards
//! the vertex it was collapsed into, which sees every edge but the two at itself, along a
//! direction that sees those two as well (the cone both faces at the kept vertex allow). So
//! every face is positively oriented after every insertion: the prolonged map folds no face.

use crate::mesh::decimate::{Collapse, Hierarchy};
use crate::mesh::geometry::{dot, norm, signed_area_2d, sub};

/// What the prolongation did.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct ProlongReport {
    /// Vertices put back.
    pub inserted: usize,
    /// Of those, placed nearer the vertex they were collapsed into than their mean value
    /// point (which folded a face of their star).
    pub moved_towards_kept: usize,
    /// Of those, placed by the cone direction at the kept vertex.
    pub placed_in_cone: usize,
    /// Vertices for which no position kept their star unfolded (placed at the kept vertex's
    /// cone point anyway; the area refinement and the fold count see them).
    pub unplaced: usize,
}

/// Halvings of the step towards the kept vertex, and of the cone step, before giving up.
const HALVINGS: usize = 40;

/// Called between levels of the prolongation with the level's index, the map so far, the
/// faces of the mesh so far (input numbering) and which vertices it has.
pub(crate) type LevelStep<'a> = dyn FnMut(usize, &mut [[f64; 2]], &[[u32; 3]], &[bool]) + 'a;

/// Put every vertex removed by `hierarchy` back into `plane` (input numbering; the coarse
/// vertices placed), in reverse order of removal. `orientation` is `1` when the map's faces
/// are positively oriented, `-1` when negatively. When the mesh has `level_sizes[k]`
/// vertices, `at_level` is called with `k` and the mesh so far.
///
/// The mean value point is taken on the domain (the cap: `domain.lift` of the star's planar
/// points, combined, then `domain.project`ed back), where the areas are measured: combined
/// in the plane, the points near a closed surface's puncture, where the stereographic
/// projection's scale changes fastest, came out with their faces' areas off by 10% on
/// average.
#[allow(clippy::too_many_arguments)]
pub(crate) fn prolong(
    plane: &mut [[f64; 2]],
    vertices: &[[f64; 3]],
    hierarchy: &Hierarchy,
    orientation: f64,
    domain: &DomainPoints,
    level_sizes: &[usize],
    at_level: &mut LevelStep,
) -> ProlongReport {
    let mut report = ProlongReport::default();
    let mut weights: Vec<(u32, f64)> = Vec::new();
    let mut mesh = LevelMesh::new(vertices.len(), hierarchy);
    for c in hierarchy.collapses.iter().rev() {
        let star = hierarchy.star(c);
        report.inserted += 1;
        let candidate = mean_value_point(plane, vertices, c.removed, star, domain, &mut weights);
        let sees = |p: [f64; 2]| star.iter().all(|&[a, b]| orientation * signed_area_2d(p, plane[a as usize], plane[b as usize]) > 0.0);
        let position = if sees(candidate) {
            Some(candidate)
        } else {
            report.moved_towards_kept += 1;
            towards_kept(plane, c, star, candidate, orientation, &sees, &mut report).map(|p| widened(plane, star, p, orientation))
        };
        plane[c.removed as usize] = position.unwrap_or_else(|| {
            report.unplaced += 1;
            plane[c.kept as usize]
        });
        mesh.split(c, star);
        if let Some(k) = level_sizes.iter().position(|&s| s == mesh.size) {
            at_level(k, plane, &mesh.faces, &mesh.present);
        }
    }
    report
}

/// The mesh between levels: its faces (input numbering) and which vertices it has.
struct LevelMesh {
    faces: Vec<[u32; 3]>,
    incident: Vec<Vec<u32>>,
    present: Vec<bool>,
    size: usize,
}

impl LevelMesh {
    fn new(n: usize, hierarchy: &Hierarchy) -> LevelMesh {
        let faces = hierarchy.coarse_faces.clone();
        let mut incident = vec![Vec::new(); n];
        for (f, t) in faces.iter().enumerate() {
            for &v in t {
                incident[v as usize].push(f as u32);
            }
        }
        let present = hierarchy.is_coarse.clone();
        let size = present.iter().filter(|&&p| p).count();
        LevelMesh { faces, incident, present, size }
    }

    /// Undo the collapse `c`: the faces `(kept, a, b)` of the removed vertex's star become
    /// `(removed, a, b)`, and the two faces at the edge come back.
    fn split(&mut self, c: &Collapse, star: &[[u32; 2]]) {
        let (v, u) = (c.removed, c.kept);
        for &[a, b] in star {
            if a == u || b == u {
                let f = self.faces.len() as u32;
                self.faces.push([v, a, b]);
                for w in [v, a, b] {
                    self.incident[w as usize].push(f);
                }
                continue;
            }
            let faces = &self.faces;
            let found = self.incident[u as usize].iter().position(|&f| is_cyclic(faces[f as usize], [u, a, b]));
            if let Some(k) = found {
                let f = self.incident[u as usize].swap_remove(k);
                for x in self.faces[f as usize].iter_mut() {
                    if *x == u {
                        *x = v;
                    }
                }
                self.incident[v as usize].push(f);
            }
        }
        self.present[v as usize] = true;
        self.size += 1;
    }
}

/// Whether `t` is the triangle `s` up to a cyclic shift.
fn is_cyclic(t: [u32; 3], s: [u32; 3]) -> bool {
    (0..3).any(|k| t[k] == s[0] && t[(k + 1) % 3] == s[1] && t[(k + 2) % 3] == s[2])
}

/// The point nearer the kept vertex that sees the whole star: first along the way to the
/// mean value `candidate`, then along the cone direction of the two faces at the kept vertex.
fn towards_kept(
    plane: &[[f64; 2]],
    c: &Collapse,
    star: &[[u32; 2]],
    candidate: [f64; 2],
    orientation: f64,
    sees: &dyn Fn([f64; 2]) -> bool,
    report: &mut ProlongReport,
) -> Option<[f64; 2]> {
    let u = plane[c.kept as usize];
    let at = |d: [f64; 2], t: f64| [u[0] + t * d[0], u[1] + t * d[1]];
    let to_candidate = [candidate[0] - u[0], candidate[1] - u[1]];
    let mut t = 0.5;
    for _ in 0..HALVINGS {
        if sees(at(to_candidate, t)) {
            return Some(at(to_candidate, t));
        }
        t *= 0.5;
    }
    // The faces (removed, kept, x) and (removed, y, kept).
    let x = star.iter().find(|s| s[0] == c.kept).map(|s| plane[s[1] as usize])?;
    let y = star.iter().find(|s| s[1] == c.kept).map(|s| plane[s[0] as usize])?;
    let unit = |p: [f64; 2]| {
        let d = [p[0] - u[0], p[1] - u[1]];
        let l = d[0].hypot(d[1]);
        (l > 0.0).then(|| [d[0] / l, d[1] / l])
    };
    let (ex, ey) = (unit(x)?, unit(y)?);
    // Left normals: cross(e, L(e)) > 0.
    let d = [orientation * (-ex[1] + ey[1]), orientation * (ex[0] - ey[0])];
    let l = d[0].hypot(d[1]);
    if l <= 0.0 {
        return None;
    }
    let d = [d[0] / l, d[1] / l];
    let reach = star.iter().flat_map(|s| s.iter()).map(|&w| {
        let p = plane[w as usize];
        (p[0] - u[0]).hypot(p[1] - u[1])
    });
    let mut t = 0.5 * reach.filter(|&r| r > 0.0).fold(f64::INFINITY, f64::min);
    for _ in 0..HALVINGS {
        if sees(at(d, t)) {
            report.placed_in_cone += 1;
            return Some(at(d, t));
        }
        t *= 0.5;
    }
    None
}

/// `p`, which sees the whole star, moved towards the centroid of the star's polygon as long
/// as that enlarges the star's smallest face ([`WIDEN_STEPS`] steps, each the longest of
/// 1, 1/2, 1/4 and 1/8 of the way that does): a point found near the kept vertex leaves thin
/// faces that the vertices put back later would have to be fitted into.
fn widened(plane: &[[f64; 2]], star: &[[u32; 2]], p: [f64; 2], orientation: f64) -> [f64; 2] {
    let smallest = |q: [f64; 2]| star.iter().map(|&[a, b]| orientation * signed_area_2d(q, plane[a as usize], plane[b as usize])).fold(f64::INFINITY, f64::min);
    let k = star.len() as f64;
    let g = star.iter().fold([0.0, 0.0], |s, &[a, _]| [s[0] + plane[a as usize][0] / k, s[1] + plane[a as usize][1] / k]);
    let (mut p, mut worst) = (p, smallest(p));
    for _ in 0..WIDEN_STEPS {
        let step = [1.0, 0.5, 0.25, 0.125].into_iter().map(|t| [p[0] + t * (g[0] - p[0]), p[1] + t * (g[1] - p[1])]).find(|&q| smallest(q) > worst);
        match step {
            Some(q) => {
                worst = smallest(q);
                p = q;
            }
            None => break,
        }
    }
    p
}

/// Steps of [`widened`].
const WIDEN_STEPS: usize = 4;

/// The mean value weights of `v` in its 3-D `star` (faces `(v, a, b)`), unnormalised, one
/// entry per face corner (a neighbour appears once per face it shares with `v`): the weight
/// of a neighbour `w` is `(tan(alpha/2) + tan(beta/2)) / |w - v|` over the two angles at `v`
/// of the faces at the edge `vw`.
pub(crate) fn mean_value_weights(vertices: &[[f64; 3]], v: u32, star: &[[u32; 2]], weights: &mut Vec<(u32, f64)>) {
    weights.clear();
    let pv = vertices[v as usize];
    for &[a, b] in star {
        let (ea, eb) = (sub(vertices[a as usize], pv), sub(vertices[b as usize], pv));
        let (la, lb) = (norm(ea), norm(eb));
        if la <= 0.0 || lb <= 0.0 {
            continue;
        }
        let cos = (dot(ea, eb) / (la * lb)).clamp(-1.0, 1.0);
        // tan(theta / 2) = sqrt((1 - cos) / (1 + cos)).
        let half = ((1.0 - cos) / (1.0 + cos).max(1e-300)).sqrt();
        weights.push((a, half / la));
        weights.push((b, half / lb));
    }
}

/// The planar point of `v`'s mean value coordinates in its 3-D `star`
/// ([`mean_value_weights`]) applied to the star's points on the domain.
fn mean_value_point(plane: &[[f64; 2]], vertices: &[[f64; 3]], v: u32, star: &[[u32; 2]], domain: &DomainPoints, weights: &mut Vec<(u32, f64)>) -> [f64; 2] {
    mean_value_weights(vertices, v, star, weights);
    let mut total: f64 = weights.iter().map(|w| w.1).sum();
    if !(total > 0.0 && total.is_finite()) {
        // A degenerate star: its neighbours' mean.
        weights.clear();
        weights.extend(star.iter().map(|&[a, _]| (a, 1.0)));
        total = star.len() as f64;
    }
    let s = weights.iter().fold([0.0; 3], |s, &(w, k)| {
        let q = (domain.lift)(plane[w as usize]);
        [s[0] + k * q[0], s[1] + k * q[1], s[2] + k * q[2]]
    });
    (domain.project)([s[0] / total, s[1] / total, s[2] / total])
}

/// The planar map's domain: `lift` takes a planar point onto it, `project` takes a point
/// near it (a combination of domain points) back to the plane.
pub(crate) struct DomainPoints<'a> {
    pub lift: &'a (dyn Fn([f64; 2]) -> [f64; 3] + Sync),
    pub project: &'a (dyn Fn([f64; 3]) -> [f64; 2] + Sync),
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::decimate::decimate;
    use crate::mesh::shapes;

    #[test]
    fn a_flat_grid_comes_back_as_itself_and_unfolded() {
        // The planar map of a flat disk is its own (x, y): prolonged from a decimation, every
        // removed vertex of a flat star lands exactly where it was.
        let mesh = shapes::grid_disk(20);
        let n = mesh.vertices.len();
        let boundary = crate::mesh::topology::is_boundary_vertex(&mesh);
        // The boundary is locked (the decimation is for closed meshes; an open one's
        // boundary edges are never collapsed).
        let h = decimate(&mesh.vertices, &mesh.faces, &boundary, &vec![1.0; n], n / 4);
        assert!(h.collapses.len() > n / 2, "{} of {n} removed", h.collapses.len());
        let exact: Vec<[f64; 2]> = mesh.vertices.iter().map(|p| [p[0], p[1]]).collect();
        let mut plane: Vec<[f64; 2]> = exact.iter().zip(&h.is_coarse).map(|(p, &k)| if k { *p } else { [f64::NAN; 2] }).collect();
        let mut levels = Vec::new();
        let sizes: Vec<usize> = (1..4).map(|k| n / 4 + k * n / 6).collect();
        let domain = DomainPoints { lift: &|p| [p[0], p[1], 0.0], project: &|q| [q[0], q[1]] };
        let report = prolong(&mut plane, &mesh.vertices, &h, 1.0, &domain, &sizes, &mut |_, _, faces: &[[u32; 3]], present: &[bool]| {
            // Every level is a closed-up disk of the same Euler characteristic.
            let kept = present.iter().filter(|&&p| p).count() as i64;
            let edges = crate::mesh::topology::edge_faces(&crate::mesh::TriMesh::new(vec![[0.0; 3]; present.len()], faces.to_vec())).unwrap().len() as i64;
            levels.push(kept - edges + faces.len() as i64);
        });
        assert!(levels.len() == 3 && levels.iter().all(|&chi| chi == 1), "{levels:?}");
        assert_eq!(report.inserted, h.collapses.len());
        assert_eq!(report.unplaced, 0);
        let worst = plane.iter().zip(&exact).map(|(p, q)| (p[0] - q[0]).hypot(p[1] - q[1])).fold(0.0, f64::max);
        assert!(worst < 1e-9, "moved by {worst}");
        assert!(crate::mesh::geometry::folded_faces(&plane, &mesh.faces).is_empty());
    }

}
