//! Meshes of the cap to pull back onto the surface (paper Sec. 4.2): a uniform, well-shaped
//! triangle mesh with about `N` faces, or a latitude/longitude mesh.

use crate::mesh::shapes::{flat_disk_below, lat_long_cap, spherical_cap, spherical_cap_sectors};
use crate::mesh::TriMesh;

/// The uniform cap mesh of [`spherical_cap`] (rings equally spaced in polar angle, ring sizes
/// growing with the circumference: near-equilateral faces of near-equal area) whose face
/// count is closest to `target_faces`.
pub fn uniform_cap(z_star: f64, target_faces: usize) -> TriMesh {
    let make = |rings: usize| spherical_cap(z_star, rings, spherical_cap_sectors(z_star, rings));
    // Face count grows like rings^2: bracket, then bisect on rings.
    let (mut lo, mut hi) = (1usize, 2usize);
    while make(hi).n_faces() < target_faces && hi < 4096 {
        lo = hi;
        hi *= 2;
    }
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        if make(mid).n_faces() < target_faces {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let (a, b) = (make(lo), make(hi));
    let err = |m: &TriMesh| (m.n_faces() as f64 - target_faces as f64).abs();
    if err(&a) <= err(&b) {
        a
    } else {
        b
    }
}

/// The latitude/longitude cap mesh ([`lat_long_cap`]).
pub fn lat_long(z_star: f64, rings: usize, sectors: usize) -> TriMesh {
    lat_long_cap(z_star, rings, sectors)
}

/// A cap mesh closed by a flat bottom disk (for closed surfaces, whose punctured quad maps
/// to the bottom, paper Sec. 3.2.3).
#[derive(Debug, Clone)]
pub struct ClosedCapGrid {
    /// The cap mesh and the bottom disk, sharing the rim: a closed genus-0 mesh.
    pub mesh: TriMesh,
    /// Vertices from this index on are inside the bottom disk (the rim belongs to the cap).
    pub first_bottom_vertex: usize,
}

/// Close `cap` (a mesh of [`uniform_cap`] or [`lat_long`], whose rim ring is laid out last)
/// with a flat disk at the rim's height ([`flat_disk_below`]).
pub fn close_bottom(cap: TriMesh) -> ClosedCapGrid {
    let n = cap.vertices.len();
    let z_rim = cap.vertices.last().map_or(0.0, |p| p[2]);
    let rim = cap.vertices.iter().rev().take_while(|p| p[2] == z_rim).count();
    let first_rim = n - rim;
    let radius = cap.vertices.get(first_rim).map_or(0.0, |p| p[0].hypot(p[1]));
    let disk = flat_disk_below(z_rim, radius, rim);
    // The disk's rim is its last `rim` vertices, at the same angles as the cap's rim.
    let disk_rim_start = disk.vertices.len() - rim;
    let renumber = |v: u32| -> u32 {
        let v = v as usize;
        if v >= disk_rim_start {
            (first_rim + (v - disk_rim_start)) as u32
        } else {
            (n + v) as u32
        }
    };
    let mut vertices = cap.vertices;
    vertices.extend_from_slice(&disk.vertices[..disk_rim_start]);
    let mut faces = cap.faces;
    faces.extend(disk.faces.iter().map(|f| f.map(renumber)));
    ClosedCapGrid { mesh: TriMesh::new(vertices, faces), first_bottom_vertex: n }
}
