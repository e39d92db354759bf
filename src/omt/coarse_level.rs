//! A coarse transport problem for the radius search (speed; paper Sec. 3.1.2, Eq. 12).
//!
//! The radius search evaluates the conformal energy of `h_r o r g` at a dozen radii, each a
//! full transport solve; on large meshes that is most of the parameterization's time. Here the
//! search runs on a subset of the transport sites instead, in the spirit of Mérigot's
//! multiscale transport (Mérigot 2011, "A multiscale approach to optimal transport"):
//!
//! - **Coarse sites**: a greedy covering of the mesh graph by `h`-hop balls, every boundary
//!   vertex (rim vertex, or puncture corner) a site, `h` the smallest that leaves at most the
//!   requested number of sites. They are vertices of the initial disk map, so they are
//!   distinct and spread evenly over the surface rather than over the distorted disk map.
//! - **Prolongation** `P`: each vertex's barycentric coordinates in the Delaunay
//!   triangulation of the coarse sites in the disk map (invariant under the radius scaling).
//! - **Restriction**: the coarse target masses are `P^T tau`, so they sum to the fine ones.
//!
//! Each radius is then solved on the coarse sites, its centroid map carried to every vertex
//! by `P`, and the conformal energy (Eq. 12) measured on the full mesh. Only `r*` is solved at
//! full resolution, from the Voronoi diagram: the coarse weights interpolated by `P` (or any
//! fraction of them down to 1/8) make some sites redundant on the hand, which the transport
//! solver's flips cannot represent (measured and dropped).

use crate::mesh::geometry::signed_area_2d;
use crate::mesh::topology::neighbors_of_faces;
use super::triangulation::Site;
use spade::{DelaunayTriangulation, Point2, PositionInTriangulation, Triangulation};

/// Coarse sites, their target masses and the map from coarse to fine positions.
#[derive(Debug, Clone)]
pub struct CoarseLevel {
    /// Disk-map positions of the coarse sites (a subset of the fine sites).
    pub sites: Vec<[f64; 2]>,
    /// Whether each coarse site is a boundary vertex.
    pub on_boundary: Vec<bool>,
    /// Target masses `P^T tau` of the coarse sites.
    pub masses: Vec<f64>,
    /// Per fine vertex, up to three `(coarse site, weight)` pairs (unused slots weigh 0).
    prolongation: Vec<[(u32, f64); 3]>,
    /// The radius `h` of the covering's balls.
    hops: usize,
}

impl CoarseLevel {
    /// The coarse level of the transport problem with sites `disk_map` (one per vertex of
    /// `faces`), boundary flags and target masses, with at most about `max_sites` sites
    /// (never fewer than the boundary vertices). `None` when the sites cannot be triangulated
    /// or no covering is smaller than the mesh.
    pub fn build(disk_map: &[[f64; 2]], faces: &[[u32; 3]], on_boundary: &[bool], target: &[f64], max_sites: usize) -> Option<Self> {
        let neighbors = neighbors_of_faces(disk_map.len(), faces);
        let mut seeds = Vec::new();
        let mut hops = 1;
        for h in 1..=MAX_HOPS {
            (seeds, hops) = (cover(&neighbors, on_boundary, h), h);
            if seeds.len() <= max_sites.max(on_boundary.iter().filter(|b| **b).count()) {
                break;
            }
        }
        Self::from_seeds(disk_map, on_boundary, target, seeds, hops)
    }

    /// The level of the same problem on the covering by the largest balls that give more
    /// sites than this level (one hop less: about two to three times the sites), if that is
    /// fewer than half the vertices; `None` otherwise, or from a covering by 1-hop balls: the
    /// next level is the full problem.
    pub fn finer(&self, disk_map: &[[f64; 2]], faces: &[[u32; 3]], on_boundary: &[bool], target: &[f64]) -> Option<Self> {
        let neighbors = neighbors_of_faces(disk_map.len(), faces);
        let (hops, seeds) = (1..self.hops).rev().map(|h| (h, cover(&neighbors, on_boundary, h))).find(|(_, seeds)| seeds.len() > self.len())?;
        if 2 * seeds.len() >= disk_map.len() {
            return None;
        }
        Self::from_seeds(disk_map, on_boundary, target, seeds, hops)
    }

