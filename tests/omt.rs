//! Semi-discrete transport: the Hessian against finite differences of the cell masses, mass
//! conservation, and Newton convergence to prescribed masses.

use capmesh::omt::cells::integrate;
use capmesh::omt::triangulation::RegularTriangulation;
use capmesh::omt::{OtOptions, OtSolver, RadialDensity, StereographicDensity, UniformDensity};
use capmesh::progress::NoProgress;

fn lcg(seed: u64) -> impl FnMut() -> f64 {
    let mut s = seed;
    move || {
        s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((s >> 11) as f64) / ((1u64 << 53) as f64)
    }
}

/// Random sites in the disk of radius r, some on the circle.
fn sites(n: usize, r: f64, seed: u64) -> Vec<[f64; 2]> {
    let mut rnd = lcg(seed);
    let mut out = Vec::new();
    let m = 24;
    for k in 0..m {
        let t = 2.0 * std::f64::consts::PI * (k as f64 + 0.3 * rnd()) / m as f64;
        out.push([r * t.cos(), r * t.sin()]);
    }
    while out.len() < n {
        let p = [r * (2.0 * rnd() - 1.0), r * (2.0 * rnd() - 1.0)];
        if p[0] * p[0] + p[1] * p[1] < 0.9 * r * r {
            out.push(p);
        }
    }
    out
}

/// `n` random target masses varying by a factor 4.
fn targets(n: usize, seed: u64) -> Vec<f64> {
    let mut rnd = lcg(seed);
    (0..n).map(|_| 0.5 + 1.5 * rnd()).collect()
}

fn masses(sites: &[[f64; 2]], w: &[f64], r: f64, d: &dyn RadialDensity) -> Vec<f64> {
    let mut tri = RegularTriangulation::delaunay(sites).unwrap();
    assert!(tri.update_weights(w));
    integrate(&tri, r, d).mass
}

#[test]
fn hessian_matches_finite_differences_of_masses() {
    for (r, d) in [(1.7, &StereographicDensity as &dyn RadialDensity), (1.0, &UniformDensity as &dyn RadialDensity)] {
        let s = sites(120, r, 11);
        let mut rnd = lcg(5);
        let w: Vec<f64> = (0..s.len()).map(|_| 0.002 * r * r * (rnd() - 0.5)).collect();
        let mut tri = RegularTriangulation::delaunay(&s).unwrap();
        assert!(tri.update_weights(&w));
        let cells = integrate(&tri, r, d);
        let n = s.len();
        // Dense Hessian from the edge list: H_ij = -c, H_ii = sum c.
        let mut h = vec![vec![0.0; n]; n];
        for &(i, j, c) in &cells.edges {
            let (i, j) = (i as usize, j as usize);
            h[i][j] -= c;
            h[j][i] -= c;
            h[i][i] += c;
            h[j][j] += c;
        }
        let delta = 1e-7 * r * r;
        let mut worst: f64 = 0.0;
        let scale = h.iter().map(|row| row.iter().map(|x| x.abs()).fold(0.0, f64::max)).fold(0.0, f64::max);
        for j in (0..n).step_by(7) {
            let mut wp = w.clone();
            wp[j] += delta;
            let mut wm = w.clone();
            wm[j] -= delta;
            let (mp, mm) = (masses(&s, &wp, r, d), masses(&s, &wm, r, d));
            for i in 0..n {
                let fd = (mp[i] - mm[i]) / (2.0 * delta);
                worst = worst.max((fd - h[i][j]).abs());
            }
        }
        assert!(worst < 1e-5 * scale, "Hessian vs finite differences: worst {worst:.3e}, scale {scale:.3e}");
    }
}

#[test]
fn cell_masses_sum_to_the_disk_mass() {
    for r in [0.3, 1.0, 4.0] {
        let s = sites(300, r, 3);
        let mut rnd = lcg(9);
        let w: Vec<f64> = (0..s.len()).map(|_| 1e-5 * r * r * (rnd() - 0.5)).collect();
        for d in [&StereographicDensity as &dyn RadialDensity, &UniformDensity] {
            let m = masses(&s, &w, r, d);
            let total: f64 = m.iter().sum();
            assert!((total - d.disk_mass(r)).abs() < 1e-11 * d.disk_mass(r), "r = {r}: {total} vs {}", d.disk_mass(r));
            assert!(m.iter().all(|x| *x > 0.0));
        }
    }
}

