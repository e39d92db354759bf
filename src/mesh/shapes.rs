//! Procedural meshes for tests and benchmarks: a spherical cap, three spheres (one folded), a
//! planar disk, an annulus and a torus. All faces are counter-clockwise seen from outside (closed surfaces),
//! from the sphere's outside (cap) or from `+z` (planar shapes).
//!
//! Parameters are clamped to sensible ranges instead of panicking; each function documents how,
//! and ring and sector counts are at most [`MAX_RINGS`] and [`MAX_SECTORS`] (so that vertex
//! indices fit in `u32`).

use std::collections::HashMap;
use std::f64::consts::{PI, TAU};

use crate::mesh::geometry::{dot, norm, scale, sub};
use crate::mesh::TriMesh;

/// Largest number of rings (radial subdivisions) any shape accepts.
pub const MAX_RINGS: usize = 10_000;

/// Largest number of sectors (vertices around a ring) any shape accepts.
pub const MAX_SECTORS: usize = 100_000;

/// A circle of vertices `z = const` (or a single pole vertex when `count == 1`).
struct Ring {
    z: f64,
    radius: f64,
    count: usize,
}

/// Vertex indices of consecutive rings laid out one after the other.
fn push_ring(vertices: &mut Vec<[f64; 3]>, ring: &Ring) -> Vec<u32> {
    let start = vertices.len() as u32;
    for j in 0..ring.count {
        let phi = TAU * j as f64 / ring.count as f64;
        vertices.push([ring.radius * phi.cos(), ring.radius * phi.sin(), ring.z]);
    }
    (start..start + ring.count as u32).collect()
}

/// Triangulate the band between an `inner` ring (closer to the pole / centre) and an `outer`
/// ring, both with increasing angle and a vertex at angle 0. Chooses the shorter diagonal at
/// each step. A ring of one vertex gives a fan. Triangles are counter-clockwise seen from the
/// side where the angle increases counter-clockwise (outside of a sphere, `+z` for the plane).
fn stitch(vertices: &[[f64; 3]], inner: &[u32], outer: &[u32], faces: &mut Vec<[u32; 3]>) {
    let (na, nb) = (inner.len(), outer.len());
    if na == 0 || nb == 0 {
        return;
    }
    let dist = |p: u32, q: u32| norm(sub(vertices[p as usize], vertices[q as usize]));
    let (steps_a, steps_b) = (if na == 1 { 0 } else { na }, if nb == 1 { 0 } else { nb });
    let (mut i, mut k) = (0usize, 0usize);
    while i < steps_a || k < steps_b {
        let (a, a1) = (inner[i % na], inner[(i + 1) % na]);
        let (b, b1) = (outer[k % nb], outer[(k + 1) % nb]);
        let advance_inner = if k == steps_b {
            true
        } else if i == steps_a {
            false
        } else {
            dist(a1, b) <= dist(a, b1)
        };
        if advance_inner {
            faces.push([a, b, a1]);
            i += 1;
        } else {
            faces.push([a, b, b1]);
            k += 1;
        }
    }
}

/// Mesh from a stack of rings, top to bottom (pole rings have `count == 1`).
fn ring_stack(rings: &[Ring]) -> TriMesh {
    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    let mut previous: Option<Vec<u32>> = None;
    for ring in rings {
        let ids = push_ring(&mut vertices, ring);
        if let Some(prev) = &previous {
            stitch(&vertices, prev, &ids, &mut faces);
        }
        previous = Some(ids);
    }
    TriMesh::new(vertices, faces)
}

/// Recommended `sectors` for [`spherical_cap`]: near-equilateral triangles of near-uniform
/// area for the given `z0` and `rings`.
pub fn spherical_cap_sectors(z0: f64, rings: usize) -> usize {
    let z0 = clamp_z0(z0);
    let rings = rings.clamp(1, MAX_RINGS);
    let theta_max = z0.acos();
    let max_sin = if theta_max >= PI / 2.0 {
        1.0
    } else {
        theta_max.sin()
    };
    ((TAU * max_sin * rings as f64 / theta_max).round() as usize).max(3)
}