    /// The level on the covering `seeds` by `hops`-hop balls.
    fn from_seeds(disk_map: &[[f64; 2]], on_boundary: &[bool], target: &[f64], seeds: Vec<u32>, hops: usize) -> Option<Self> {
        let n = disk_map.len();
        if seeds.len() >= n || seeds.len() < 3 {
            return None;
        }
        let elems: Vec<Site> = seeds.iter().enumerate().map(|(k, &v)| Site { p: point(disk_map[v as usize]), id: k as u32 }).collect();
        let dt: DelaunayTriangulation<Site> = DelaunayTriangulation::bulk_load(elems).ok()?;
        if dt.num_vertices() != seeds.len() {
            return None;
        }
        let mut coarse_of = vec![u32::MAX; n];
        for (k, &v) in seeds.iter().enumerate() {
            coarse_of[v as usize] = k as u32;
        }
        let prolongation: Vec<[(u32, f64); 3]> = (0..n)
            .map(|i| {
                if coarse_of[i] != u32::MAX {
                    return [(coarse_of[i], 1.0), (0, 0.0), (0, 0.0)];
                }
                let q = disk_map[i];
                match dt.locate(point(q)) {
                    PositionInTriangulation::OnVertex(v) => [(dt.vertex(v).data().id, 1.0), (0, 0.0), (0, 0.0)],
                    PositionInTriangulation::OnFace(f) => {
                        let v = dt.face(f).vertices();
                        let p = v.map(|x| [x.position().x, x.position().y]);
                        let l = barycentric(p, q);
                        [(v[0].data().id, l[0]), (v[1].data().id, l[1]), (v[2].data().id, l[2])]
                    }
                    PositionInTriangulation::OnEdge(e) => {
                        let [a, b] = dt.directed_edge(e).vertices();
                        let (pa, pb) = ([a.position().x, a.position().y], [b.position().x, b.position().y]);
                        let t = segment_parameter(pa, pb, q);
                        [(a.data().id, 1.0 - t), (b.data().id, t), (0, 0.0)]
                    }
                    _ => {
                        let v = dt.nearest_neighbor(point(q)).map_or(0, |v| v.data().id);
                        [(v, 1.0), (0, 0.0), (0, 0.0)]
                    }
                }
            })
            .collect();
        let mut masses = vec![0.0; seeds.len()];
        for (i, row) in prolongation.iter().enumerate() {
            for &(c, w) in row {
                masses[c as usize] += w * target[i];
            }
        }
        let sites = seeds.iter().map(|&v| disk_map[v as usize]).collect();
        let on_boundary = seeds.iter().map(|&v| on_boundary[v as usize]).collect();
        Some(Self { sites, on_boundary, masses, prolongation, hops })
    }

    /// Number of coarse sites.
    pub fn len(&self) -> usize {
        self.sites.len()
    }

    /// Positions of every fine vertex from positions of the coarse sites (`P x`).
    pub fn prolong(&self, coarse: &[[f64; 2]]) -> Vec<[f64; 2]> {
        self.prolongation
            .iter()
            .map(|row| {
                let mut p = [0.0; 2];
                for &(c, w) in row {
                    p[0] += w * coarse[c as usize][0];
                    p[1] += w * coarse[c as usize][1];
                }
                p
            })
            .collect()
    }
}

/// Largest ball radius of the covering tried.
const MAX_HOPS: usize = 64;

/// Greedy covering: every boundary vertex, then each vertex (in index order) not within
/// `hops` edges of an earlier site.
fn cover(neighbors: &[Vec<u32>], on_boundary: &[bool], hops: usize) -> Vec<u32> {
    let n = neighbors.len();
    let mut depth = vec![usize::MAX; n];
    let mut seeds = Vec::new();
    let mut frontier = Vec::new();
    let mut next = Vec::new();
    let mut mark = |s: u32, depth: &mut Vec<usize>, seeds: &mut Vec<u32>| {
        seeds.push(s);
        depth[s as usize] = 0;
        frontier.clear();
        frontier.push(s);
        for d in 1..=hops {
            next.clear();
            for &v in &frontier {
                for &u in &neighbors[v as usize] {
                    if depth[u as usize] > d {
                        depth[u as usize] = d;
                        next.push(u);
                    }
                }
            }
            std::mem::swap(&mut frontier, &mut next);
        }
    };
    for v in 0..n {
        if on_boundary[v] {
            mark(v as u32, &mut depth, &mut seeds);
        }
    }
    for v in 0..n {
        if depth[v] == usize::MAX && !neighbors[v].is_empty() {
            mark(v as u32, &mut depth, &mut seeds);
        }
    }
    seeds
}

fn point(p: [f64; 2]) -> Point2<f64> {
    Point2::new(p[0], p[1])
}

/// Barycentric coordinates of `q` in the triangle `p`, clamped to be non-negative.
fn barycentric(p: [[f64; 2]; 3], q: [f64; 2]) -> [f64; 3] {
    let total = signed_area_2d(p[0], p[1], p[2]);
    let mut l = [signed_area_2d(q, p[1], p[2]), signed_area_2d(p[0], q, p[2]), signed_area_2d(p[0], p[1], q)].map(|x| (x / total).max(0.0));
    let s: f64 = l.iter().sum();
    if !(s > 0.0 && total != 0.0) {
        return [1.0, 0.0, 0.0];
    }
    l.iter_mut().for_each(|x| *x /= s);
    l
}

