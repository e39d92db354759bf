//! The remesh being shaped: connectivity, each vertex's point in the map's plane and on the
//! surface, and what each vertex may do. A vertex's surface position is always the lift of its
//! planar point through the inverse map (paper Sec. 4.2), so it lies exactly on the input.

use crate::mesh::fasthash::FastMap;
use crate::mesh::geometry::{cross, dot, norm, signed_area_2d, sub};
use crate::cap::InverseMap;

/// What a vertex of the remesh may do.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Role {
    /// Moves in the plane (tangential relaxation, area equalization).
    Free,
    /// Slides along the input's boundary.
    Boundary,
    /// Stays (a closed surface's rim and bottom, a boundary corner).
    Fixed,
    /// Stays on a crease of the input (`super::crease`).
    Crease,
}

/// The inverse map as a lift from the plane to the surface: [`InverseMap::locate_plane`]
/// with a face hint (an index of [`InverseMap::top_faces`]).
pub(crate) struct SurfaceLift<'a> {
    inverse: &'a InverseMap<'a>,
}

impl<'a> SurfaceLift<'a> {
    /// The lift through `inverse`.
    pub(crate) fn new(inverse: &'a InverseMap<'a>) -> Self {
        Self { inverse }
    }

    /// The input's per-vertex `values` interpolated at the planar point `q` (linear on the
    /// input face it lies in), trying face `hint` first.
    pub(crate) fn interpolate(&self, q: [f64; 2], hint: u32, values: &[f64]) -> Option<f64> {
        let hint = (hint != u32::MAX).then_some(hint as usize);
        let (point, _) = self.inverse.locate_plane_near(q, hint)?;
        let f = self.inverse.mesh().faces[point.face];
        let w = point.barycentric;
        Some(w[0] * values[f[0] as usize] + w[1] * values[f[1] as usize] + w[2] * values[f[2] as usize])
    }

    /// The differential of the inverse map on face `face` (an index of
    /// [`InverseMap::top_faces`]): the 3x2 matrix taking a planar displacement inside the face
    /// to the surface displacement (the map is linear on each input face). `None` for a face
    /// without planar area.
    pub(crate) fn jacobian(&self, face: u32) -> Option<nalgebra::Matrix3x2<f64>> {
        let f = self.inverse.mesh().faces[*self.inverse.top_faces().get(face as usize)?];
        let plane = &self.inverse.map().plane;
        let [p0, p1, p2] = f.map(|v| nalgebra::Vector2::from(plane[v as usize]));
        let [x0, x1, x2] = f.map(|v| nalgebra::Vector3::from(self.inverse.mesh().vertices[v as usize]));
        let m = nalgebra::Matrix2::from_columns(&[p1 - p0, p2 - p0]);
        let n = nalgebra::Matrix3x2::from_columns(&[x1 - x0, x2 - x0]);
        let j = n * m.try_inverse()?;
        j.iter().all(|x| x.is_finite()).then_some(j)
    }

    /// The inverse map.
    pub(crate) fn inverse(&self) -> &InverseMap<'a> {
        self.inverse
    }

    /// The surface point of the planar point `q` and the face it lies in (an index of
    /// [`InverseMap::top_faces`]), trying face `hint` first (the answer does not depend on
    /// it, see [`crate::remesh::locate::Locator::locate_near`]).
    pub(crate) fn lift(&self, q: [f64; 2], hint: u32) -> Option<([f64; 3], u32)> {
        let hint = (hint != u32::MAX).then_some(hint as usize);
        let (point, face) = self.inverse.locate_plane_near(q, hint)?;
        Some((point.position, face as u32))
    }
}

/// Where the remesh's faces must stay oriented: the test that keeps its planar points an
/// embedding of the surface's triangulation (docs/method.md section 18, "Orientation on the
/// cap").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Chart {
    /// Straight-edged triangles in the map's plane (open surfaces).
    Plane,
    /// Triangles on the cap the plane stands for, oriented as the flat triangle through their
    /// three cap points (closed surfaces: their cap covers nearly the whole sphere, whose
    /// stereographic plane bends a band around it, a long bone's shaft, into an annulus).
    Cap,
}