fn clamp_z0(z0: f64) -> f64 {
    if z0.is_nan() {
        0.0
    } else {
        z0.clamp(-1.0 + 1e-9, 1.0 - 1e-9)
    }
}

/// The part of the unit sphere with `z >= z0`: a vertex at the pole `(0, 0, 1)`, then `rings`
/// rings equally spaced in polar angle, the last one at `z = z0` exactly (the boundary).
///
/// Ring `i` gets `max(3, round(sectors * sin(theta_i) / max_sin))` vertices, where `max_sin` is
/// the largest `sin(theta)` over the rings: the counts grow with the circumference, so with
/// `sectors` = [`spherical_cap_sectors`]`(z0, rings)` the triangles are near-equilateral and of
/// near-uniform area. `z0` is clamped to `(-1, 1)`, `rings >= 1`, `sectors >= 3`.
pub fn spherical_cap(z0: f64, rings: usize, sectors: usize) -> TriMesh {
    let z0 = clamp_z0(z0);
    let rings = rings.clamp(1, MAX_RINGS);
    let sectors = sectors.clamp(3, MAX_SECTORS);
    let theta_max = z0.acos();
    let theta = |i: usize| theta_max * i as f64 / rings as f64;
    let max_sin = (1..=rings).map(|i| theta(i).sin()).fold(0.0f64, f64::max);
    let mut stack = vec![Ring {
        z: 1.0,
        radius: 0.0,
        count: 1,
    }];
    for i in 1..=rings {
        let (z, radius) = if i == rings {
            (z0, ((1.0 - z0) * (1.0 + z0)).sqrt())
        } else {
            (theta(i).cos(), theta(i).sin())
        };
        let count = ((sectors as f64 * theta(i).sin() / max_sin).round() as usize).max(3);
        stack.push(Ring { z, radius, count });
    }
    ring_stack(&stack)
}

/// Closed unit sphere from `rings` latitude bands (`>= 2`) of `sectors` vertices (`>= 3`),
/// with a vertex at each pole.
pub fn uv_sphere(rings: usize, sectors: usize) -> TriMesh {
    let rings = rings.clamp(2, MAX_RINGS);
    let sectors = sectors.clamp(3, MAX_SECTORS);
    let mut stack = vec![Ring {
        z: 1.0,
        radius: 0.0,
        count: 1,
    }];
    for i in 1..rings {
        let theta = PI * i as f64 / rings as f64;
        stack.push(Ring {
            z: theta.cos(),
            radius: theta.sin(),
            count: sectors,
        });
    }
    stack.push(Ring {
        z: -1.0,
        radius: 0.0,
        count: 1,
    });
    ring_stack(&stack)
}

/// The regular icosahedron inscribed in the unit sphere, faces oriented outwards.
fn icosahedron() -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let phi = (1.0 + 5f64.sqrt()) / 2.0;
    let mut vertices: Vec<[f64; 3]> = Vec::new();
    for s1 in [-1.0, 1.0] {
        for s2 in [-phi, phi] {
            vertices.push([0.0, s1, s2]);
            vertices.push([s1, s2, 0.0]);
            vertices.push([s2, 0.0, s1]);
        }
    }
    // Faces: triples of mutually adjacent vertices (edge length 2), oriented outwards.
    let n = vertices.len();
    let adjacent = |i: usize, j: usize| {
        let d = sub(vertices[i], vertices[j]);
        (dot(d, d) - 4.0).abs() < 1e-9
    };
    let mut faces = Vec::new();
    for i in 0..n {
        for j in i + 1..n {
            for k in j + 1..n {
                if adjacent(i, j) && adjacent(j, k) && adjacent(i, k) {
                    let (a, b, c) = (vertices[i], vertices[j], vertices[k]);
                    let normal = crate::mesh::geometry::cross(sub(b, a), sub(c, a));
                    let outward = dot(normal, a) > 0.0;
                    let face = if outward { [i, j, k] } else { [i, k, j] };
                    faces.push(face.map(|v| v as u32));
                }
            }
        }
    }
    (vertices.iter().map(|&p| scale(p, 1.0 / norm(p))).collect(), faces)
}