#[test]
fn newton_reaches_prescribed_masses() {
    let r = 2.0;
    let s = sites(400, r, 21);
    let target = targets(s.len(), 2);
    let d = StereographicDensity;
    let mut solver = OtSolver::new(&s, r, &d).unwrap();
    let (cells, report) = solver.solve(&target, &OtOptions::default(), &NoProgress).unwrap();
    let total: f64 = target.iter().sum();
    for (m, t) in cells.mass.iter().zip(&target) {
        let t = t * d.disk_mass(r) / total;
        assert!((m - t).abs() < 1e-4 * t, "mass {m} target {t}");
    }
    assert!(report.mass_error <= 1e-7);
    assert!(report.iterations >= 1);
    // The iterations integrate masses only; the returned integrals carry every cell's moment,
    // equal to a full integration at the final weights.
    let mut tri = RegularTriangulation::delaunay(solver.sites()).unwrap();
    assert!(tri.update_weights(solver.weights()));
    let full = integrate(&tri, r, &d);
    assert_eq!(cells.moment.len(), s.len());
    for i in 0..s.len() {
        let (a, b) = (cells.centroid(i).unwrap(), full.centroid(i).unwrap());
        assert!((a[0] - b[0]).abs() < 1e-12 * r && (a[1] - b[1]).abs() < 1e-12 * r, "cell {i}: {a:?} vs {b:?}");
    }
    // Warm start at another radius converges in few iterations.
    solver.rescale(1.1);
    let (_, again) = solver.solve(&target, &OtOptions::default(), &NoProgress).unwrap();
    assert!(again.iterations <= report.iterations + 2);
}

#[test]
fn backtracking_factor_outside_the_unit_interval_is_refused() {
    let r = 1.5;
    let s = sites(60, r, 5);
    let target = vec![1.0; s.len()];
    let d = StereographicDensity;
    let mut solver = OtSolver::new(&s, r, &d).unwrap();
    for shrink in [0.0, 1.0, 2.0, f64::NAN] {
        let options = OtOptions::default().with_log_step_shrink(shrink);
        let err = solver.solve(&target, &options, &NoProgress).err().unwrap_or_else(|| panic!("shrink {shrink} accepted"));
        assert!(err.to_string().contains("log_step_shrink"), "{err}");
    }
    // Halving, the finer default and anything between converge to the same masses.
    for shrink in [0.5, 0.6, capmesh::omt::options::LOG_STEP_SHRINK] {
        let options = OtOptions::default().with_log_step_shrink(shrink);
        let (cells, report) = OtSolver::new(&s, r, &d).unwrap().solve(&target, &options, &NoProgress).unwrap();
        assert!(report.mass_error <= options.tolerance, "shrink {shrink}: {}", report.mass_error);
        assert_eq!(cells.mass.len(), s.len());
    }
}

/// Below `OtOptions::stale_step_error`, after a full step, Newton first tries the direction
/// from the last factorization: the same masses to the tolerance with fewer factorizations.
#[test]
fn steps_with_the_last_factorization_reach_the_masses_with_fewer_factorizations() {
    let r = 2.0;
    let s = sites(1500, r, 33);
    let target = targets(s.len(), 7);
    let d = StereographicDensity;
    let solve = |stale_step_error: f64| {
        let options = OtOptions::default().with_stale_step_error(stale_step_error);
        OtSolver::new(&s, r, &d).unwrap().solve(&target, &options, &NoProgress).unwrap()
    };
    let (fresh_cells, fresh) = solve(0.0);
    let (stale_cells, stale) = solve(capmesh::omt::options::STALE_STEP_ERROR);
    eprintln!("every step factored {fresh:?}\nwith stale steps {stale:?}");
    assert_eq!(fresh.stale_steps, 0);
    assert!(stale.stale_steps >= 1, "{stale:?}");
    assert!(stale.iterations - stale.stale_steps < fresh.iterations, "{stale:?} against {fresh:?}");
    for report in [&fresh, &stale] {
        assert!(report.mass_error <= OtOptions::default().tolerance, "{report:?}");
    }
    for (a, b) in fresh_cells.mass.iter().zip(&stale_cells.mass) {
        assert!((a - b).abs() < 1e-5 * a, "{a} against {b}");
    }
}

#[test]
fn predicted_warm_start_saves_newton_steps_and_reaches_the_same_masses() {
    use capmesh::omt::planar_transport::PlanarTransport;
    let disk = sites(1500, 1.0, 41);
    let on_boundary: Vec<bool> = (0..disk.len()).map(|i| i < 24).collect();
    let target = targets(disk.len(), 9);
    let d = StereographicDensity;
    let options = OtOptions::default().with_tolerance(1e-7);
    let run = |predict: bool| {
        let mut t = PlanarTransport::new(&disk, &on_boundary, &target, &d, options.clone());
        t.set_prediction(predict);
        for r in [0.6, 0.9] {
            t.map_at(r, &NoProgress).unwrap();
        }
        let before = t.newton_iterations;
        let map = t.map_at(0.75, &NoProgress).unwrap();
        (map, t.newton_iterations - before, t.predicted_starts)
    };
    let (plain, plain_steps, plain_predicted) = run(false);
    let (predicted, predicted_steps, starts) = run(true);
    eprintln!("Newton steps at r = 0.75: {plain_steps} from the last weights, {predicted_steps} from predicted ones");
    assert_eq!((plain_predicted, starts), (0, 1));
    assert!(predicted_steps < plain_steps, "{predicted_steps} against {plain_steps}");
    for (a, b) in plain.masses.iter().zip(&predicted.masses) {
        assert!((a - b).abs() < 1e-5 * a, "{a} against {b}");
    }
    for (p, q) in plain.centroids.iter().zip(&predicted.centroids) {
        assert!((p[0] - q[0]).hypot(p[1] - q[1]) < 1e-5, "{p:?} against {q:?}");
    }
}
