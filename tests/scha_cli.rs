//! The spherical cap harmonics through the command line (issue 33): on the face at N = 15 the
//! reconstruction keeps the boundary loop (the figures: max error <= 0.05 of the
//! diagonal, mean <= 0.005, boundary loop <= 0.02), the coefficients file names the basis and
//! every degree and re-evaluates to the written surface, `--resample-faces` gives a cap-grid
//! remesh whose rim follows the boundary loop, and `shape --groups` compares groups.

mod common;

use capmesh::harmonics::{basis_index, BasisKind, CapBoundary, HarmonicFit};
use common::cli::{capmesh, harmonics, HarmonicsFiles};
use common::csv::Table;
use common::{data, TempDir};

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// Distance from `p` to the segment `a b`.
fn to_segment(p: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let len2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    let t = if len2 > 0.0 { (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1] + (p[2] - a[2]) * d[2]) / len2).clamp(0.0, 1.0) } else { 0.0 };
    dist(p, [a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2]])
}

#[test]
fn scha_keeps_the_face_boundary_at_order_15() {
    const ORDER: usize = 15;
    let dir = TempDir::new("scha-cli-face");
    let input = data("open_face_choi.obj.gz");
    let files = HarmonicsFiles::in_dir(&dir, "face.ply");
    let (out, coefficients, report, cap, resampled) = (&files.output, &files.coefficients, &files.report, &files.cap_mesh, dir.join("grid.ply"));
    let run = harmonics(&input, &["--basis", "scha", "--order", &ORDER.to_string()], &files);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let stdout = String::from_utf8_lossy(&run.stdout);
    eprintln!("{stdout}");
    assert!(stdout.contains("scha basis (neumann)") && stdout.contains("boundary loop"), "{stdout}");

    let original = capmesh::io::read_mesh(&input).unwrap();
    let recon = capmesh::io::read_mesh(out).unwrap();
    assert_eq!(recon.faces, original.faces);
    let diag = original.bounding_box_diagonal();

    // The figures at N = 15.
    let r: serde_json::Value = serde_json::from_slice(&std::fs::read(report).unwrap()).unwrap();
    assert_eq!(r["basis"], serde_json::json!({"spherical_cap": "neumann"}));
    let top = &r["errors_by_order"][ORDER];
    let (mean, max) = (top["mean_relative"].as_f64().unwrap(), top["max_relative"].as_f64().unwrap());
    let boundary = r["boundary_max_relative"].as_f64().unwrap();
    eprintln!("N = {ORDER}: mean {mean:.5}, max {max:.4}, boundary loop {boundary:.4} of the diagonal");
    assert!(mean <= 0.005, "mean error {mean}");
    assert!(max <= 0.05, "max error {max}");
    assert!(boundary <= 0.02, "boundary loop error {boundary}");
    assert!(r["ellipsoid_aspect_ratio"].is_null(), "the AH-only ellipsoid is not reported for scha");

    // The boundary loop is measured on the written surface too.
    let (_, topology) = capmesh::mesh::validate(&original).unwrap();
    let lp = &topology.boundary_loops[0];
    let worst = lp.iter().map(|&v| dist(recon.vertices[v as usize], original.vertices[v as usize])).fold(0.0f64, f64::max);
    assert!((worst / diag - boundary).abs() < 1e-9, "{worst} vs {boundary}");

    // The coefficients file names the basis and every degree; re-evaluated it gives the surface.
    let c: serde_json::Value = serde_json::from_slice(&std::fs::read(coefficients).unwrap()).unwrap();
    assert_eq!((c["basis"].as_str(), c["boundary"].as_str()), (Some("scha"), Some("neumann")));
    assert!(c.get("q1").is_none() && c["definition"].as_str().unwrap().contains("Theta"));
    let list = c["coefficients"].as_array().unwrap();
    let mut by_index = vec![[0.0; 3]; list.len()];
    let mut degrees = vec![0.0; list.len()];
    for e in list {
        let i = basis_index(e["n"].as_u64().unwrap() as usize, e["m"].as_i64().unwrap() as isize).unwrap();
        by_index[i] = ["x", "y", "z"].map(|k| e[k].as_f64().unwrap());
        degrees[i] = e["degree"].as_f64().unwrap();
    }
    // Degrees rise with n at fixed m, are not all integers (Z* != 0, -1) and start at 0 (the constant).
    assert!(degrees[0].abs() < 1e-9, "{}", degrees[0]);
    assert!(degrees.iter().any(|d| (d - d.round()).abs() > 0.05), "{degrees:?}");
    for m in 0..=ORDER as isize {
        for n in m as usize + 1..=ORDER {
            assert!(degrees[basis_index(n, m).unwrap()] > degrees[basis_index(n - 1, m).unwrap()], "n = {n}, m = {m}");
        }
    }
    let fitted = HarmonicFit {
        basis: BasisKind::SphericalCap(CapBoundary::Neumann),
        z_star: c["z_star"].as_f64().unwrap(),
        order: ORDER,
        coefficients: by_index,
    };
    let cap = capmesh::io::read_mesh(cap).unwrap();
    let evaluated = fitted.reconstruct(&cap.vertices, ORDER).unwrap();
    let differ = evaluated.iter().zip(&recon.vertices).map(|(a, b)| dist(*a, *b)).fold(0.0f64, f64::max);
    assert!(differ <= 1e-9 * diag, "coefficients re-evaluated differ by {differ}");

    // The same fit on a cap grid: an open disk of about 3000 faces whose rim follows the loop.
    let run = capmesh()
        .args(["harmonics", "--quiet", "--basis", "scha", "--order", &ORDER.to_string(), "--resample-faces", "3000"])
        .arg(&input)
        .arg("-o")
        .arg(&resampled)
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let grid = capmesh::io::read_mesh(&resampled).unwrap();
    assert!((2700..=3300).contains(&grid.faces.len()), "{} faces", grid.faces.len());
    let (_, grid_topology) = capmesh::mesh::validate(&grid).unwrap();
    assert_eq!(grid_topology.boundary_loops.len(), 1);
    let rim_gap = grid_topology.boundary_loops[0]
        .iter()
        .map(|&v| {
            let p = grid.vertices[v as usize];
            (0..lp.len())
                .map(|i| to_segment(p, original.vertices[lp[i] as usize], original.vertices[lp[(i + 1) % lp.len()] as usize]))
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0f64, f64::max);
    eprintln!("resampled rim: farthest {:.4} of the diagonal from the input's boundary loop", rim_gap / diag);
    assert!(rim_gap <= 0.02 * diag, "rim {rim_gap} from the loop (diagonal {diag})");
}

#[test]
fn shape_compares_groups_with_welch() {
    let dir = TempDir::new("scha-cli-groups");
    let meshes = ["open_meg_helmet_babysquid_mne.obj.gz", "open_lv_endo_rabbit_chaste.obj.gz", "closed_bunny_npm.obj.gz", "closed_bird_skull_CPallidusA_choi.obj.gz"];
    let groups = dir.join("groups.csv");
    std::fs::write(
        &groups,
        format!("file,group\n# a comment\n{},open\n\"{}\",open\n{},closed\n{},closed\n", meshes[0], meshes[1], meshes[2], meshes[3]),
    )
    .unwrap();
    let csv = dir.join("shape.csv");
    let mut cmd = capmesh();
    cmd.args(["shape", "--quiet", "--basis", "scha", "--groups"]).arg(&groups).arg("--csv").arg(&csv);
    for m in meshes {
        cmd.arg(data(m));
    }
    let out = cmd.output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let stdout = String::from_utf8_lossy(&out.stdout);
    eprintln!("{stdout}");
    assert!(stdout.contains("Welch's t-test open vs closed"), "{stdout}");

    // The summary's means are those of the CSV's aspect ratios.
    let table = Table::read(&csv);
    let ratio = |name: &str| -> f64 { table.get(name, "aspect_ratio").parse().unwrap() };
    let summary: serde_json::Value = serde_json::from_slice(&std::fs::read(dir.join("shape.groups.json")).unwrap()).unwrap();
    let open_mean = (ratio(meshes[0]) + ratio(meshes[1])) / 2.0;
    assert_eq!(summary["groups"][0]["group"], "open");
    assert_eq!(summary["groups"][0]["count"], 2);
    assert!((summary["groups"][0]["mean"].as_f64().unwrap() - open_mean).abs() < 1e-9 * open_mean);
    let p = summary["tests"][0]["p_value"].as_f64().unwrap();
    assert!(p > 0.0 && p <= 1.0, "{p}");
    let summary_csv = std::fs::read_to_string(dir.join("shape.groups.csv")).unwrap();
    assert_eq!(summary_csv.lines().count(), 4, "{summary_csv}");

    // A groups file naming a mesh that was not given is refused before any analysis.
    std::fs::write(&groups, "nothere.obj,open\n").unwrap();
    let out = capmesh().args(["shape", "--quiet", "--groups"]).arg(&groups).arg("--csv").arg(dir.join("x.csv")).arg(data(meshes[0])).output().unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("line 1") && err.contains("nothere.obj"), "{err}");
    assert!(!dir.join("x.csv").exists(), "analysis ran despite the bad groups file");
}