impl Chart {
    /// The signed area of the triangle `(a, b, c)` of planar points in this chart, in units of
    /// planar area: on the cap, half the triple product of the three cap points (the flat
    /// triangle's signed area times its plane's distance from the sphere's centre, which is
    /// about 1 for a small triangle) divided by the stereographic area factor
    /// `4 / (1 + |m|^2)^2` at their planar centroid `m`, so the two agree for a small triangle.
    pub(crate) fn signed_area(self, a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
        match self {
            Chart::Plane => signed_area_2d(a, b, c),
            Chart::Cap => {
                let [x, y, z] = [a, b, c].map(crate::cap::inverse_stereographic);
                let m = [(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0];
                let r = 1.0 + m[0] * m[0] + m[1] * m[1];
                0.5 * dot(x, cross(y, z)) * r * r / 4.0
            }
        }
    }
}

/// The orientation (+1 or -1) held in `chart` by most faces that have a planar point at every
/// corner and a corner that moves.
pub(crate) fn planar_orientation(faces: &[[u32; 3]], plane: &[[f64; 2]], has_plane: &[bool], role: &[Role], chart: Chart) -> f64 {
    let s: f64 = faces
        .iter()
        .filter(|f| f.iter().all(|&v| has_plane[v as usize]) && f.iter().any(|&v| role[v as usize] != Role::Fixed))
        .map(|f| chart.signed_area(plane[f[0] as usize], plane[f[1] as usize], plane[f[2] as usize]).signum())
        .sum();
    if s < 0.0 { -1.0 } else { 1.0 }
}

/// The remesh under optimisation.
pub(crate) struct Shaping {
    /// Faces (changed by flips).
    pub faces: Vec<[u32; 3]>,
    /// Planar point of each vertex (meaningful where `has_plane`).
    pub plane: Vec<[f64; 2]>,
    /// Surface position of each vertex.
    pub position: Vec<[f64; 3]>,
    /// The input face each vertex was last located in (a hint for the next lift).
    pub hint: Vec<u32>,
    /// What each vertex may do.
    pub role: Vec<Role>,
    /// Whether each vertex has a planar point (not a closed surface's bottom): faces
    /// touching one that has not are never changed.
    pub has_plane: Vec<bool>,
    /// +1 or -1: the orientation the faces keep in `chart`.
    pub orientation: f64,
    /// Where that orientation is judged.
    pub chart: Chart,
}

impl Shaping {
    /// Whether vertex `v` has a planar point.
    pub fn planar(&self, v: u32) -> bool {
        self.has_plane[v as usize]
    }

    /// Whether the triangle `(a, b, c)` of planar points has the kept orientation and an area
    /// above `min_area` (planar units) in the mesh's [`Chart`].
    pub fn oriented(&self, a: [f64; 2], b: [f64; 2], c: [f64; 2], min_area: f64) -> bool {
        self.orientation * self.chart.signed_area(a, b, c) > min_area
    }

    /// The faces around each vertex.
    pub fn incidence(&self) -> Incidence {
        Incidence::new(self.plane.len(), &self.faces)
    }

