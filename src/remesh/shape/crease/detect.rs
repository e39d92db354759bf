//! Finding the creases (see [`super`]): chains of sharp input edges that also bend at the
//! remesh's scale.

use super::grid::PointGrid;
use crate::mesh::fasthash::FastMap;
use crate::mesh::geometry::{cross, dot, norm, sub};
use crate::remesh::shape::state::SurfaceLift;

/// A crease must also bend by this share of the crease bound between the mean normals of
/// the faces on its two sides within one remesh edge length: a staircased segmentation's
/// steps bend sharply but not at the remesh's scale.
const SCALE_SHARE: f64 = 0.75;

/// The input's crease chains as input vertex lists (a closed loop repeats its first vertex
/// last): edges whose faces are both mapped into the plane and bend by more than `crease`
/// (radians), also at the scale `len` (see [`SCALE_SHARE`]), split at vertices where other
/// than two such edges meet.
pub(crate) fn crease_chains(lift: &SurfaceLift, crease: f64, len: f64) -> Vec<Vec<u32>> {
    let inverse = lift.inverse();
    let mesh = inverse.mesh();
    let mut top = vec![false; mesh.faces.len()];
    for &f in inverse.top_faces() {
        top[f] = true;
    }
    let cos_crease = crease.cos();
    let centroids = Centroids::new(mesh, len);
    let mut creases: Vec<(u32, u32)> = crate::remesh::shape::state::edge_faces(&mesh.faces)
        .into_iter()
        .filter(|(_, f)| f[0] != u32::MAX && f[1] != u32::MAX)
        .map(|(e, f)| (e, f.map(|t| t as usize)))
        .filter(|(_, f)| top[f[0]] && top[f[1]])
        .filter(|(_, f)| {
            let (n1, n2) = (face_normal(mesh, f[0]), face_normal(mesh, f[1]));
            let l = norm(n1) * norm(n2);
            l > 0.0 && dot(n1, n2) < cos_crease * l
        })
        .filter(|&((a, b), f)| bends_at_scale(mesh, [a, b], f, &centroids, len, (SCALE_SHARE * crease).cos()))
        .map(|(e, _)| e)
        .collect();
    creases.sort_unstable();
    let mut adjacent: FastMap<u32, Vec<u32>> = FastMap::default();
    for &(a, b) in &creases {
        adjacent.entry(a).or_default().push(b);
        adjacent.entry(b).or_default().push(a);
    }
    for list in adjacent.values_mut() {
        list.sort_unstable();
    }
    let degree = |v: u32| adjacent.get(&v).map_or(0, Vec::len);
    let mut used: FastMap<(u32, u32), ()> = FastMap::default();
    let mut chains = Vec::new();
    // Chains from ends and junctions first, then the closed loops left.
    let mut starts: Vec<u32> = adjacent.keys().copied().filter(|&v| degree(v) != 2).collect();
    starts.sort_unstable();
    let mut loops: Vec<u32> = adjacent.keys().copied().filter(|&v| degree(v) == 2).collect();
    loops.sort_unstable();
    for start in starts.into_iter().chain(loops) {
        for &first in &adjacent[&start] {
            if used.contains_key(&(start.min(first), start.max(first))) {
                continue;
            }
            let mut chain = vec![start];
            let (mut prev, mut at) = (start, first);
            loop {
                used.insert((prev.min(at), prev.max(at)), ());
                chain.push(at);
                if at == start || degree(at) != 2 {
                    break;
                }
                let Some(&next) = adjacent[&at].iter().find(|&&u| u != prev && !used.contains_key(&(at.min(u), at.max(u)))) else { break };
                (prev, at) = (at, next);
            }
            chains.push(chain);
        }
    }
    chains
}

/// The normal of face `f` of `mesh`, scaled by twice its area.
fn face_normal(mesh: &crate::mesh::TriMesh, f: usize) -> [f64; 3] {
    let [a, b, c] = mesh.faces[f].map(|v| mesh.vertices[v as usize]);
    cross(sub(b, a), sub(c, a))
}

/// The input's face centroids, and the faces by their centroids in cubes of side `cell`.
struct Centroids {
    at: Vec<[f64; 3]>,
    grid: PointGrid,
}

impl Centroids {
    fn new(mesh: &crate::mesh::TriMesh, cell: f64) -> Self {
        let at: Vec<[f64; 3]> = mesh.faces.iter().map(|f| {
            let [a, b, c] = f.map(|v| mesh.vertices[v as usize]);
            [0, 1, 2].map(|k| (a[k] + b[k] + c[k]) / 3.0)
        }).collect();
        let grid = PointGrid::new(cell, at.iter().enumerate().map(|(f, &x)| (f as u32, x)));
        Self { at, grid }
    }
}