/// Closed unit sphere: an icosahedron subdivided `subdivisions` times (each face into four),
/// `20 * 4^s` faces. `subdivisions` is clamped to at most 9.
pub fn icosphere(subdivisions: usize) -> TriMesh {
    let (mut vertices, mut faces) = icosahedron();
    for _ in 0..subdivisions.min(9) {
        let mut midpoint: HashMap<(u32, u32), u32> = HashMap::new();
        let mut mid = |a: u32, b: u32, vertices: &mut Vec<[f64; 3]>| {
            *midpoint.entry((a.min(b), a.max(b))).or_insert_with(|| {
                let p = crate::mesh::geometry::add(vertices[a as usize], vertices[b as usize]);
                vertices.push(scale(p, 1.0 / norm(p)));
                (vertices.len() - 1) as u32
            })
        };
        let mut next = Vec::with_capacity(faces.len() * 4);
        for &[a, b, c] in &faces {
            let ab = mid(a, b, &mut vertices);
            let bc = mid(b, c, &mut vertices);
            let ca = mid(c, a, &mut vertices);
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        faces = next;
    }
    TriMesh::new(vertices, faces)
}

/// Most frequency of [`geodesic_sphere`] (20 million faces).
pub const MAX_GEODESIC_FREQUENCY: usize = 1000;

/// Closed unit sphere: every face of an icosahedron split into `frequency^2` triangles by a
/// grid of `frequency` steps along each side, the grid points projected onto the sphere
/// (a class I geodesic sphere). `10 f^2 + 2` vertices and `20 f^2` faces for any frequency
/// `f` (clamped to `1..=MAX_GEODESIC_FREQUENCY`), where [`icosphere`] has only powers of 4.
pub fn geodesic_sphere(frequency: usize) -> TriMesh {
    let f = frequency.clamp(1, MAX_GEODESIC_FREQUENCY);
    let (corners, ico_faces) = icosahedron();
    let mut vertices = corners.clone();
    // Points inside an icosahedron edge (a, b), a < b, numbered from a.
    let mut edge_points: HashMap<(u32, u32), Vec<u32>> = HashMap::new();
    let mut faces = Vec::with_capacity(20 * f * f);
    let on_sphere = |p: [f64; 3]| scale(p, 1.0 / norm(p));
    for &[a, b, c] in &ico_faces {
        let [pa, pb, pc] = [a, b, c].map(|v| corners[v as usize]);
        // The point with `i` steps towards b and `j` towards c: index in `vertices`.
        let mut grid = vec![0u32; (f + 1) * (f + 2) / 2];
        let at = |i: usize, j: usize| i * (2 * f + 3 - i) / 2 + j;
        for i in 0..=f {
            for j in 0..=f - i {
                let k = f - i - j;
                let index = match (i, j, k) {
                    (0, 0, _) => a,
                    (_, 0, 0) => b,
                    (0, _, 0) => c,
                    _ => {
                        // On a side of the icosahedron face: shared with the neighbour.
                        let side = if j == 0 { Some((a, b, i)) } else if i == 0 { Some((a, c, j)) } else if k == 0 { Some((b, c, j)) } else { None };
                        match side {
                            Some((u, v, t)) => {
                                let (lo, hi, t) = if u < v { (u, v, t) } else { (v, u, f - t) };
                                let points = edge_points.entry((lo, hi)).or_insert_with(|| {
                                    let (p, q) = (corners[lo as usize], corners[hi as usize]);
                                    (1..f)
                                        .map(|s| {
                                            let w = s as f64 / f as f64;
                                            vertices.push(on_sphere([0, 1, 2].map(|d| (1.0 - w) * p[d] + w * q[d])));
                                            (vertices.len() - 1) as u32
                                        })
                                        .collect()
                                });
                                points[t - 1]
                            }
                            None => {
                                let (wb, wc) = (i as f64 / f as f64, j as f64 / f as f64);
                                vertices.push(on_sphere([0, 1, 2].map(|d| (1.0 - wb - wc) * pa[d] + wb * pb[d] + wc * pc[d])));
                                (vertices.len() - 1) as u32
                            }
                        }
                    }
                };
                grid[at(i, j)] = index;
            }
        }
        // Triangles of the grid, oriented like (a, b, c).
        for i in 0..f {
            for j in 0..f - i {
                faces.push([grid[at(i, j)], grid[at(i + 1, j)], grid[at(i, j + 1)]]);
                if i + j + 1 < f {
                    faces.push([grid[at(i + 1, j)], grid[at(i + 1, j + 1)], grid[at(i, j + 1)]]);
                }
            }
        }
    }
    TriMesh::new(vertices, faces)
}

/// A folded (cortex-like) closed surface on the [`geodesic_sphere`] of `frequency`: the radius
/// `1 + 0.12 sum_i sin(9 d_i . p + 2.4 i) / sqrt(12)` over twelve directions `d_i` on a
/// Fibonacci spiral of the sphere (gyri and sulci about 0.7 apart, radius 0.74-1.28 at
/// frequency 114), then axes (1, 0.75, 0.6). Genus 0 (a radial graph over the sphere).
pub fn folded_sphere(frequency: usize) -> TriMesh {
    const WAVES: usize = 12;
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let directions: Vec<[f64; 3]> = (0..WAVES)
        .map(|i| {
            let z = 1.0 - (2 * i + 1) as f64 / WAVES as f64;
            let (s, t) = ((1.0 - z * z).sqrt(), golden * i as f64);
            [s * t.cos(), s * t.sin(), z]
        })
        .collect();
    let mut mesh = geodesic_sphere(frequency);
    for p in &mut mesh.vertices {
        let sum: f64 = directions.iter().enumerate().map(|(i, d)| (9.0 * (d[0] * p[0] + d[1] * p[1] + d[2] * p[2]) + 2.4 * i as f64).sin()).sum();
        let r = 1.0 + 0.12 * sum / (WAVES as f64).sqrt();
        *p = [r * p[0], 0.75 * r * p[1], 0.6 * r * p[2]];
    }
    mesh
}

/// Planar unit disk in `z = 0`: a centre vertex and `n` concentric rings (ring `i` has radius
/// `i / n` and `6 i` vertices), near-equilateral triangles, counter-clockwise seen from `+z`.
/// `n >= 1`.
pub fn grid_disk(n: usize) -> TriMesh {
    let n = n.clamp(1, MAX_RINGS);
    let mut stack = vec![Ring {
        z: 0.0,
        radius: 0.0,
        count: 1,
    }];
    for i in 1..=n {
        stack.push(Ring {
            z: 0.0,
            radius: i as f64 / n as f64,
            count: 6 * i,
        });
    }
    ring_stack(&stack)
}

/// Planar annulus in `z = 0` between `inner_radius` and `outer_radius`, with `rings` radial
/// bands (`>= 1`) and `sectors` vertices per circle (`>= 3`), counter-clockwise seen from `+z`.
/// Two boundary loops. A non-positive or non-finite `inner_radius` becomes 0.5; an
/// `outer_radius` not larger than it becomes twice it.
pub fn annulus(inner_radius: f64, outer_radius: f64, rings: usize, sectors: usize) -> TriMesh {
    let inner = if inner_radius > 0.0 && inner_radius.is_finite() {
        inner_radius
    } else {
        0.5
    };
    let outer = if outer_radius > inner && outer_radius.is_finite() {
        outer_radius
    } else {
        2.0 * inner
    };
    let rings = rings.clamp(1, MAX_RINGS);
    let sectors = sectors.clamp(3, MAX_SECTORS);
    let stack: Vec<Ring> = (0..=rings)
        .map(|i| Ring {
            z: 0.0,
            radius: inner + (outer - inner) * i as f64 / rings as f64,
            count: sectors,
        })
        .collect();
    ring_stack(&stack)
}

/// Closed torus around the `z` axis: tube centre radius `major`, tube radius `minor`,
/// `n_major` segments around the axis and `n_minor` around the tube (both `>= 3`), outward
/// faces. Invalid radii fall back to `major = 1`, `minor = major / 3`.
pub fn torus(major: f64, minor: f64, n_major: usize, n_minor: usize) -> TriMesh {
    let major = if major > 0.0 && major.is_finite() {
        major
    } else {
        1.0
    };
    let minor = if minor > 0.0 && minor < major {
        minor
    } else {
        major / 3.0
    };
    let (nu, nv) = (n_major.clamp(3, MAX_SECTORS), n_minor.clamp(3, MAX_RINGS));
    let mut vertices = Vec::with_capacity(nu * nv);
    for i in 0..nu {
        let u = TAU * i as f64 / nu as f64;
        for j in 0..nv {
            let v = TAU * j as f64 / nv as f64;
            let rho = major + minor * v.cos();
            vertices.push([rho * u.cos(), rho * u.sin(), minor * v.sin()]);
        }
    }
    let id = |i: usize, j: usize| ((i % nu) * nv + (j % nv)) as u32;
    let mut faces = Vec::with_capacity(2 * nu * nv);
    for i in 0..nu {
        for j in 0..nv {
            // d/du x d/dv points outwards.
            faces.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            faces.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    TriMesh::new(vertices, faces)
}

/// Flat disk `z = z0` of the given `radius`, its rim a ring of `rim` vertices at the angles
/// [`spherical_cap`] and [`lat_long_cap`] use for their boundary ring (vertex 0 at angle 0),
/// laid out last. Concentric rings with counts growing with the radius keep the triangles
/// near-equilateral. Faces are counter-clockwise seen from `-z` (the outside of a cap's
/// bottom). `rim >= 3`.
pub fn flat_disk_below(z0: f64, radius: f64, rim: usize) -> TriMesh {
    let rim = rim.clamp(3, MAX_SECTORS);
    let inner = ((rim as f64 / TAU).floor() as usize).min(MAX_RINGS);
    let mut stack = vec![Ring { z: z0, radius: 0.0, count: 1 }];
    for j in 1..=inner {
        let t = j as f64 / (inner + 1) as f64;
        stack.push(Ring { z: z0, radius: radius * t, count: ((rim as f64 * t).round() as usize).max(3) });
    }
    stack.push(Ring { z: z0, radius, count: rim });
    let up = ring_stack(&stack);
    TriMesh::new(up.vertices, up.faces.into_iter().map(|f| [f[0], f[2], f[1]]).collect())
}

/// Latitude/longitude mesh of the cap `z >= z0`: a vertex at the pole, `rings` rings equally
/// spaced in polar angle (the last at `z = z0`), each with `sectors` vertices on the same
/// meridians; each quad is split along its shorter diagonal, with a fan at the pole
/// (paper Sec. 4.2, remeshing by latitude and longitude lines).
pub fn lat_long_cap(z0: f64, rings: usize, sectors: usize) -> TriMesh {
    let z0 = clamp_z0(z0);
    let rings = rings.clamp(1, MAX_RINGS);
    let sectors = sectors.clamp(3, MAX_SECTORS);
    let theta_max = z0.acos();
    let mut stack = vec![Ring { z: 1.0, radius: 0.0, count: 1 }];
    for i in 1..=rings {
        let (z, radius) = if i == rings {
            (z0, ((1.0 - z0) * (1.0 + z0)).sqrt())
        } else {
            let t = theta_max * i as f64 / rings as f64;
            (t.cos(), t.sin())
        };
        stack.push(Ring { z, radius, count: sectors });
    }
    ring_stack(&stack)
}
