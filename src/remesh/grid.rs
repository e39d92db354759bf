//! Meshes of the cap to pull back onto the surface (paper Sec. 4.2): a uniform, well-shaped
//! triangle mesh with about `N` faces, or a latitude/longitude mesh.

use crate::mesh::shapes::{lat_long_cap, spherical_cap, spherical_cap_sectors};
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