    /// Colour classes of the vertices that move (`role != Fixed`): no two vertices of a class
    /// share a face, so a class moves in parallel with the same result as one by one
    /// (greedy colouring in vertex order: deterministic).
    pub fn color_classes(&self, incidence: &Incidence) -> Vec<Vec<u32>> {
        let n = self.plane.len();
        let mut color = vec![u32::MAX; n];
        let mut classes: Vec<Vec<u32>> = Vec::new();
        let mut taken: Vec<bool> = Vec::new();
        for v in 0..n {
            if matches!(self.role[v], Role::Fixed | Role::Crease) || incidence.of(v).is_empty() {
                continue;
            }
            taken.clear();
            taken.resize(classes.len() + 1, false);
            for &t in incidence.of(v) {
                for &u in &self.faces[t as usize] {
                    if color[u as usize] != u32::MAX {
                        taken[color[u as usize] as usize] = true;
                    }
                }
            }
            let c = taken.iter().position(|&x| !x).unwrap_or(classes.len());
            if c == classes.len() {
                classes.push(Vec::new());
            }
            color[v] = c as u32;
            classes[c].push(v as u32);
        }
        classes
    }
}

/// Faces around each vertex.
pub(crate) use crate::mesh::topology::VertexFaces as Incidence;

/// Each undirected edge `(min, max)`: its face where it runs min -> max, and where it runs
/// max -> min (`u32::MAX` when none).
pub(crate) fn edge_faces(faces: &[[u32; 3]]) -> FastMap<(u32, u32), [u32; 2]> {
    // About 3F/2 edges: sized once (growing the table was a twentieth of the shape stage).
    let mut edges: FastMap<(u32, u32), [u32; 2]> = FastMap::with_capacity_and_hasher(3 * faces.len() / 2 + 16, Default::default());
    for (t, f) in faces.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            edges.entry((a.min(b), a.max(b))).or_insert([u32::MAX; 2])[usize::from(a > b)] = t as u32;
        }
    }
    edges
}

/// The neighbours of vertex `v` of `mesh` (sorted, each once).
pub(crate) fn neighbours(mesh: &Shaping, incidence: &Incidence, v: u32) -> Vec<u32> {
    let mut out: Vec<u32> = incidence.of(v as usize).iter().flat_map(|&t| mesh.faces[t as usize]).filter(|&u| u != v).collect();
    out.sort_unstable();
    out.dedup();
    out
}

/// Whether collapsing edge `(a, b)` keeps the mesh manifold: the two ends share exactly two
/// neighbours (the edge's link condition).
pub(crate) fn link_is_two(mesh: &Shaping, incidence: &Incidence, a: u32, b: u32) -> bool {
    let (na, nb) = (neighbours(mesh, incidence, a), neighbours(mesh, incidence, b));
    na.iter().filter(|v| nb.binary_search(v).is_ok()).count() == 2
}

/// Remove the faces marked `dead` (same length as `faces`), keeping the others' order.
pub(crate) fn drop_faces(faces: &mut Vec<[u32; 3]>, dead: &[bool]) {
    let mut k = 0;
    faces.retain(|_| {
        k += 1;
        !dead[k - 1]
    });
}

/// The corner of `face` after the directed edge `a -> b` (`None` if the face does not run
/// `a -> b`).
pub(crate) fn third(face: [u32; 3], a: u32, b: u32) -> Option<u32> {
    (0..3).find(|&k| face[k] == a && face[(k + 1) % 3] == b).map(|k| face[(k + 2) % 3])
}

/// The least of `measure` (e.g. [`smallest_angle`]) over the faces `ring` around vertex `v`
/// with `v` at `x`.
pub(crate) fn ring_least(mesh: &Shaping, ring: &[u32], v: usize, x: [f64; 3], measure: fn([f64; 3], [f64; 3], [f64; 3]) -> f64) -> f64 {
    ring.iter()
        .map(|&t| {
            let p = mesh.faces[t as usize].map(|w| if w as usize == v { x } else { mesh.position[w as usize] });
            measure(p[0], p[1], p[2])
        })
        .fold(f64::INFINITY, f64::min)
}

/// The vertices of the faces of `mesh` whose smallest angle is below `threshold` (radians)
/// that `keep` accepts, sorted, each once.
pub(crate) fn thin_face_vertices(mesh: &Shaping, threshold: f64, keep: impl Fn(u32) -> bool) -> Vec<u32> {
    let mut vertices: Vec<u32> = mesh
        .faces
        .iter()
        .filter(|f| f[0] != f[1] && smallest_angle(mesh.position[f[0] as usize], mesh.position[f[1] as usize], mesh.position[f[2] as usize]) < threshold)
        .flatten()
        .copied()
        .filter(|&v| keep(v))
        .collect();
    vertices.sort_unstable();
    vertices.dedup();
    vertices
}

