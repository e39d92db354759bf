//! Where the spherical cap harmonics fit spends its time against the adaptive harmonics, on one
//! mesh, parameterized once: `cargo run --release --example scha_timing -- MESH [ORDER] [REPS]`.
//!
//! Runs on one thread (rayon and faer) and measures process CPU time, which a shared machine's
//! load moves far less than wall time (on 2 cores at a load of 16, medians of 3 wall-time runs
//! of fresh processes differed by a factor 0.7 to 1.7 between two bases doing the same work).
//! Prints the basis construction and the evaluation at every vertex of each basis, then times
//! `harmonics::analyze_map` (fit of every order, errors, reconstruction, aspect ratio: the CLI's
//! `fit_seconds`) `REPS` times (default 5) with ah and scha Neumann, and the same work done the
//! way it was before the closed-surface basis and `fit_with_errors_in` (issue 33), all four
//! alternating, and reports the medians (last line `TIMING ah scha ah_before scha_before`, read
//! by `benchmarks/scha_table.py`). The spherical cap
//! basis is cached within a process after its first build, so its construction time (built
//! afresh each repetition, `SchaBasis::new`) is added to each scha run: the figure a fresh
//! `capmesh harmonics` process pays.
use capmesh::harmonics::{analyze_map, BasisKind, CapBoundary, HarmonicBasis, HarmonicsOptions, SchaBasis};
use capmesh::mesh::SurfaceKind;
use capmesh::{parameterize, read_mesh, NoProgress, ParamOptions};

/// CPU seconds of this process.
fn cpu() -> f64 {
    let mut ts = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: clock_gettime writes the timespec it is given.
    unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut ts) };
    ts.tv_sec as f64 + 1e-9 * ts.tv_nsec as f64
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

fn main() -> Result<(), Box<dyn std::error::Error + Send + Sync>> {
    let args: Vec<String> = std::env::args().collect();
    let path = args.get(1).map_or("tests/data/open_face_choi.obj.gz", String::as_str);
    let order: usize = args.get(2).map_or(Ok(15), |s| s.parse())?;
    let reps: usize = args.get(3).map_or(Ok(5), |s| s.parse())?;
    let mesh = read_mesh(std::path::Path::new(path))?;
    let map = parameterize(&mesh, &ParamOptions::default(), &NoProgress)?;
    let z_star = map.report.z_star.unwrap_or(-1.0);
    print!("{path}: ");
    // The parameterization above on every core; the measurements below on one thread.
    faer::set_global_parallelism(faer::Par::Seq);
    rayon::ThreadPoolBuilder::new().num_threads(1).build()?.install(|| measure(&mesh, &map, z_star, order, reps))
}

fn measure(mesh: &capmesh::TriMesh, map: &capmesh::CapMap, z_star: f64, order: usize, reps: usize) -> Result<(), Box<dyn std::error::Error + Send + Sync>> {
    let closed = map.report.kind == SurfaceKind::ClosedSphere;
    let scha_z = capmesh::harmonics::scha::basis_cap(z_star, closed);
    println!("Z* = {z_star:.4} (scha basis on Z >= {scha_z:.4}), {} vertices, order {order}, one thread, CPU time", mesh.vertices.len());
    let scha = BasisKind::SphericalCap(CapBoundary::Neumann);
    for (kind, z) in [(BasisKind::Adaptive, z_star), (scha, scha_z)] {
        let t = cpu();
        let basis = HarmonicBasis::new(kind, z, order)?;
        let build = cpu() - t;
        let t = cpu();
        let mut sum = 0.0;
        for p in &map.cap {
            sum += basis.evaluate(*p)?.iter().sum::<f64>();
        }
        let eval = cpu() - t;
        println!("{kind:?}: basis {build:.4} s, evaluation at every vertex {eval:.4} s (checksum {sum:.3})");
    }
    // Four runs per repetition, rotated: ah and scha through analyze_map (now), and the same
    // work done the way analyze_map did it before (basis evaluated for the fit, again for the
    // errors and again for the reconstruction; scha on the parameterization's cap `z_star` also
    // for a closed surface).
    let runs: [(&str, BasisKind, bool); 4] = [("ah", BasisKind::Adaptive, false), ("scha", scha, false), ("ah before", BasisKind::Adaptive, true), ("scha before", scha, true)];
    let mut seconds = vec![Vec::new(); runs.len()];
    for rep in 0..reps {
        for r in 0..runs.len() {
            let slot = (r + rep) % runs.len();
            let (_, kind, before) = runs[slot];
            let cap_z = if before { z_star } else { scha_z };
            let t = cpu();
            if kind != BasisKind::Adaptive {
                SchaBasis::new(cap_z, order, CapBoundary::Neumann)?;
                SchaBasis::new(cap_z, 1, CapBoundary::Neumann)?;
            }
            if before {
                old_path(kind, mesh, map, z_star, order)?;
            } else {
                analyze_map(mesh, map, &HarmonicsOptions::default().with_order(order).with_basis(kind), &NoProgress)?;
            }
            seconds[slot].push(cpu() - t);
        }
    }
    let m: Vec<f64> = seconds.into_iter().map(median).collect();
    for (r, (name, _, _)) in runs.iter().enumerate() {
        println!("{name}: median CPU {:.3} s over {reps} runs", m[r]);
    }
    println!("scha / ah: {:.2} now, {:.2} before", m[1] / m[0], m[3] / m[2]);
    println!("TIMING {:.4} {:.4} {:.4} {:.4}", m[0], m[1], m[2], m[3]);
    Ok(())
}

/// The fit as `analyze_map` did it before `fit_with_errors_in` and the whole-sphere basis of
/// closed surfaces: the basis evaluated three times, scha on the map's cap.
fn old_path(kind: BasisKind, mesh: &capmesh::TriMesh, map: &capmesh::CapMap, z_star: f64, order: usize) -> Result<(), Box<dyn std::error::Error + Send + Sync>> {
    use capmesh::harmonics::{aspect_ratio_in, fit_all_orders_in, fit_in, order_errors, order_one_ellipsoid};
    let (cap, values) = (&map.cap, &mesh.vertices);
    let fits = fit_all_orders_in(kind, cap, values, z_star, order)?;
    let errors = order_errors(&fits, cap, values)?;
    let top = fits.last().ok_or("no fit")?;
    let positions = top.reconstruct(cap, order)?;
    aspect_ratio_in(kind, cap, values, z_star)?;
    if kind == BasisKind::Adaptive {
        order_one_ellipsoid(&fit_in(kind, cap, values, z_star, 1)?)?;
    }
    assert_eq!((errors.len(), positions.len()), (order + 1, cap.len()));
    Ok(())
}