/// Parameter `t` of the projection of `q` onto the segment `a b`, clamped to `[0, 1]`.
fn segment_parameter(a: [f64; 2], b: [f64; 2], q: [f64; 2]) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1]];
    let len2 = d[0] * d[0] + d[1] * d[1];
    if len2 == 0.0 {
        return 0.0;
    }
    (((q[0] - a[0]) * d[0] + (q[1] - a[1]) * d[1]) / len2).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::geometry::vertex_areas;
    use crate::mesh::shapes::grid_disk;
    use crate::mesh::topology::{is_boundary_vertex, within_rings};

    fn disk_level(rings: usize, max_sites: usize) -> (crate::mesh::TriMesh, Vec<[f64; 2]>, Vec<bool>, Vec<f64>, CoarseLevel) {
        let mesh = grid_disk(rings);
        let plane: Vec<[f64; 2]> = mesh.vertices.iter().map(|p| [p[0], p[1]]).collect();
        let boundary = is_boundary_vertex(&mesh);
        let target = vertex_areas(&mesh.vertices, &mesh.faces);
        let level = CoarseLevel::build(&plane, &mesh.faces, &boundary, &target, max_sites).expect("coarse level");
        (mesh, plane, boundary, target, level)
    }

    #[test]
    fn covering_keeps_the_boundary_and_respects_the_size() {
        let (mesh, _, boundary, _, level) = disk_level(40, 600);
        let rim = boundary.iter().filter(|b| **b).count();
        assert!(level.len() <= 600 && level.len() > rim, "{} sites, {} on the rim", level.len(), rim);
        assert!(level.len() < mesh.n_vertices() / 4);
        // Every boundary vertex is a site, flagged as such.
        assert_eq!(level.on_boundary.iter().filter(|b| **b).count(), rim);
        // The covering the level is built on: every boundary vertex is a seed, and every
        // vertex is within `hops` edges of one.
        let neighbors = neighbors_of_faces(mesh.n_vertices(), &mesh.faces);
        for hops in 1..=4 {
            let seeds = cover(&neighbors, &boundary, hops);
            let mut is_site = vec![false; mesh.n_vertices()];
            seeds.iter().for_each(|&v| is_site[v as usize] = true);
            assert!(boundary.iter().zip(&is_site).all(|(b, s)| !b || *s), "hops {hops}: a boundary vertex is not a seed");
            assert!(within_rings(&is_site, &mesh.faces, hops).iter().all(|&w| w), "hops {hops}: a vertex is farther from every seed");
        }
    }

    #[test]
    fn prolongation_reproduces_linear_functions_and_restriction_keeps_mass() {
        let (_, plane, _, target, level) = disk_level(30, 400);
        // Barycentric interpolation is exact for linear maps: the coarse sites' own positions
        // come back as every vertex's position (all vertices lie in the coarse sites' hull,
        // whose corners are the rim vertices).
        let back = level.prolong(&level.sites);
        for (p, q) in back.iter().zip(&plane) {
            assert!((p[0] - q[0]).abs() < 1e-12 && (p[1] - q[1]).abs() < 1e-12, "{p:?} vs {q:?}");
        }
        let affine: Vec<[f64; 2]> = level.sites.iter().map(|p| [2.0 * p[0] - p[1] + 0.3, 0.5 * p[1] - 1.0]).collect();
        for (p, q) in level.prolong(&affine).iter().zip(&plane) {
            assert!((p[0] - (2.0 * q[0] - q[1] + 0.3)).abs() < 1e-12 && (p[1] - (0.5 * q[1] - 1.0)).abs() < 1e-12);
        }
        let (fine, coarse): (f64, f64) = (target.iter().sum(), level.masses.iter().sum());
        assert!((fine - coarse).abs() < 1e-12 * fine, "{fine} vs {coarse}");
        assert!(level.masses.iter().all(|m| *m > 0.0));
    }

    /// Each finer level covers by smaller balls, so it has more sites, until the
    /// next would hold half the vertices: then the full problem is next (`None`).
    #[test]
    fn finer_levels_have_more_sites_down_to_the_full_problem() {
        let (mesh, plane, boundary, target, level) = disk_level(60, 1000);
        assert!(level.hops >= 3, "{} hops", level.hops);
        let mut levels = vec![level];
        while let Some(next) = levels.last().unwrap().finer(&plane, &mesh.faces, &boundary, &target) {
            levels.push(next);
        }
        for pair in levels.windows(2) {
            assert!(pair[1].hops < pair[0].hops);
            assert!(pair[1].len() > pair[0].len(), "{} then {} sites", pair[0].len(), pair[1].len());
        }
        let last = levels.last().unwrap();
        assert!(2 * last.len() < mesh.n_vertices());
        let masses: f64 = last.masses.iter().sum();
        assert!((masses - target.iter().sum::<f64>()).abs() < 1e-12 * masses);
    }

    #[test]
    fn no_level_when_every_vertex_is_a_site() {
        // A fan of four triangles: all five vertices are on the boundary.
        let plane = [[0.0, 0.0], [1.0, 0.0], [0.5, 1.0], [-0.5, 1.0], [-1.0, 0.0]];
        let faces = [[0, 1, 2], [0, 2, 3], [0, 3, 4]];
        let boundary = [true; 5];
        assert!(CoarseLevel::build(&plane, &faces, &boundary, &[1.0; 5], 2).is_none());
    }
}
