//! Creases of the input kept by the remesh (ours, with `--keep-creases`; the paper pulls the
//! cap mesh back as is, Sec. 4.2): remesh vertices put on the input's sharp edges and joined
//! along them, as isotropic remeshers with feature edges do. See docs/method.md, "21. Creases".
//!
//! A crease is a chain of input edges whose two faces' normals differ by more than the crease
//! bound, also at the remesh's scale ([`SCALE_SHARE`]). The map is linear on each input face,
//! so an input edge goes onto the segment between its ends' planar points, and a point at a
//! fraction of the edge in the plane lifts to the same fraction of the edge on the surface: a
//! vertex put there lies exactly on the crease. Along each chain long enough at the remesh's
//! scale, points are spaced by about the remesh's edge length; the nearest free remesh vertex
//! of each travels onto it over the iterations (each move kept valid in the plane and on the
//! surface) and stays there, and edge flips join consecutive ones. The flips' crease bound then
//! keeps the joining edges; crease vertices of faces still thin at the end are freed.

use super::smooth::{ring_faces_same_side, ring_valid_in_plane};
use super::state::{third, Incidence, Role, Shaping, SurfaceLift};
use crate::mesh::fasthash::FastMap;
use crate::mesh::geometry::{cross, dot, norm, sub};

/// A chain shorter than this many remesh edge lengths is not kept (a scanned surface's
/// jags and short folds).
const MIN_CHAIN_EDGES: f64 = 3.0;

/// A vertex farther than this many edge lengths from a crease point is not moved onto it.
const REACH: f64 = 0.75;

/// A crease point this close (in edge lengths) to a vertex already on a crease takes that
/// vertex (a junction of chains).
const JUNCTION: f64 = 0.25;

/// A crease point this close (in edge lengths) to a vertex on another crease point gets no
/// vertex.
const CROWDED: f64 = 0.6;

/// A crease vertex of a face whose smallest angle is below this (degrees) at the end of the
/// iterations is freed, for the sliver removal and the moves for shape
/// ([`super::sliver`], [`super::worst`]).
pub(crate) const RELEASE_BELOW_DEG: f64 = 15.0;

/// The vertex of a crease point skipped as crowded.
const SKIPPED: u32 = u32::MAX - 1;

/// Halvings of a taken vertex's move towards its crease point.
const HALVINGS: usize = 5;

/// A point along a crease: planar and surface position.
type CreasePoint = ([f64; 2], [f64; 3]);

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
    let mut creases: Vec<(u32, u32)> = super::state::edge_faces(&mesh.faces)
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

/// Numbered points in cubes of side `cell`, for the points within `cell` of a place.
struct PointGrid {
    cell: f64,
    cubes: FastMap<[i64; 3], Vec<(u32, [f64; 3])>>,
}

impl PointGrid {
    fn new(cell: f64, points: impl IntoIterator<Item = (u32, [f64; 3])>) -> Self {
        let mut cubes: FastMap<[i64; 3], Vec<(u32, [f64; 3])>> = FastMap::default();
        if cell > 0.0 {
            for (i, x) in points {
                cubes.entry(x.map(|c| (c / cell).floor() as i64)).or_default().push((i, x));
            }
        }
        Self { cell, cubes }
    }

    /// The points within `radius` (at most the cell) of `x` and their distances, cube by cube.
    fn near(&self, x: [f64; 3], radius: f64) -> impl Iterator<Item = (u32, f64)> + '_ {
        let c = x.map(|v| (v / self.cell).floor() as i64);
        (0..27)
            .flat_map(move |k| {
                let key = [c[0] + k % 3 - 1, c[1] + (k / 3) % 3 - 1, c[2] + k / 9 - 1];
                self.cubes.get(&key).map_or(&[][..], |l| &l[..]).iter()
            })
            .map(move |&(i, y)| (i, norm(sub(y, x))))
            .filter(move |&(_, d)| d <= radius)
    }
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

