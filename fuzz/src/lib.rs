//! Shared checks of the fuzz targets in `fuzz_targets/`.

use capmesh::param::{parameterize, ParamOptions};
use capmesh::io::{read_mesh_from_bytes, Format};
use capmesh::mesh::shapes::{icosphere, spherical_cap};
use capmesh::progress::NoProgress;
use capmesh::remesh::{remesh, CapGrid, RemeshOptions};
use capmesh::TriMesh;

/// Every face index of `mesh` names a vertex.
pub fn check_indices(mesh: &TriMesh) {
    let n = mesh.vertices.len();
    for f in &mesh.faces {
        assert!(f.iter().all(|&v| (v as usize) < n), "face {f:?} with {n} vertices");
    }
}

/// Parse `data` as `format`; a mesh that comes back must have in-range indices.
pub fn check_read(data: &[u8], format: Format) {
    if let Ok(mesh) = read_mesh_from_bytes(data, format) {
        check_indices(&mesh);
    }
}

/// Reads the fuzz input a few bits at a time.
struct Bytes<'a>(&'a [u8]);

impl Bytes<'_> {
    fn byte(&mut self) -> u8 {
        match self.0.split_first() {
            Some((&b, rest)) => {
                self.0 = rest;
                b
            }
            None => 0,
        }
    }
    fn below(&mut self, n: usize) -> usize {
        let v = u16::from_le_bytes([self.byte(), self.byte()]) as usize;
        v % n.max(1)
    }
    fn coordinate(&mut self) -> f64 {
        match self.byte() {
            0 => f64::NAN,
            1 => f64::INFINITY,
            2 => 1e300,
            _ => i16::from_le_bytes([self.byte(), self.byte()]) as f64 / 4096.0,
        }
    }
}

/// A small mesh from the input: either raw vertices and faces, or a valid cap or sphere with a
/// few input-driven edits (moved, swapped, repeated or dropped faces, moved, merged or
/// non-finite vertices).
pub fn decode_mesh(data: &[u8]) -> TriMesh {
    let mut b = Bytes(data);
    match b.byte() % 4 {
        0 => {
            let nv = 3 + b.below(40);
            let nf = 1 + b.below(60);
            let vertices = (0..nv).map(|_| [b.coordinate(), b.coordinate(), b.coordinate()]).collect();
            let faces = (0..nf).map(|_| [b.below(nv + 1) as u32, b.below(nv + 1) as u32, b.below(nv + 1) as u32]).collect();
            TriMesh::new(vertices, faces)
        }
        mode => {
            let mut m = if mode == 1 { icosphere(1) } else { spherical_cap(-0.5 + 0.1 * (b.byte() % 15) as f64, 4, 12) };
            for _ in 0..b.byte() % 6 {
                let (nv, nf) = (m.vertices.len(), m.faces.len());
                if nv == 0 || nf == 0 {
                    break;
                }
                let (v, f) = (b.below(nv), b.below(nf));
                match b.byte() % 8 {
                    0 => m.faces[f][b.below(3)] = b.below(nv + 2) as u32,
                    1 => m.faces[f].swap(0, 1),
                    2 => {
                        let g = m.faces[f];
                        m.faces.push(g);
                    }
                    3 => {
                        m.faces.remove(f);
                    }
                    4 => m.vertices[v] = m.vertices[b.below(nv)],
                    5 => m.vertices[v][b.below(3)] = b.coordinate(),
                    _ => m.vertices[v][b.below(3)] += (b.byte() as f64 - 128.0) / 2048.0,
                }
            }
            m
        }
    }
}

/// Parameterize and remesh the decoded mesh with small budgets; successes must be sane.
pub fn check_pipeline(data: &[u8]) {
    let mesh = decode_mesh(data);
    let param = ParamOptions::default().with_max_search_evaluations(6).with_area_refinement(5);
    if let Ok(map) = parameterize(&mesh, &param, &NoProgress) {
        assert_eq!(map.cap.len(), mesh.vertices.len());
        let used = used_vertices(&mesh);
        for (v, p) in map.cap.iter().enumerate() {
            if used[v] {
                let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
                assert!((r - 1.0).abs() < 1e-9, "vertex {v} at {p:?} is not on the unit sphere");
            }
        }
        let options = RemeshOptions::default().with_grid(CapGrid::Uniform { faces: 60 }).with_param(param).with_area_equalization(3);
        if let Ok((out, _)) = remesh(&mesh, &options, &NoProgress) {
            check_indices(&out);
            assert!(out.vertices.iter().all(|p| p.iter().all(|x| x.is_finite())), "non-finite remeshed vertex");
        }
    }
}

fn used_vertices(mesh: &TriMesh) -> Vec<bool> {
    let mut used = vec![false; mesh.vertices.len()];
    for f in &mesh.faces {
        for &v in f {
            if let Some(u) = used.get_mut(v as usize) {
                *u = true;
            }
        }
    }
    used
}
