//! Joining consecutive crease points by edge flips (see [`super`]): the edges their planar
//! segment crosses are flipped while the mesh stays an embedding in its chart.

use crate::remesh::shape::state::{third, Shaping};

/// Flips tried to join two crease points.
const MAX_JOIN_FLIPS: usize = 8;

/// The faces around each vertex, kept up to date through the joining flips.
pub(super) struct Around(Vec<Vec<u32>>);

impl Around {
    pub(super) fn new(mesh: &Shaping) -> Self {
        let mut around = vec![Vec::new(); mesh.plane.len()];
        for (t, f) in mesh.faces.iter().enumerate() {
            for &v in f {
                around[v as usize].push(t as u32);
            }
        }
        Self(around)
    }

    /// The faces around `v`.
    fn of(&self, v: u32) -> &[u32] {
        &self.0[v as usize]
    }

    /// Whether `(u, w)` is an edge of `mesh`.
    pub(super) fn joined(&self, mesh: &Shaping, u: u32, w: u32) -> bool {
        self.of(u).iter().any(|&t| mesh.faces[t as usize].contains(&w))
    }

    /// The face running `b -> a` (`None` on the boundary).
    fn running(&self, mesh: &Shaping, b: u32, a: u32) -> Option<usize> {
        self.of(b).iter().map(|&t| t as usize).find(|&t| third(mesh.faces[t], b, a).is_some())
    }

    /// Flip the edge `(a, b)` of faces `t1 = (c, a, b)` and `t2 = (d, b, a)` into `(c, d)`.
    fn flip(&mut self, mesh: &mut Shaping, [t1, t2]: [usize; 2], [a, b, c, d]: [u32; 4]) {
        mesh.faces[t1] = [c, a, d];
        mesh.faces[t2] = [d, b, c];
        let (t1, t2) = (t1 as u32, t2 as u32);
        self.0[a as usize].retain(|&t| t != t2);
        self.0[b as usize].retain(|&t| t != t1);
        self.0[c as usize].push(t2);
        self.0[d as usize].push(t1);
    }
}

/// Make `(u, w)` an edge of `mesh` by flipping the edges that the planar segment `u -> w`
/// crosses, each only when both its new faces are oriented in the mesh's chart (so the mesh
/// stays an embedding). Returns the flips made.
pub(super) fn join(mesh: &mut Shaping, around: &mut Around, u: u32, w: u32) -> usize {
    if ![u, w].iter().all(|&v| mesh.planar(v)) {
        return 0;
    }
    let mut flips = 0;
    for _ in 0..MAX_JOIN_FLIPS {
        let Some(crossed) = crossed_edges(mesh, around, u, w) else { return flips };
        let mut flipped = false;
        for (t1, t2, a, b) in crossed {
            // t1 = (c, a, b) runs a -> b, t2 runs b -> a with corner d.
            let (Some(c), Some(d)) = (third(mesh.faces[t1], a, b), third(mesh.faces[t2], b, a)) else { continue };
            if ![a, b, c, d].iter().all(|&v| mesh.planar(v)) {
                continue;
            }
            let p = |v: u32| mesh.plane[v as usize];
            if mesh.oriented(p(c), p(a), p(d), 0.0) && mesh.oriented(p(d), p(b), p(c), 0.0) && !around.joined(mesh, c, d) {
                around.flip(mesh, [t1, t2], [a, b, c, d]);
                flips += 1;
                flipped = true;
                break;
            }
        }
        if !flipped {
            return flips;
        }
    }
    flips
}

