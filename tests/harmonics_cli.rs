//! The `harmonics` and `shape` subcommands on real meshes: `harmonics` writes a reconstruction
//! with the input's connectivity, coefficients that the library re-evaluates to the same surface,
//! and a report whose error falls with the order; `shape` analyses a cohort in parallel, gives
//! one CSV row per mesh (the paper's aspect ratio in `aspect_ratio`) and fails, after writing
//! the CSV, naming the mesh that could not be analysed; a poor map marks its row and exits 3.

mod common;

use common::cli::{capmesh, harmonics, HarmonicsFiles};
use common::csv::Table;
use common::{data, TempDir};

use capmesh::harmonics::{aspect_ratio, basis_index, basis_len, fit, order_one_ellipsoid, HarmonicFit};
use std::collections::HashMap;
use std::path::Path;

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

#[test]
fn harmonics_on_the_face_writes_reconstruction_coefficients_and_report() {
    const ORDER: usize = 4;
    let dir = TempDir::new("harmonics-cli-face");
    let input = data("open_face_choi.obj.gz");
    let before = std::fs::read(&input).unwrap();
    let files = HarmonicsFiles::in_dir(&dir, "face_ah.ply");
    let (out, coefficients, report, cap) = (&files.output, &files.coefficients, &files.report, &files.cap_mesh);
    let run = harmonics(&input, &["--order", &ORDER.to_string()], &files);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    eprintln!("{}", String::from_utf8_lossy(&run.stdout));
    assert_eq!(std::fs::read(&input).unwrap(), before, "input modified");

    let original = capmesh::io::read_mesh(&input).unwrap();
    let recon = capmesh::io::read_mesh(out).unwrap();
    assert_eq!(recon.vertices.len(), original.vertices.len());
    assert_eq!(recon.faces, original.faces, "connectivity changed");
    let diag = original.bounding_box_diagonal();

    // The report: one error row per order 0..=N, mean error strictly falling with the order.
    let r: serde_json::Value = serde_json::from_slice(&std::fs::read(report).unwrap()).unwrap();
    assert_eq!(r["order"].as_u64(), Some(ORDER as u64));
    assert_eq!(r["vertices"].as_u64(), Some(original.vertices.len() as u64));
    let rows = r["errors_by_order"].as_array().unwrap();
    assert_eq!(rows.len(), ORDER + 1);
    let mean: Vec<f64> = rows.iter().map(|e| e["mean_relative"].as_f64().unwrap()).collect();
    for (n, e) in rows.iter().enumerate() {
        assert_eq!(e["order"].as_u64(), Some(n as u64));
        let (m, mx) = (e["mean_distance"].as_f64().unwrap(), e["max_distance"].as_f64().unwrap());
        assert!(m > 0.0 && mx >= m, "order {n}: mean {m} max {mx}");
        assert!((e["mean_relative"].as_f64().unwrap() - m / diag).abs() < 1e-12, "order {n}");
    }
    assert!(mean.windows(2).all(|w| w[1] < w[0]), "mean error does not fall: {mean:?}");
    assert!(mean[ORDER] < 0.5 * mean[1], "{mean:?}");
    let ratio = r["aspect_ratio"].as_f64().unwrap();
    assert!(ratio >= 1.0 && ratio.is_finite(), "aspect ratio {ratio}");
    assert!(r["param"]["z_star"].is_number() && r["seconds"].as_f64().unwrap() > 0.0);

    // The written surface is the order-N representation: its mean distance to the input is the
    // report's order-N error.
    let measured = recon.vertices.iter().zip(&original.vertices).map(|(a, b)| dist(*a, *b)).sum::<f64>()
        / original.vertices.len() as f64;
    let reported = rows[ORDER]["mean_distance"].as_f64().unwrap();
    assert!((measured - reported).abs() <= 1e-9 * diag, "{measured} vs {reported}");

    // The coefficients, evaluated by the library at the cap positions, give the same surface.
    let c: serde_json::Value = serde_json::from_slice(&std::fs::read(coefficients).unwrap()).unwrap();
    let z_star = c["z_star"].as_f64().unwrap();
    assert_eq!(Some(z_star), r["z_star"].as_f64());
    assert!((c["q1"].as_f64().unwrap() - 2.0 / (1.0 - z_star)).abs() < 1e-12);
    assert!(c["coefficients"].as_array().unwrap().iter().all(|e| e["degree"].as_f64() == e["n"].as_f64()), "AH degrees are the orders");
    assert!((c["q2"].as_f64().unwrap() + (1.0 + z_star) / (1.0 - z_star)).abs() < 1e-12);
    let list = c["coefficients"].as_array().unwrap();
    assert_eq!(list.len(), basis_len(ORDER));
    let mut coefficients_by_index = vec![None; list.len()];
    for e in list {
        let (n, m) = (e["n"].as_u64().unwrap() as usize, e["m"].as_i64().unwrap() as isize);
        let i = basis_index(n, m).unwrap_or_else(|| panic!("bad (n, m) = ({n}, {m})"));
        assert!(coefficients_by_index[i].is_none(), "({n}, {m}) twice");
        coefficients_by_index[i] = Some(["x", "y", "z"].map(|k| e[k].as_f64().unwrap()));
    }
    assert_eq!(c["basis"].as_str(), Some("ah"));
    let fitted = HarmonicFit {
        basis: Default::default(),
        z_star,
        order: c["order"].as_u64().unwrap() as usize,
        coefficients: coefficients_by_index.into_iter().map(Option::unwrap).collect(),
    };
    let cap = capmesh::io::read_mesh(cap).unwrap();
    assert_eq!(cap.faces, original.faces);
    for p in &cap.vertices {
        assert!((dist(*p, [0.0; 3]) - 1.0).abs() < 1e-9 && p[2] >= z_star - 1e-9, "{p:?}");
    }
    let evaluated = fitted.reconstruct(&cap.vertices, ORDER).unwrap();
    let worst = evaluated.iter().zip(&recon.vertices).map(|(a, b)| dist(*a, *b)).fold(0.0f64, f64::max);
    assert!(worst <= 1e-9 * diag, "coefficients re-evaluated differ by {worst}");

    // Every m > 0 term vanishes on Z = Z*: the boundary loop collapses to one point (up to the
    // rounding of the boundary vertices' height, amplified by sqrt(Z - Z*)).
    let (_, topology) = capmesh::mesh::validate(&original).unwrap();
    let boundary = &topology.boundary_loops[0];
    let first = recon.vertices[boundary[0] as usize];
    let spread = boundary.iter().map(|&v| dist(recon.vertices[v as usize], first)).fold(0.0f64, f64::max);
    let loop_size = boundary.iter().map(|&v| dist(original.vertices[v as usize], original.vertices[boundary[0] as usize])).fold(0.0f64, f64::max);
    eprintln!(
        "boundary loop: {} vertices, extent {:.4} of the diagonal in the input, {:.3e} reconstructed",
        boundary.len(),
        loop_size / diag,
        spread / diag
    );
    assert!(spread <= 1e-6 * diag && loop_size > 0.1 * diag, "spread {spread}, loop {loop_size}, diagonal {diag}");
}