/// Whether the input edge `[a, b]` with faces `[f1, f2]` bends at the scale `len`: the
/// area-weighted mean normals of the faces within `len` of its midpoint, on `f1`'s side and on
/// `f2`'s side of the plane through the edge that bisects it, have a cosine below `cos_bound`.
fn bends_at_scale(mesh: &crate::mesh::TriMesh, [a, b]: [u32; 2], [f1, f2]: [usize; 2], centroids: &Centroids, len: f64, cos_bound: f64) -> bool {
    if !(len > 0.0) {
        return true;
    }
    let normal = |f: usize| face_normal(mesh, f);
    let unit = |v: [f64; 3]| {
        let l = norm(v);
        v.map(|c| c / l)
    };
    let (n1, n2) = (unit(normal(f1)), unit(normal(f2)));
    let (xa, xb) = (mesh.vertices[a as usize], mesh.vertices[b as usize]);
    let mid = [0, 1, 2].map(|k| 0.5 * (xa[k] + xb[k]));
    let split = sub(n1, n2);
    let side_of_f1 = dot(sub(centroids.at[f1], mid), split).signum();
    let (mut s1, mut s2) = ([0.0; 3], [0.0; 3]);
    for (f, _) in centroids.grid.near(mid, len) {
        let n = normal(f as usize);
        let s = if dot(sub(centroids.at[f as usize], mid), split).signum() == side_of_f1 { &mut s1 } else { &mut s2 };
        for k in 0..3 {
            s[k] += n[k];
        }
    }
    let l = norm(s1) * norm(s2);
    l > 0.0 && dot(s1, s2) < cos_bound * l
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::TriMesh;

    /// A strip along x of `n` x 2 quads whose cross-section (y, z) is the profile `profile`:
    /// vertex rows at the profile's points, two triangles per quad.
    fn strip(profile: &[[f64; 2]], n: usize) -> TriMesh {
        let m = profile.len();
        let vertices = (0..=n).flat_map(|i| profile.iter().map(move |p| [i as f64 * 0.1, p[0], p[1]])).collect();
        let mut faces = Vec::new();
        for i in 0..n as u32 {
            for j in 0..m as u32 - 1 {
                let (a, b, c, d) = (i * m as u32 + j, i * m as u32 + j + 1, (i + 1) * m as u32 + j, (i + 1) * m as u32 + j + 1);
                faces.push([a, c, b]);
                faces.push([b, c, d]);
            }
        }
        TriMesh::new(vertices, faces)
    }

    /// The faces of `mesh` on either side of its edge `(a, b)`.
    fn sides(mesh: &TriMesh, a: u32, b: u32) -> [usize; 2] {
        let f: Vec<usize> = (0..mesh.faces.len()).filter(|&t| mesh.faces[t].contains(&a) && mesh.faces[t].contains(&b)).collect();
        [f[0], f[1]]
    }
    /// A roof (two planes meeting at 90 degrees) bends at any scale; a staircase of steps
    /// 0.1 wide bends by 90 degrees at each step but not at the scale 1.
    #[test]
    fn a_roof_bends_at_scale_and_a_staircase_does_not() {
        let cos_bound = (SCALE_SHARE * 60f64.to_radians()).cos();
        let roof: Vec<[f64; 2]> = (-10..=10).map(|k| [k as f64 * 0.1, -(k as f64).abs() * 0.1]).collect();
        let mesh = strip(&roof, 40);
        let ridge = (20 * roof.len() + 10) as u32;
        let centroids = Centroids::new(&mesh, 1.0);
        assert!(bends_at_scale(&mesh, [ridge, ridge + roof.len() as u32], sides(&mesh, ridge, ridge + roof.len() as u32), &centroids, 1.0, cos_bound));
        // Steps: up 0.1, across 0.1, up 0.1, ...
        let stairs: Vec<[f64; 2]> = (0..=20).map(|k| [((k + 1) / 2) as f64 * 0.1, (k / 2) as f64 * 0.1]).collect();
        let mesh = strip(&stairs, 40);
        let step = (20 * stairs.len() + 10) as u32;
        let [f1, f2] = sides(&mesh, step, step + stairs.len() as u32);
        let (n1, n2) = (face_normal(&mesh, f1), face_normal(&mesh, f2));
        assert!(dot(n1, n2).abs() < 1e-9 * norm(n1) * norm(n2), "the step itself bends by 90 degrees");
        let centroids = Centroids::new(&mesh, 1.0);
        assert!(!bends_at_scale(&mesh, [step, step + stairs.len() as u32], [f1, f2], &centroids, 1.0, cos_bound));
    }
}