/// The smallest angle (radians) of the triangle `(a, b, c)`.
pub(crate) fn smallest_angle(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    let (s, c) = smallest_angle_sin_cos(a, b, c);
    s.atan2(c)
}

/// The tangent of the smallest angle of the triangle `(a, b, c)` (0 for a degenerate one):
/// it orders triangles as [`smallest_angle`] does (the smallest angle is at most 60 degrees,
/// where the tangent grows with the angle) without an `atan2`, which was a tenth of the
/// shape stage's time in the flips' comparisons.
pub(crate) fn smallest_angle_tan(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    let (s, c) = smallest_angle_sin_cos(a, b, c);
    if c > 0.0 { s / c } else if s > 0.0 { f64::INFINITY } else { 0.0 }
}

/// `(|u x v|, -u . v)` of the two edges at the smallest angle of `(a, b, c)`: that angle is
/// their `atan2`.
fn smallest_angle_sin_cos(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> (f64, f64) {
    // The smallest angle is opposite the shortest edge: one angle instead of three (this
    // is the shape stage's innermost test).
    let (ab, bc, ca) = (sub(b, a), sub(c, b), sub(a, c));
    let (lab, lbc, lca) = (dot(ab, ab), dot(bc, bc), dot(ca, ca));
    let (u, v) = if lab <= lbc && lab <= lca {
        (ca, bc) // opposite c: the edges c->a and c->b
    } else if lbc <= lca {
        (ab, ca) // opposite a
    } else {
        (bc, ab) // opposite b
    };
    // u and v point into and out of the opposite vertex; the angle between -u and v.
    (norm(cross(u, v)), -dot(u, v))
}

#[cfg(test)]
mod tests {
    use super::{smallest_angle, smallest_angle_tan, SurfaceLift};
    use crate::mesh::geometry::triangle_angles;

    /// The inverse map's differential on a face ([`SurfaceLift::jacobian`]) carries a planar
    /// displacement inside the face to the surface displacement the lift gives (the map is
    /// linear on each input face), on the left ventricle's map.
    #[test]
    fn the_lift_jacobian_is_the_lifts_derivative() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/open_lv_endo_rabbit_chaste.obj.gz");
        let mesh = crate::read_mesh(std::path::Path::new(path)).expect("the bundled mesh reads");
        let map = crate::parameterize(&mesh, &crate::ParamOptions::default(), &crate::NoProgress).expect("the bundled mesh maps");
        let inverse = map.inverse(&mesh).expect("an inverse map");
        let lift = SurfaceLift::new(&inverse);
        let mut checked = 0;
        for face in (0..inverse.top_faces().len()).step_by(37) {
            let p = mesh.faces[inverse.top_faces()[face]].map(|v| map.plane[v as usize]);
            let c = [(p[0][0] + p[1][0] + p[2][0]) / 3.0, (p[0][1] + p[1][1] + p[2][1]) / 3.0];
            // A tenth of the way towards the first corner: still inside the face.
            let d = [0.1 * (p[0][0] - c[0]), 0.1 * (p[0][1] - c[1])];
            let (Some((x0, f0)), Some((x1, f1))) = (lift.lift(c, face as u32), lift.lift([c[0] + d[0], c[1] + d[1]], face as u32)) else { continue };
            let Some(j) = lift.jacobian(f0) else { continue };
            if f0 != f1 {
                continue;
            }
            let dx = j * nalgebra::Vector2::from(d);
            let want = nalgebra::Vector3::from(x1) - nalgebra::Vector3::from(x0);
            assert!((dx - want).norm() <= 1e-6 * want.norm(), "face {face}: {dx:?} vs {want:?}");
            checked += 1;
        }
        assert!(checked > inverse.top_faces().len() / 37 / 2, "only {checked} faces checked");
    }

    /// The one-atan2 shortcut equals the smallest of the three angles computed in full.
    #[test]
    fn smallest_angle_is_the_least_of_the_three() {
        let mut seed = 12345u64;
        let mut next = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for _ in 0..1000 {
            let [a, b, c] = [[next(), next(), next()], [next(), next(), next()], [next(), next(), next()]];
            let t = triangle_angles(a, b, c);
            let want = t[0].min(t[1]).min(t[2]);
            assert!((smallest_angle(a, b, c) - want).abs() < 1e-12, "{a:?} {b:?} {c:?}");
            // The flips' key is the tangent of the same angle.
            assert!((smallest_angle_tan(a, b, c).atan() - want).abs() < 1e-12, "{a:?} {b:?} {c:?}");
        }
        // An obtuse triangle: the smallest angle is still opposite the shortest edge.
        let got = smallest_angle([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [-0.2, 0.05, 0.0]);
        let t = triangle_angles([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [-0.2, 0.05, 0.0]);
        assert!((got - t[0].min(t[1]).min(t[2])).abs() < 1e-12);
        // Degenerate triangles have the key 0, as their smallest angle.
        assert_eq!(smallest_angle_tan([0.0; 3], [0.0; 3], [1.0, 0.0, 0.0]), 0.0);
        assert_eq!(smallest_angle_tan([0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]), 0.0);
    }

    /// The cap's signed area agrees with the plane's on a small triangle anywhere (the
    /// stereographic area factor taken out), has its sign, and is zero for three points on a
    /// great circle, which the plane bends into a curved arc: the unit circle is the cap's
    /// equator, so points along it lie on a straight line of the cap.
    #[test]
    fn cap_area_is_the_planar_area_of_small_triangles_and_straightens_the_equator() {
        use super::Chart;
        use crate::mesh::geometry::signed_area_2d;
        for centre in [[0.0, 0.0], [0.7, -0.4], [3.0, 2.0], [15.0, -9.0]] {
            let h = 1e-4 * (1.0f64).max(centre[0] * centre[0] + centre[1] * centre[1]).sqrt();
            let [a, b, c] = [[0.0, 0.0], [h, 0.2 * h], [0.3 * h, 0.9 * h]].map(|d| [centre[0] + d[0], centre[1] + d[1]]);
            let (plane, cap) = (signed_area_2d(a, b, c), Chart::Cap.signed_area(a, b, c));
            assert!(plane > 0.0 && (cap / plane - 1.0).abs() < 1e-3, "{centre:?}: plane {plane:e}, cap {cap:e}");
            assert!(Chart::Cap.signed_area(a, c, b) < 0.0);
            assert_eq!(Chart::Plane.signed_area(a, b, c), plane);
        }
        let on_equator = |t: f64| [t.cos(), t.sin()];
        let [a, b, c] = [0.0, 0.3, 0.6].map(on_equator);
        assert!(signed_area_2d(a, b, c) > 1e-3, "an arc of the unit circle bends in the plane");
        assert!(Chart::Cap.signed_area(a, b, c).abs() < 1e-15, "{}", Chart::Cap.signed_area(a, b, c));
    }
}

/// Meshes for the shape stage's unit tests.
#[cfg(test)]
pub(crate) mod test_meshes {
    use super::{Role, Shaping};

    /// A flat `k x k` grid of two triangles a cell whose surface points are its planar points:
    /// vertex `(i, j)` at `point(i, j)`, which also gives its role.
    pub(crate) fn flat_grid(k: usize, point: impl Fn(usize, usize) -> ([f64; 2], Role)) -> Shaping {
        let idx = |i: usize, j: usize| (j * (k + 1) + i) as u32;
        let (plane, role): (Vec<[f64; 2]>, Vec<Role>) = (0..=k).flat_map(|j| (0..=k).map(move |i| (i, j))).map(|(i, j)| point(i, j)).unzip();
        let mut faces = Vec::new();
        for j in 0..k {
            for i in 0..k {
                faces.push([idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)]);
                faces.push([idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)]);
            }
        }
        let n = plane.len();
        let position = plane.iter().map(|p| [p[0], p[1], 0.0]).collect();
        Shaping { faces, plane, position, hint: vec![u32::MAX; n], role, has_plane: vec![true; n], orientation: 1.0, chart: super::Chart::Plane }
    }
}