#[test]
fn harmonics_refuses_bad_requests_before_any_work() {
    let dir = TempDir::new("harmonics-cli-refuse");
    let copy = dir.join("helmet.obj.gz");
    std::fs::copy(data("open_meg_helmet_babysquid_mne.obj.gz"), &copy).unwrap();
    let before = std::fs::read(&copy).unwrap();
    for flag in ["-o", "--coefficients", "--report", "--cap-mesh"] {
        let mut cmd = capmesh();
        cmd.args(["harmonics", "--quiet"]).arg(&copy);
        if flag != "-o" {
            cmd.arg("-o").arg(dir.join("out.ply"));
        }
        let out = cmd.arg(flag).arg(&copy).output().unwrap();
        assert!(!out.status.success(), "{flag}");
        assert!(String::from_utf8_lossy(&out.stderr).contains("refusing to overwrite"), "{flag}");
        assert_eq!(std::fs::read(&copy).unwrap(), before, "{flag}: input modified");
    }
    // 2171 vertices cannot carry the 40401 functions of order 200.
    let target = dir.join("too_high.ply");
    let out = capmesh().args(["harmonics", "--quiet", "--order", "200"]).arg(&copy).arg("-o").arg(&target).output().unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("helmet.obj.gz") && err.contains("2171 points for 40401 basis functions"), "{err}");
    assert!(!target.exists());
    // An output format that cannot be written is refused up front.
    let out = capmesh().args(["harmonics", "--quiet"]).arg(&copy).arg("-o").arg(dir.join("out.xyz")).output().unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("out.xyz: unknown mesh format"));
    // The planar disk has no cap to put harmonics on.
    let out = capmesh().args(["harmonics", "--quiet", "--domain", "disk"]).arg(&copy).arg("-o").arg(&target).output().unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("not the planar disk"));
}

