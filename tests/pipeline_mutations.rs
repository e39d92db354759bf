//! The pipeline on small damaged meshes: deterministic mutations of a small cap and a small
//! sphere (moved, swapped or repeated face indices, collapsed, NaN, huge or jittered
//! coordinates, dropped faces) either map or fail with an error; nothing panics, and every map that
//! succeeds has finite cap positions on the unit sphere.

mod common;

use common::Rng;

use capmesh::param::{parameterize, ParamOptions};
use capmesh::mesh::shapes::{icosphere, spherical_cap};
use capmesh::progress::NoProgress;
use capmesh::TriMesh;

fn mutate(mesh: &TriMesh, rng: &mut Rng) -> TriMesh {
    let mut m = mesh.clone();
    for _ in 0..1 + rng.below(3) {
        let (nv, nf) = (m.vertices.len(), m.faces.len());
        if nf == 0 || nv == 0 {
            break;
        }
        let f = rng.below(nf);
        let v = rng.below(nv);
        match rng.below(10) {
            7..=9 => {
                // A small jitter keeps the mesh valid: most of these must map.
                let k = rng.below(3);
                m.vertices[v][k] += 0.02 * ((rng.next() % 1000) as f64 / 1000.0 - 0.5);
            }
            0 => m.faces[f][rng.below(3)] = rng.below(nv + 2) as u32,
            1 => m.faces[f].swap(0, 1),
            2 => {
                let g = m.faces[f];
                m.faces.push(g);
            }
            3 => m.vertices[v] = m.vertices[rng.below(nv)],
            4 => m.vertices[v][rng.below(3)] = f64::NAN,
            5 => m.vertices[v][rng.below(3)] *= 1e12,
            _ => {
                m.faces.remove(f);
            }
        }
    }
    m
}

fn check(base: &TriMesh, seed: u64, rounds: usize) {
    let mut rng = Rng(seed);
    let (mut ok, mut err) = (0, 0);
    for round in 0..rounds {
        let m = mutate(base, &mut rng);
        let result = std::panic::catch_unwind(|| parameterize(&m, &ParamOptions::default(), &NoProgress));
        match result {
            Ok(Ok(map)) => {
                ok += 1;
                for p in &map.cap {
                    let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
                    // Unreferenced vertices sit at the origin; every other one is on the sphere.
                    assert!(r.is_finite() && (r == 0.0 || (r - 1.0).abs() < 1e-9), "round {round}: cap point {p:?}");
                }
            }
            Ok(Err(e)) => {
                err += 1;
                assert!(!e.to_string().is_empty());
            }
            Err(_) => panic!("round {round}: the pipeline panicked"),
        }
    }
    eprintln!("{ok} mapped, {err} refused");
    assert!(err > 0 && ok > 0, "mutations should both pass and fail: {ok} mapped, {err} refused");
}

#[test]
fn damaged_open_caps_map_or_fail_cleanly() {
    check(&spherical_cap(0.2, 5, 16), 11, 150);
}

#[test]
fn damaged_closed_spheres_map_or_fail_cleanly() {
    check(&icosphere(1), 12, 150);
}
