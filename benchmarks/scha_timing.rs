//! Where the spherical cap harmonics fit spends its time (basis construction, evaluation,
//! fit) against the adaptive harmonics, on one mesh: `cargo run --release --example scha_timing
//! -- MESH ORDER`.
use capmesh::harmonics::{fit_all_orders_in, BasisKind, CapBoundary, HarmonicBasis};
use capmesh::{parameterize, read_mesh, NoProgress, ParamOptions};
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let path = args.get(1).map_or("tests/data/open_face_choi.obj.gz", String::as_str);
    let order: usize = args.get(2).map_or(Ok(15), |s| s.parse())?;
    let mesh = read_mesh(std::path::Path::new(path))?;
    let map = parameterize(&mesh, &ParamOptions::default(), &NoProgress)?;
    let z_star = map.report.z_star.unwrap_or(-1.0);
    println!("{path}: Z* = {z_star:.4}, {} vertices, order {order}", mesh.vertices.len());
    for m in [0, order / 2, order] {
        let f = capmesh::harmonics::cap_legendre::CapLegendre::new(z_star, m, order - m + 1, capmesh::harmonics::cap_legendre::Rim::Neumann)?;
        println!("m = {m}: terms kept {:?}", f.terms());
    }
    for kind in [BasisKind::Adaptive, BasisKind::SphericalCap(CapBoundary::Neumann), BasisKind::SphericalCap(CapBoundary::Mixed)] {
        let t = Instant::now();
        let basis = HarmonicBasis::new(kind, z_star, order)?;
        let build = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let mut sum = 0.0;
        for p in &map.cap {
            sum += basis.evaluate(*p)?.iter().sum::<f64>();
        }
        let eval = t.elapsed().as_secs_f64();
        let t = Instant::now();
        fit_all_orders_in(kind, &map.cap, &mesh.vertices, z_star, order)?;
        let fit = t.elapsed().as_secs_f64();
        println!("{kind:?}: basis {build:.4} s, evaluation at every vertex {eval:.4} s (checksum {sum:.3}), fit {fit:.3} s");
    }
    Ok(())
}