#[test]
fn shape_analyses_a_cohort_and_names_the_bad_mesh() {
    let dir = TempDir::new("harmonics-cli-cohort");
    let cohort = dir.join("cohort");
    std::fs::create_dir_all(cohort.join("closed")).unwrap();
    std::fs::copy(data("open_meg_helmet_babysquid_mne.obj.gz"), cohort.join("helmet.obj.gz")).unwrap();
    std::fs::copy(data("closed_bunny_npm.obj.gz"), cohort.join("closed/bunny.obj.gz")).unwrap();
    std::fs::copy(data("bad_genus2_bird_skull_choi.obj.gz"), cohort.join("closed/skull_genus2.obj.gz")).unwrap();
    std::fs::write(cohort.join("notes.txt"), "not a mesh\n").unwrap();
    let csv = dir.join("shape.csv");
    let out = capmesh()
        .args(["shape", "--quiet"])
        .arg(&cohort)
        .arg(data("open_lv_endo_rabbit_chaste.obj.gz"))
        .arg("--csv")
        .arg(&csv)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "a genus-2 mesh in the cohort must fail the command");
    assert!(err.contains("skull_genus2.obj.gz") && err.contains("genus 2"), "{err}");
    assert!(err.contains("1 of 4 meshes failed"), "{err}");

    let text = std::fs::read_to_string(&csv).unwrap();
    eprintln!("{text}");
    let table = Table::parse(&text);
    let col = |name: &str| table.col(name);
    let rows: HashMap<String, Vec<String>> = table
        .rows
        .iter()
        .map(|f| {
            let name = Path::new(&f[col("file")]).file_name().unwrap().to_string_lossy().into_owned();
            (name, f.clone())
        })
        .collect();
    assert_eq!(rows.len(), 4, "{:?}", rows.keys().collect::<Vec<_>>());
    for (name, vertices, kind) in [
        ("helmet.obj.gz", "2171", "open"),
        ("bunny.obj.gz", "1839", "closed"),
        ("open_lv_endo_rabbit_chaste.obj.gz", "4239", "open"),
    ] {
        let row = &rows[name];
        assert_eq!(row[col("status")], "ok", "{row:?}");
        assert_eq!(row[col("vertices")], vertices);
        assert_eq!(row[col("kind")], kind);
        assert!(row[col("error")].is_empty());
        let z: f64 = row[col("z_star")].parse().unwrap();
        assert!((-1.0..1.0).contains(&z), "{name}: Z* {z}");
        let s: Vec<f64> = ["sigma1", "sigma2", "sigma3"].iter().map(|c| row[col(c)].parse().unwrap()).collect();
        assert!(s[0] >= s[1] && s[1] >= s[2] && s[2] > 0.0, "{name}: {s:?}");
        let ratio: f64 = row[col("aspect_ratio")].parse().unwrap();
        assert!((ratio - s[0] / s[2]).abs() < 1e-9 * ratio, "{name}: {ratio} vs {s:?}");
        let ellipsoid: f64 = row[col("ellipsoid_aspect_ratio")].parse().unwrap();
        assert!(ellipsoid >= 1.0, "{name}: {ellipsoid}");
    }
    let bad = &rows["skull_genus2.obj.gz"];
    assert_eq!(bad[col("status")], "failed");
    assert!(bad[col("error")].contains("genus 2"), "{bad:?}");
    assert!(bad[col("z_star")].is_empty());

    // The aspect_ratio column is the paper's least-squares ratio, the other the exact ellipsoid.
    let helmet = capmesh::io::read_mesh(&data("open_meg_helmet_babysquid_mne.obj.gz")).unwrap();
    let map = capmesh::param::parameterize(&helmet, &Default::default(), &capmesh::NoProgress).unwrap();
    let z_star = map.report.z_star.unwrap();
    let paper = aspect_ratio(&map.cap, &helmet.vertices, z_star).unwrap().ratio;
    let exact = order_one_ellipsoid(&fit(&map.cap, &helmet.vertices, z_star, 1).unwrap()).unwrap().aspect_ratio();
    let row = &rows["helmet.obj.gz"];
    let (csv_paper, csv_exact): (f64, f64) =
        (row[col("aspect_ratio")].parse().unwrap(), row[col("ellipsoid_aspect_ratio")].parse().unwrap());
    eprintln!("helmet: paper {paper} (csv {csv_paper}), ellipsoid {exact} (csv {csv_exact})");
    assert!((csv_paper - paper).abs() < 1e-6 * paper && (csv_exact - exact).abs() < 1e-6 * exact);
    assert!((paper - exact).abs() > 0.1, "the two ratios should differ on the helmet's small cap");
}

