//! Closest-point queries: capmesh's `metrics::closest::SurfaceDistance` against parry3d-f64's
//! `TriMesh` (BVH) point projection, on the same mesh and the same random queries, in one run.
//!
//! `cargo run --release --bin closest -- MESH [QUERIES]` prints a Markdown table: build time,
//! query time (best of 3), and the largest difference between the two distances.

use std::path::PathBuf;
use std::time::Instant;

use capmesh::metrics::closest::SurfaceDistance;
use parry3d_f64::math::Vector;
use parry3d_f64::query::PointQuery;
use parry3d_f64::shape::TriMesh as ParryMesh;

fn main() {
    let mut args = std::env::args().skip(1);
    let path = PathBuf::from(args.next().expect("usage: closest MESH [QUERIES]"));
    let queries: usize = args.next().map_or(100_000, |s| s.parse().expect("QUERIES is a number"));
    let mesh = capmesh::io::read_mesh(&path).unwrap_or_else(|e| panic!("{e}"));
    let (lo, hi) = mesh.bounding_box().expect("non-empty mesh");
    // Queries uniform in the bounding box grown by 10% per side (a fixed LCG: the same points
    // every run).
    let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut uniform = || {
        state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let boxed: Vec<[f64; 3]> = (0..queries)
        .map(|_| std::array::from_fn(|i| {
            let ext = hi[i] - lo[i];
            lo[i] - 0.1 * ext + 1.2 * ext * uniform()
        }))
        .collect();
    // Queries near the surface (what the Hausdorff sampling asks): a random point of a random
    // face moved along its normal by up to one mean edge length either way.
    let edge = mesh.faces.iter().map(|f| {
        let (a, b) = (mesh.vertices[f[0] as usize], mesh.vertices[f[1] as usize]);
        ((a[0]-b[0]).powi(2) + (a[1]-b[1]).powi(2) + (a[2]-b[2]).powi(2)).sqrt()
    }).sum::<f64>() / mesh.faces.len() as f64;
    let near: Vec<[f64; 3]> = (0..queries)
        .map(|_| {
            let f = mesh.faces[(uniform() * mesh.faces.len() as f64) as usize % mesh.faces.len()];
            let q = f.map(|v| mesh.vertices[v as usize]);
            let (mut u, mut v) = (uniform(), uniform());
            if u + v > 1.0 { (u, v) = (1.0 - u, 1.0 - v); }
            let e1: [f64; 3] = std::array::from_fn(|i| q[1][i] - q[0][i]);
            let e2: [f64; 3] = std::array::from_fn(|i| q[2][i] - q[0][i]);
            let n = [e1[1]*e2[2]-e1[2]*e2[1], e1[2]*e2[0]-e1[0]*e2[2], e1[0]*e2[1]-e1[1]*e2[0]];
            let nl = (n[0]*n[0]+n[1]*n[1]+n[2]*n[2]).sqrt().max(1e-300);
            let off = (2.0 * uniform() - 1.0) * edge / nl;
            std::array::from_fn(|i| q[0][i] + u * e1[i] + v * e2[i] + off * n[i])
        })
        .collect();

    let best = |f: &mut dyn FnMut() -> Vec<f64>| {
        let mut out = Vec::new();
        let mut time = f64::INFINITY;
        for _ in 0..3 {
            let t = Instant::now();
            out = f();
            time = time.min(t.elapsed().as_secs_f64());
        }
        (time, out)
    };

    let mut t = Instant::now();
    let ours = SurfaceDistance::new(&mesh);
    let mut ours_build = t.elapsed().as_secs_f64();
    for _ in 0..2 {
        t = Instant::now();
        let _ = SurfaceDistance::new(&mesh);
        ours_build = ours_build.min(t.elapsed().as_secs_f64());
    }

    let build_parry = || {
        let v: Vec<Vector> = mesh.vertices.iter().map(|p| Vector::new(p[0], p[1], p[2])).collect();
        ParryMesh::new(v, mesh.faces.clone()).expect("parry accepts the mesh")
    };
    t = Instant::now();
    let parry = build_parry();
    let mut parry_build = t.elapsed().as_secs_f64();
    for _ in 0..2 {
        t = Instant::now();
        let _ = build_parry();
        parry_build = parry_build.min(t.elapsed().as_secs_f64());
    }
    let name = path.file_name().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    println!("mesh `{name}`: {} vertices, {} faces; {queries} queries per set; times best of 3, one thread", mesh.vertices.len(), mesh.faces.len());
    println!();
    println!("| implementation | build (ms) | queries | query time (ms) | per query (us) | largest difference |");
    println!("|---|---:|---|---:|---:|---:|");
    for (label, points) in [("random in the box grown by 10%", &boxed), ("within one edge of the surface", &near)] {
        let (ours_query, d_ours) = best(&mut || points.iter().map(|&p| ours.distance(p)).collect());
        let mut hint = None;
        let (hint_query, _) = best(&mut || points.iter().map(|&p| ours.distance_near(p, &mut hint)).collect());
        let (parry_query, d_parry) = best(&mut || {
            points
                .iter()
                .map(|p| {
                    let q = Vector::new(p[0], p[1], p[2]);
                    (parry.project_local_point(q, false).point - q).length()
                })
                .collect()
        });
        let max_diff = d_ours.iter().zip(&d_parry).map(|(a, b)| (a - b).abs()).fold(0.0f64, f64::max);
        let per = |t: f64| t * 1e6 / points.len() as f64;
        println!("| capmesh `SurfaceDistance::distance` (grid) | {:.1} | {label} | {:.1} | {:.2} | |", ours_build * 1e3, ours_query * 1e3, per(ours_query));
        println!("| capmesh `SurfaceDistance::distance_near` (grid, previous face as hint) | {:.1} | {label} | {:.1} | {:.2} | |", ours_build * 1e3, hint_query * 1e3, per(hint_query));
        println!("| parry3d-f64 0.26 `TriMesh::project_local_point` (BVH) | {:.1} | {label} | {:.1} | {:.2} | {max_diff:.1e} |", parry_build * 1e3, parry_query * 1e3, per(parry_query));
    }
}
