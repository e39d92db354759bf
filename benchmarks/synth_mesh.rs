//! Writes the synthetic meshes of the stage benchmark (`benchmarks/stage_bench.sh`):
//!
//! * `open N`: a bumpy height-field disk (`grid_disk` rings, near-equilateral triangles) of
//!   about N vertices: `z = 0.25 sin(3x) cos(4y) + 0.3 x^2`;
//! * `closed S`: a bumpy ellipsoid, the icosphere of `S` subdivisions (`10 * 4^S + 2`
//!   vertices) with radius `1 + 0.08 sin(5x) sin(4y) sin(3z)` and axes (1, 0.7, 1.4);
//! * `geodesic N`: the same ellipsoid on the geodesic sphere of about N vertices
//!   (`10 f^2 + 2`, frequency `f` the nearest to `sqrt((N - 2) / 10)`);
//! * `folded N`: a folded (cortex-like) closed surface on that geodesic sphere
//!   ([`capmesh::mesh::shapes::folded_sphere`]; before its axes, half the faces of the 130k
//!   one tilted by more than 29 degrees from the sphere, a tenth by more than 45);
//! * `subdivide K IN OUT`: the mesh IN midpoint-subdivided K times
//!   ([`capmesh::mesh::subdivide_midpoint`], the same surface with `4^K` times the faces).
//!
//! `cargo run --release --example synth_mesh -- open 100000 out.ply`

use capmesh::io::{read_mesh, write_mesh};
use capmesh::mesh::shapes::{folded_sphere, geodesic_sphere, grid_disk, icosphere};
use capmesh::mesh::subdivide_midpoint;
use std::path::Path;

fn main() {
    let mut args: Vec<String> = std::env::args().collect();
    if args.len() == 5 && args[1] == "subdivide" {
        // subdivide K IN OUT: read IN here, then the kind's usual path writes OUT.
        let input = args.remove(3);
        return subdivide(&args[2], Path::new(&input), Path::new(&args[3]));
    }
    if args.len() != 4 {
        eprintln!("usage: synth_mesh open N OUT | closed SUBDIVISIONS OUT | geodesic N OUT | folded N OUT | subdivide K IN OUT");
        std::process::exit(2);
    }
    let size: usize = args[2].parse().unwrap_or_else(|_| {
        eprintln!("synth_mesh: '{}' is not a count", args[2]);
        std::process::exit(2)
    });
    let mut mesh = match args[1].as_str() {
        "open" => {
            // 1 + 3 n (n + 1) vertices.
            let n = (((size as f64 - 1.0) / 3.0).sqrt().round() as usize).max(1);
            let mut m = grid_disk(n);
            for p in &mut m.vertices {
                p[2] = 0.25 * (3.0 * p[0]).sin() * (4.0 * p[1]).cos() + 0.3 * p[0] * p[0];
            }
            m
        }
        "closed" => bumpy_ellipsoid(icosphere(size)),
        "geodesic" => bumpy_ellipsoid(geodesic_sphere((((size.max(12) - 2) as f64 / 10.0).sqrt().round() as usize).max(1))),
        "folded" => folded_sphere((((size.max(12) - 2) as f64 / 10.0).sqrt().round() as usize).max(1)),
        other => {
            eprintln!("synth_mesh: unknown kind '{other}' (open, closed, geodesic or folded)");
            std::process::exit(2)
        }
    };
    mesh.vertices.shrink_to_fit();
    if let Err(e) = write_mesh(Path::new(&args[3]), &mesh) {
        eprintln!("synth_mesh: {e}");
        std::process::exit(1);
    }
    println!("{} vertices, {} faces -> {}", mesh.vertices.len(), mesh.faces.len(), args[3]);
}

/// `synth_mesh subdivide K IN OUT`.
fn subdivide(times: &str, input: &Path, output: &Path) {
    let times: usize = times.parse().unwrap_or_else(|_| {
        eprintln!("synth_mesh: '{times}' is not a count of subdivisions");
        std::process::exit(2)
    });
    let mesh = read_mesh(input).unwrap_or_else(|e| {
        eprintln!("synth_mesh: {e}");
        std::process::exit(1)
    });
    let mesh = subdivide_midpoint(&mesh, times);
    if let Err(e) = write_mesh(output, &mesh) {
        eprintln!("synth_mesh: {e}");
        std::process::exit(1);
    }
    println!("{} vertices, {} faces -> {}", mesh.vertices.len(), mesh.faces.len(), output.display());
}

/// The unit sphere `m` made a bumpy ellipsoid: radius `1 + 0.08 sin(5x) sin(4y) sin(3z)`,
/// axes (1, 0.7, 1.4).
fn bumpy_ellipsoid(mut m: capmesh::mesh::TriMesh) -> capmesh::mesh::TriMesh {
    for p in &mut m.vertices {
        let r = 1.0 + 0.08 * (5.0 * p[0]).sin() * (4.0 * p[1]).sin() * (3.0 * p[2]).sin();
        *p = [r * p[0], 0.7 * r * p[1], 1.4 * r * p[2]];
    }
    m
}