#[test]
fn shape_succeeds_on_good_meshes_and_never_overwrites_an_input() {
    let dir = TempDir::new("harmonics-cli-good");
    let copy = dir.join("helmet.obj.gz");
    std::fs::copy(data("open_meg_helmet_babysquid_mne.obj.gz"), &copy).unwrap();
    let before = std::fs::read(&copy).unwrap();
    let out = capmesh().args(["shape", "--quiet"]).arg(&copy).arg("--csv").arg(&copy).output().unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("refusing to overwrite"));
    assert_eq!(std::fs::read(&copy).unwrap(), before);

    let csv = dir.join("one.csv");
    let out = capmesh().args(["shape", "--quiet", "--jobs", "1"]).arg(&*dir).arg("--csv").arg(&csv).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = std::fs::read_to_string(&csv).unwrap();
    assert_eq!(text.lines().count(), 2, "{text}");
    assert!(text.lines().nth(1).unwrap().contains(",ok,good,2171,"), "{text}");
}

/// A poor map is never a silent success (issue 27): the bundled bunny stretched 300 times
/// along x maps, after every lambda fallback, at a mean |d_area| near 3 (above the 0.3
/// threshold). `shape` marks its row `poor` (the helmet's is `good`) and exits 3;
/// `--allow-poor-map` exits 0 (the rows kept by `--resume` count too); `harmonics` exits 3
/// with the report's `param.quality` `poor`, its outputs written.
#[test]
fn poor_maps_mark_the_shape_row_and_exit_3() {
    let dir = TempDir::new("harmonics-cli-poor");
    let cohort = dir.join("cohort");
    std::fs::create_dir(&cohort).unwrap();
    let mut bunny = capmesh::io::read_mesh(&data("closed_bunny_npm.obj.gz")).unwrap();
    bunny.vertices.iter_mut().for_each(|p| p[0] *= 300.0);
    let stretched = cohort.join("bunny_x300.ply");
    capmesh::io::write_mesh(&stretched, &bunny).unwrap();
    std::fs::copy(data("open_meg_helmet_babysquid_mne.obj.gz"), cohort.join("helmet.obj.gz")).unwrap();

    let csv = dir.join("shape.csv");
    let out = capmesh().args(["shape", "--quiet"]).arg(&cohort).arg("--csv").arg(&csv).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(3), "{err}");
    assert!(err.contains("1 of 2 meshes have a poor map") && err.contains("--allow-poor-map"), "{err}");
    let text = std::fs::read_to_string(&csv).unwrap();
    let table = Table::parse(&text);
    assert_eq!(table.rows.len(), 2, "{text}");
    assert_eq!(table.get("bunny_x300.ply", "quality"), "poor", "{text}");
    assert_eq!(table.get("helmet.obj.gz", "quality"), "good", "{text}");
    let allowed = capmesh().args(["shape", "--quiet", "--resume", "--allow-poor-map"]).arg(&cohort).arg("--csv").arg(&csv).output().unwrap();
    assert!(allowed.status.success(), "{}", String::from_utf8_lossy(&allowed.stderr));
    let again = capmesh().args(["shape", "--quiet", "--resume"]).arg(&cohort).arg("--csv").arg(&csv).output().unwrap();
    assert_eq!(again.status.code(), Some(3), "kept poor rows still count: {}", String::from_utf8_lossy(&again.stderr));

    let report = dir.join("report.json");
    let out = capmesh().args(["harmonics", "--quiet", "--order", "1"]).arg(&stretched).arg("-o").arg(dir.join("rec.ply")).arg("--report").arg(&report).output().unwrap();
    assert_eq!(out.status.code(), Some(3), "{}", String::from_utf8_lossy(&out.stderr));
    let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(json["param"]["quality"], "poor");
    assert!(dir.join("rec.ply").exists());
}