/// The edges `(a, b)` that the planar segment `u -> w` crosses, in order from `u`, each with
/// its face running `a -> b` and the one running `b -> a`: `None` when `(u, w)` is an edge
/// already or the walk does not reach `w`.
fn crossed_edges(mesh: &Shaping, around: &Around, u: u32, w: u32) -> Option<Vec<(usize, usize, u32, u32)>> {
    let faces = &mesh.faces;
    let p = |v: u32| mesh.plane[v as usize];
    let side = |a: u32, b: u32, q: [f64; 2]| crate::mesh::geometry::signed_area_2d(p(a), p(b), q) * mesh.orientation;
    let (pu, pw) = (p(u), p(w));
    if around.joined(mesh, u, w) {
        return None;
    }
    // The face of u whose opposite edge (a, b) the segment leaves through.
    let mut current = around.of(u).iter().map(|&t| t as usize).find_map(|t| {
        let f = faces[t];
        let k = f.iter().position(|&x| x == u)?;
        let (a, b) = (f[(k + 1) % 3], f[(k + 2) % 3]);
        // w beyond (a, b), between the rays u -> a and u -> b.
        (side(u, a, pw) > 0.0 && side(b, u, pw) > 0.0 && side(a, b, pw) < 0.0).then_some((t, a, b))
    })?;
    let mut out = Vec::new();
    for _ in 0..64 {
        let (t, a, b) = current;
        let t2 = around.running(mesh, b, a)?;
        out.push((t, t2, a, b));
        let c = third(faces[t2], b, a)?;
        if c == w {
            return Some(out);
        }
        // Leave t2 = (b, a, c) through (a, c) or (c, b): the side of the segment c lies on.
        let s = crate::mesh::geometry::signed_area_2d(pu, pw, p(c)) * mesh.orientation;
        current = if s > 0.0 { (t2, a, c) } else { (t2, c, b) };
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::remesh::shape::state::Role;

    /// A fan of thin triangles between u = (0, 0) and w = (3, 0): the segment u -> w crosses
    /// the edges (a_k, b_k) of a strip of three quads; `join` flips them until (u, w) is an
    /// edge, every face still oriented in the plane.
    #[test]
    fn join_flips_the_crossed_edges() {
        // u = 0, w = 1, a_k = 2 + k above (y = 1), b_k = 5 + k below (y = -1), k = 0..3, at
        // x = 0.5, 1.5, 2.5.
        let mut plane = vec![[0.0, 0.0], [3.0, 0.0]];
        plane.extend((0..3).map(|k| [0.5 + k as f64, 1.0]));
        plane.extend((0..3).map(|k| [0.5 + k as f64, -1.0]));
        let (a, b) = (|k: u32| 2 + k, |k: u32| 5 + k);
        // u's face, the strip's quads split along (a_k, b_k) and (a_k, b_{k+1}), w's face.
        let mut faces = vec![[0, b(0), a(0)]];
        for k in 0..2 {
            faces.push([a(k), b(k), b(k + 1)]);
            faces.push([a(k), b(k + 1), a(k + 1)]);
        }
        faces.push([a(2), b(2), 1]);
        let position = plane.iter().map(|p| [p[0], p[1], 0.0]).collect();
        let n = plane.len();
        let mut mesh = Shaping { faces, plane, position, hint: vec![u32::MAX; n], role: vec![Role::Free; n], has_plane: vec![true; n], orientation: 1.0, chart: crate::remesh::shape::state::Chart::Plane };
        let area = |m: &Shaping| m.faces.iter().map(|f| crate::mesh::geometry::signed_area_2d(m.plane[f[0] as usize], m.plane[f[1] as usize], m.plane[f[2] as usize])).sum::<f64>();
        let before = area(&mesh);
        assert!(mesh.faces.iter().all(|f| mesh.oriented(mesh.plane[f[0] as usize], mesh.plane[f[1] as usize], mesh.plane[f[2] as usize], 0.0)));
        let mut around = Around::new(&mesh);
        let flips = join(&mut mesh, &mut around, 0, 1);
        assert!(flips >= 3, "{flips} flips");
        assert!(mesh.faces.iter().any(|f| f.contains(&0) && f.contains(&1)), "{:?}", mesh.faces);
        assert!(mesh.faces.iter().all(|f| mesh.oriented(mesh.plane[f[0] as usize], mesh.plane[f[1] as usize], mesh.plane[f[2] as usize], 0.0)), "{:?}", mesh.faces);
        assert!((area(&mesh) - before).abs() < 1e-12, "the faces still tile the same region");
        // Joined already: nothing more to flip.
        let mut around = Around::new(&mesh);
        assert_eq!(join(&mut mesh, &mut around, 0, 1), 0);
    }
}