/// Points along `chain` spaced by about `len` (both ends included), planar and on the
/// surface; none for a chain shorter than [`MIN_CHAIN_EDGES`] edge lengths.
fn chain_points(lift: &SurfaceLift, chain: &[u32], len: f64) -> Vec<CreasePoint> {
    let inverse = lift.inverse();
    let (x, p) = (&inverse.mesh().vertices, &inverse.map().plane);
    let mut arc = vec![0.0];
    for w in chain.windows(2) {
        let l = norm(sub(x[w[1] as usize], x[w[0] as usize]));
        arc.push(arc.last().copied().unwrap_or(0.0) + l);
    }
    let total = *arc.last().unwrap_or(&0.0);
    if !(total >= MIN_CHAIN_EDGES * len) {
        return Vec::new();
    }
    let n = (total / len).round().max(1.0) as usize;
    let closed = chain.first() == chain.last();
    let count = if closed { n } else { n + 1 };
    (0..count)
        .map(|k| {
            let s = total * k as f64 / n as f64;
            let i = arc.partition_point(|&a| a <= s).saturating_sub(1).min(chain.len() - 2);
            let seg = arc[i + 1] - arc[i];
            let t = if seg > 0.0 { ((s - arc[i]) / seg).clamp(0.0, 1.0) } else { 0.0 };
            let (a, b) = (chain[i] as usize, chain[i + 1] as usize);
            ([0, 1].map(|c| p[a][c] + t * (p[b][c] - p[a][c])), [0, 1, 2].map(|c| x[a][c] + t * (x[b][c] - x[a][c])))
        })
        .collect()
}

/// The crease points of a remesh and the vertex put on each (see the module docs).
pub(crate) struct CreaseSnap {
    /// Each chain's points: planar point, surface point and the vertex on it (`u32::MAX`:
    /// none yet, [`SKIPPED`]: none), and whether the chain is a closed loop.
    runs: Vec<(Vec<(CreasePoint, u32)>, bool)>,
    /// The remesh's edge length.
    len: f64,
}

impl CreaseSnap {
    /// The points along the creases `chains` spaced by about `len` (the remesh's edge length).
    pub(crate) fn new(lift: &SurfaceLift, chains: &[Vec<u32>], len: f64) -> Self {
        let runs = if len > 0.0 {
            chains
                .iter()
                .map(|chain| (chain_points(lift, chain, len).into_iter().map(|p| (p, u32::MAX)).collect::<Vec<_>>(), chain.first() == chain.last()))
                .filter(|(points, _)| !points.is_empty())
                .collect()
        } else {
            Vec::new()
        };
        Self { runs, len }
    }

    /// The vertices of each pair of consecutive crease points (around a closed loop too).
    fn pairs(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        self.runs.iter().flat_map(|(points, closed)| {
            let m = points.len();
            (0..if *closed { m } else { m.saturating_sub(1) }).map(move |k| (points[k].1, points[(k + 1) % m].1))
        })
    }

    /// Consecutive crease points joined by an edge of `mesh`, and all such pairs.
    pub(crate) fn joined(&self, mesh: &Shaping) -> (usize, usize) {
        let around = Around::new(mesh);
        let (mut joined, mut pairs) = (0, 0);
        for (u, w) in self.pairs() {
            pairs += 1;
            joined += usize::from(u < SKIPPED && w < SKIPPED && around.joined(mesh, u, w));
        }
        (joined, pairs)
    }

    /// Vertices on their crease points.
    pub(crate) fn placed(&self, mesh: &Shaping) -> usize {
        self.runs.iter().flat_map(|(points, _)| points).filter(|((q, _), v)| *v < SKIPPED && mesh.plane[*v as usize] == *q).count()
    }

    /// Move free vertices of `mesh` onto the points that have none yet (the nearest whose
    /// faces stay valid; it takes the role [`Role::Crease`]), then join consecutive placed
    /// points by edge flips. Returns the edges flipped.
    pub(crate) fn attempt(&mut self, mesh: &mut Shaping, lift: &SurfaceLift) -> usize {
        let len = self.len;
        if self.runs.is_empty() {
            return 0;
        }
        let incidence: Incidence = mesh.incidence();
        // Free vertices with faces (a collapsed vertex has none).
        let free = (0..mesh.plane.len()).filter(|&v| mesh.role[v] == Role::Free && mesh.planar(v as u32) && !incidence.of(v).is_empty());
        let grid = PointGrid::new(len, free.map(|v| (v as u32, mesh.position[v])));
        // The points that have a vertex, and it (judged by the point: the vertex may still
        // be on its way).
        let mut placed: Vec<([f64; 3], u32)> = self.runs.iter().flat_map(|(points, _)| points).filter(|(_, v)| *v < SKIPPED).map(|((_, x), v)| (*x, *v)).collect();
        for (points, _) in &mut self.runs {
            for ((_, x), at) in points.iter_mut() {
                if *at != u32::MAX {
                    continue;
                }
                // A junction shared with another chain: the vertex already there. A point
                // crowded by another crease's vertex (parallel creases closer than an edge
                // length, points next to a junction) is skipped for good.
                let nearest = placed.iter().map(|&(y, v)| (norm(sub(y, *x)), v)).min_by(|a, b| a.0.total_cmp(&b.0));
                match nearest {
                    Some((d, v)) if d < JUNCTION * len => {
                        *at = v;
                        continue;
                    }
                    Some((d, _)) if d < CROWDED * len => {
                        *at = SKIPPED;
                        continue;
                    }
                    _ => {}
                }
                // The nearest vertex still free is taken; it travels onto the point over the
                // iterations (see below).
                let nearest = grid.near(*x, REACH * len).filter(|&(v, _)| mesh.role[v as usize] == Role::Free).min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
                if let Some((v, _)) = nearest {
                    mesh.role[v as usize] = Role::Crease;
                    placed.push((*x, v));
                    *at = v;
                }
            }
        }
        // Each taken vertex moves onto its point, or as far towards it as its faces allow
        // (halving the move; it stays on the surface, lifted through the map). A vertex
        // shared at a junction goes to its first point.
        let mut seen = vec![false; mesh.plane.len()];
        for (points, _) in &self.runs {
            for &((q, x), v) in points {
                if v >= SKIPPED || std::mem::replace(&mut seen[v as usize], true) || mesh.plane[v as usize] == q {
                    continue;
                }
                let (v, q0) = (v as usize, mesh.plane[v as usize]);
                let ring = incidence.of(v);
                let mut step = 1.0;
                for _ in 0..=HALVINGS {
                    let p = [q0[0] + step * (q[0] - q0[0]), q0[1] + step * (q[1] - q0[1])];
                    let lifted = if step == 1.0 { Some((x, mesh.hint[v])) } else { lift.lift(p, mesh.hint[v]) };
                    if let Some((y, h)) = lifted {
                        if ring_valid_in_plane(mesh, ring, v, p) && ring_faces_same_side(mesh, ring, v, y) {
                            mesh.plane[v] = p;
                            mesh.position[v] = y;
                            mesh.hint[v] = h;
                            break;
                        }
                    }
                    step *= 0.5;
                }
            }
        }
        let mut flips = 0;
        let mut around = Around::new(mesh);
        for (u, w) in self.pairs() {
            if u < SKIPPED && w < SKIPPED && u != w && !around.joined(mesh, u, w) {
                flips += join(mesh, &mut around, u, w);
            }
        }
        flips
    }
}

/// Free the crease vertices of the faces of `mesh` below [`RELEASE_BELOW_DEG`]: a thin face
/// costs more than a point off the crease. Returns the vertices freed.
pub(crate) fn release_thin(mesh: &mut Shaping) -> usize {
    let thin = super::state::thin_face_vertices(mesh, RELEASE_BELOW_DEG.to_radians(), |v| mesh.role[v as usize] == Role::Crease);
    for &v in &thin {
        mesh.role[v as usize] = Role::Free;
    }
    thin.len()
}

/// Flips tried to join two crease points.
const MAX_JOIN_FLIPS: usize = 8;

/// The faces around each vertex, kept up to date through the joining flips.
struct Around(Vec<Vec<u32>>);

impl Around {
    fn new(mesh: &Shaping) -> Self {
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
    fn joined(&self, mesh: &Shaping, u: u32, w: u32) -> bool {
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
/// crosses, each only when both its new faces are oriented in the plane (so the planar mesh
/// stays an embedding). Returns the flips made.
fn join(mesh: &mut Shaping, around: &mut Around, u: u32, w: u32) -> usize {
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
        let mut mesh = Shaping { faces, plane, position, hint: vec![u32::MAX; n], role: vec![Role::Free; n], has_plane: vec![true; n], orientation: 1.0 };
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
