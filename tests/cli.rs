//! The `capmesh` command line on real meshes: `param` writes the cap mesh and a JSON report
//! with the documented keys; `check` describes good meshes and refuses bad ones with a
//! message naming the problem; the input is never overwritten.

mod common;

use common::{data, TempDir};

use std::path::{Path, PathBuf};
use std::process::Command;

fn capmesh() -> Command {
    Command::new(env!("CARGO_BIN_EXE_capmesh"))
}

#[test]
fn param_writes_cap_mesh_and_report() {
    let dir = TempDir::new("cli-param");
    let out = dir.join("helmet_cap.ply");
    let report = dir.join("report.json");
    let input = data("open_meg_helmet_babysquid_mne.obj.gz");
    let before = std::fs::read(&input).unwrap();
    let status = capmesh()
        .args(["param", "--quiet"])
        .arg(&input)
        .arg("-o")
        .arg(&out)
        .arg("--report")
        .arg(&report)
        .output()
        .unwrap();
    assert!(status.status.success(), "{}", String::from_utf8_lossy(&status.stderr));
    assert_eq!(std::fs::read(&input).unwrap(), before, "input modified");
    let json: serde_json::Value = serde_json::from_slice(&std::fs::read(&report).unwrap()).unwrap();
    for key in ["r_star", "z_star", "newton_iterations", "flipped_faces", "seconds"] {
        assert!(json.get(key).is_some_and(|v| v.is_number()), "report lacks numeric {key}");
    }
    let mean_area = json["area_distortion"]["mean_abs"].as_f64().unwrap();
    let mean_angle = json["angle_distortion"]["mean_abs"].as_f64().unwrap();
    assert!(mean_area > 0.0 && mean_area < 0.12 && mean_angle > 0.0 && mean_angle < 1.0);
    assert_eq!(json["flipped_faces"].as_u64(), Some(0));
    // The written mesh has the input's connectivity and lies on the unit sphere above Z*.
    let cap = capmesh::io::read_mesh(&out).unwrap();
    let orig = capmesh::io::read_mesh(&input).unwrap();
    assert_eq!(cap.faces, orig.faces);
    let z_star = json["z_star"].as_f64().unwrap();
    for p in &cap.vertices {
        assert!(((p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt() - 1.0).abs() < 1e-9);
        assert!(p[2] >= z_star - 1e-9);
    }
}

/// A copy of the MEG helmet in `dir` to serve as an input that must stay untouched, and its
/// bytes.
fn helmet_copy(dir: &Path) -> (PathBuf, Vec<u8>) {
    let copy = dir.join("helmet.obj.gz");
    std::fs::copy(data("open_meg_helmet_babysquid_mne.obj.gz"), &copy).unwrap();
    let bytes = std::fs::read(&copy).unwrap();
    (copy, bytes)
}

#[test]
fn param_refuses_to_overwrite_its_input() {
    let dir = TempDir::new("cli-overwrite");
    let (copy, before) = helmet_copy(&dir);
    let out = capmesh().args(["param", "--quiet"]).arg(&copy).arg("-o").arg(&copy).output().unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("refusing to overwrite"));
    assert_eq!(std::fs::read(&copy).unwrap(), before);
}

/// The same file under another name is still the input: a symbolic link as the output, a
/// hard link as the report.
#[cfg(unix)]
#[test]
fn remesh_refuses_links_to_its_input() {
    let dir = TempDir::new("cli-links");
    let (input, before) = helmet_copy(&dir);
    let soft = dir.join("soft.obj.gz");
    let hard = dir.join("hard.json");
    std::os::unix::fs::symlink(&input, &soft).unwrap();
    std::fs::hard_link(&input, &hard).unwrap();
    let as_output = capmesh().args(["--quiet", "remesh"]).arg(&input).arg("-o").arg(&soft).output().unwrap();
    assert!(!as_output.status.success());
    assert!(String::from_utf8_lossy(&as_output.stderr).contains("refusing to overwrite"), "{}", String::from_utf8_lossy(&as_output.stderr));
    let as_report = capmesh().args(["--quiet", "remesh"]).arg(&input).arg("-o").arg(dir.join("out.obj")).arg("--report").arg(&hard).output().unwrap();
    assert!(!as_report.status.success());
    assert!(String::from_utf8_lossy(&as_report.stderr).contains("refusing to overwrite"));
    assert_eq!(std::fs::read(&input).unwrap(), before);
}

#[test]
fn check_describes_an_open_disk() {
    let out = capmesh().arg("check").arg(data("open_lv_endo_rabbit_chaste.obj.gz")).output().unwrap();
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("vertices             4239"), "{text}");
    assert!(text.contains("boundary loops       1"));
    assert!(text.contains("Euler characteristic 1"));
    assert!(text.contains("open disk"));
}

#[test]
fn check_and_param_refuse_genus_two() {
    let dir = TempDir::new("cli-g2");
    for sub in ["check", "param"] {
        let mut cmd = capmesh();
        cmd.arg(sub).arg(data("bad_genus2_bird_skull_choi.obj.gz"));
        if sub == "param" {
            cmd.args(["--quiet", "-o"]).arg(dir.join("x.obj"));
        }
        let out = cmd.output().unwrap();
        assert!(!out.status.success(), "{sub} accepted a genus-2 surface");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("genus 2") && err.contains("bad_genus2_bird_skull_choi"), "{sub}: {err}");
    }
}

#[test]
fn param_refuses_an_annulus_with_a_clear_message() {
    let dir = TempDir::new("cli-annulus");
    let path = dir.join("annulus.obj");
    capmesh::io::write_mesh(&path, &capmesh::mesh::shapes::annulus(0.5, 1.0, 4, 24)).unwrap();
    let out = capmesh().args(["param", "--quiet"]).arg(&path).arg("-o").arg(dir.join("o.obj")).output().unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("2 boundary loops"), "{err}");
}

#[test]
fn truncated_file_is_refused_with_its_name() {
    let dir = TempDir::new("cli-trunc");
    let path = dir.join("cut.ply");
    let bytes = capmesh::io::write_mesh_to_bytes(&capmesh::mesh::shapes::grid_disk(6), capmesh::io::Format::Ply).unwrap();
    std::fs::write(&path, &bytes[..bytes.len() * 2 / 3]).unwrap();
    let out = capmesh().arg("check").arg(&path).output().unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("cut.ply") && err.contains("truncated"), "{err}");
}

/// A fold-free but poor map is never a silent success: the bunny's plain centroid map from the
/// plain stretch-energy map (lambda = 1, no smoothing, no refinement) is far from area
/// preserving; the CLI says so on stderr, the report says `quality: poor`, and the command
/// exits 3 (0 with --allow-poor-map), the outputs written either way. The default map of the
/// same mesh does not warn and is `good`.
#[test]
fn poor_maps_are_reported_and_exit_3() {
    let dir = TempDir::new("cli-poor_map");
    let input = data("closed_bunny_npm.obj.gz");
    let poor_args = ["--lambda", "1", "--smoothing", "0", "--area-refinement", "0", "--puncture-end", "bottom"];
    let report = dir.join("poor.json");
    let poor = capmesh().args(["--quiet", "param"]).arg(&input).arg("-o").arg(dir.join("poor.obj")).arg("--report").arg(&report).args(poor_args).output().unwrap();
    let err = String::from_utf8_lossy(&poor.stderr);
    assert_eq!(poor.status.code(), Some(3), "{err}");
    assert!(err.contains("warning") && err.contains("far from area preserving"), "{err}");
    assert!(err.contains("poor map") && err.contains("--allow-poor-map"), "{err}");
    let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(json["quality"], "poor");
    assert!(dir.join("poor.obj").exists(), "the outputs of a poor map are written");
    let allowed = capmesh().args(["--quiet", "param"]).arg(&input).arg("-o").arg(dir.join("poor.obj")).args(poor_args).arg("--allow-poor-map").output().unwrap();
    assert!(allowed.status.success(), "{}", String::from_utf8_lossy(&allowed.stderr));
    let remesh_report = dir.join("remesh.json");
    let remeshed = capmesh()
        .args(["--quiet", "remesh"])
        .arg(&input)
        .arg("-o")
        .arg(dir.join("remesh.obj"))
        .args(["--faces", "1000", "--optimize", "none", "--report"])
        .arg(&remesh_report)
        .args(poor_args)
        .output()
        .unwrap();
    assert_eq!(remeshed.status.code(), Some(3), "{}", String::from_utf8_lossy(&remeshed.stderr));
    let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&remesh_report).unwrap()).unwrap();
    assert_eq!(json["quality"], "poor");

    let report = dir.join("good.json");
    let good = capmesh().args(["--quiet", "param"]).arg(&input).arg("-o").arg(dir.join("good.obj")).arg("--report").arg(&report).output().unwrap();
    assert!(good.status.success());
    assert!(!String::from_utf8_lossy(&good.stderr).contains("warning"), "{}", String::from_utf8_lossy(&good.stderr));
    let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(json["quality"], "good");
}

/// The bundled bunny changed by `change`, written to `name` in `dir`.
fn bunny_variant(dir: &Path, name: &str, change: impl FnOnce(&mut capmesh::TriMesh)) -> PathBuf {
    let mut mesh = capmesh::io::read_mesh(&data("closed_bunny_npm.obj.gz")).unwrap();
    change(&mut mesh);
    let path = dir.join(name);
    capmesh::io::write_mesh(&path, &mesh).unwrap();
    path
}

/// A closed surface too elongated for the paper's lambda (the bunny stretched 10 times
/// along its axis) is mapped with a larger one, and stderr says which and why;
/// `--no-lambda-fallback` gives the transport's error instead, naming the remedy.
#[test]
fn elongated_closed_surfaces_fall_back_to_a_larger_lambda() {
    let dir = TempDir::new("cli-lambda_fallback");
    let input = bunny_variant(&dir, "bunny_x10.obj", |mesh| mesh.vertices.iter_mut().for_each(|p| p[0] *= 10.0));
    let report = dir.join("report.json");
    let out = capmesh().args(["--quiet", "param"]).arg(&input).arg("-o").arg(dir.join("cap.obj")).arg("--report").arg(&report).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(err.contains("not kept: lambda = 0.2: optimal transport stalled") && err.contains("mapped with lambda = "), "{err}");
    let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(json["lambda_fallbacks"][0]["lambda"], 0.2, "{json}");
    assert!(json["flatten"]["lambda"].as_f64().unwrap() > 0.2, "{json}");
    let refused = capmesh().args(["--quiet", "param"]).arg(&input).arg("-o").arg(dir.join("cap2.obj")).arg("--no-lambda-fallback").output().unwrap();
    let err = String::from_utf8_lossy(&refused.stderr);
    assert!(!refused.status.success(), "{err}");
    assert!(err.contains("bunny_x10.obj") && err.contains("stalled") && err.contains("larger lambda"), "{err}");
}

/// A long bone that stalls at every `lambda` is mapped by the rescue round (more
/// stretch-energy iterations), and stderr and the report say so.
#[test]
fn a_long_bone_is_mapped_by_the_rescue_round() {
    let dir = TempDir::new("cli-rescue");
    let input = dir.join("long_bone.obj");
    capmesh::io::write_mesh(&input, &common::long_bone(8.5, 212, 32)).unwrap();
    let report = dir.join("report.json");
    let out = capmesh().args(["--quiet", "param"]).arg(&input).arg("-o").arg(dir.join("cap.obj")).arg("--report").arg(&report).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(err.contains("not kept: lambda = 1: optimal transport stalled") && err.contains("mapped with lambda = 0.8 after 80 stretch-energy iterations (the transport stalled at every lambda"), "{err}");
    let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(json["lambda_fallbacks"].as_array().map(Vec::len), Some(4), "{json}");
    assert_eq!(json["lambda_fallbacks"][3]["stretch_iterations"], 10, "{json}");
    assert_eq!(json["flatten"]["stretch"]["iterations"], 80, "{json}");
}

/// An open surface whose boundary is one small triangle (the bunny with one face removed):
/// the cap's whole rim is pulled back onto three short edges and a few remeshed faces next to
/// them have zero area. The remesh says so on stderr and counts them in its report rather
/// than pass them silently.
#[test]
fn zero_area_faces_in_a_remesh_are_reported() {
    let dir = TempDir::new("cli-zero_area");
    let input = bunny_variant(&dir, "bunny_hole.obj", |mesh| {
        mesh.faces.remove(0);
    });
    let report = dir.join("report.json");
    let out = capmesh().args(["--quiet", "remesh"]).arg(&input).arg("-o").arg(dir.join("out.ply")).arg("--report").arg(&report).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    let count = json["zero_area_faces"].as_u64().expect("zero_area_faces in the report");
    let checked = capmesh::mesh::inspect(&capmesh::io::read_mesh(&dir.join("out.ply")).unwrap()).unwrap();
    assert_eq!(count as usize, checked.zero_area_faces, "the report and `check` count the same faces");
    if count > 0 {
        assert!(err.contains("zero-area faces"), "{err}");
    } else {
        assert!(!err.contains("zero-area"), "{err}");
    }
}

/// A remesh whose faces cross where the input's do not is never silent: the bird skull's plain
/// pull-back (`--optimize none`, the paper's remesh) crosses itself at its thin bones, and stderr
/// says how many faces cross; the default remesh of the same mesh crosses nowhere and does not
/// warn.
#[test]
fn self_crossing_remeshes_are_reported() {
    let dir = TempDir::new("cli-self_crossing");
    let input = data("closed_bird_skull_CPallidusA_choi.obj.gz");
    let remesh = |name: &str, args: &[&str]| {
        let report = dir.join(format!("{name}.json"));
        let out = capmesh().args(["--quiet", "remesh"]).arg(&input).arg("-o").arg(dir.join(format!("{name}.ply"))).arg("--report").arg(&report).args(args).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr).into_owned();
        assert!(out.status.success(), "{err}");
        let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
        (err, json["self_intersecting_faces"].as_u64().unwrap(), json["self_intersecting_faces_input"].as_u64().unwrap())
    };
    let (err, crossing, input_crossing) = remesh("plain", &["--optimize", "none", "--placement", "on-surface"]);
    assert!(crossing > input_crossing, "{crossing} crossing faces (input {input_crossing})");
    assert!(err.contains(&format!("{crossing} faces of the remesh cross another face (the input has {input_crossing})")), "{err}");
    let (err, crossing, _) = remesh("shaped", &[]);
    assert_eq!(crossing, 0);
    assert!(!err.contains("cross another face"), "{err}");
}

/// `--placement`: fitted by default (the vertices off the surface, the fit's report in the
/// JSON), on the surface when asked; an unknown placement is refused by name.
#[test]
fn the_vertex_placement_is_chosen_on_the_command_line() {
    let dir = TempDir::new("cli-placement");
    let input = data("open_lv_endo_rabbit_chaste.obj.gz");
    let remesh = |name: &str, args: &[&str]| {
        let report = dir.join(format!("{name}.json"));
        let out = capmesh().args(["--quiet", "remesh"]).arg(&input).arg("-o").arg(dir.join(format!("{name}.ply"))).args(["--faces", "1000", "--report"]).arg(&report).args(args).output().unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        serde_json::from_str::<serde_json::Value>(&std::fs::read_to_string(&report).unwrap()).unwrap()
    };
    let fitted = remesh("fitted", &[]);
    let on = remesh("on", &["--placement", "on-surface"]);
    assert_eq!((&fitted["fit"]["fitted"], &on["fit"]["fitted"]), (&serde_json::json!(true), &serde_json::json!(false)));
    let f = |j: &serde_json::Value, k: &str| j[k].as_f64().unwrap();
    assert!(f(&on, "d_surface_vertex_relative") < 1e-9 && f(&fitted, "d_surface_vertex_relative") > 0.0);
    assert!(f(&fitted, "d_surface_sampled_relative") < f(&on, "d_surface_sampled_relative"));
    let out = capmesh().args(["remesh"]).arg(&input).arg("-o").arg(dir.join("x.ply")).args(["--placement", "floating"]).output().unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("floating") && err.contains("on-surface"), "{err}");
    assert!(!dir.join("x.ply").exists());
}

#[test]
fn closed_standard_output_ends_quietly() {
    // `capmesh check mesh | head -1`: the reader goes away before capmesh writes (the pipe's
    // read end is closed while the 53k-vertex mesh is still being read). Writing used to
    // panic ("failed printing to stdout: Broken pipe").
    let mut child = capmesh()
        .arg("check")
        .arg(data("open_hand_choi.obj.gz"))
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(out.status.success(), "status {:?}, stderr {stderr}", out.status);
}

#[test]
fn huge_cap_meshes_are_refused_before_any_work() {
    // An accidental face count used to run until memory ran out.
    let dir = TempDir::new("cli-huge");
    let input = data("open_meg_helmet_babysquid_mne.obj.gz");
    for args in [vec!["--faces", "99999999999"], vec!["--lat-long", "--rings", "100000", "--sectors", "100000"]] {
        let out = capmesh().args(["remesh", "--quiet"]).arg(&input).arg("-o").arg(dir.join("huge.ply")).args(&args).output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?} accepted");
        assert!(stderr.contains("more than capmesh remeshes") && stderr.contains("50000000"), "{args:?}: {stderr}");
        assert!(!dir.join("huge.ply").exists());
    }
}

#[test]
fn shape_options_out_of_range_are_refused_before_any_work() {
    // A NaN shape weight or polish tolerance used to give a remesh without a word.
    let dir = TempDir::new("cli-shape-options");
    let input = data("open_meg_helmet_babysquid_mne.obj.gz");
    for (arg, named) in [("--shape-weight=nan", "shape_weight = NaN"), ("--shape-weight=-1", "shape_weight = -1"), ("--polish-tolerance=inf", "polish_tolerance = inf")] {
        let out = capmesh().args(["remesh", "--quiet"]).arg(&input).arg("-o").arg(dir.join("r.ply")).arg(arg).output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{arg} accepted");
        assert!(stderr.contains(named) && stderr.contains("open_meg_helmet"), "{arg}: {stderr}");
        assert!(!dir.join("r.ply").exists());
    }
}

#[test]
fn fixed_radii_outside_the_search_range_are_refused() {
    // radius=1000 used to give ten folded faces and mean |d_area| 0.58 without a word.
    let dir = TempDir::new("cli-radius");
    let input = data("open_meg_helmet_babysquid_mne.obj.gz");
    for r in ["1000", "0.001", "1e6"] {
        let out = capmesh().args(["param", "--quiet"]).arg(&input).arg("-o").arg(dir.join("r.ply")).arg("--domain").arg(format!("radius={r}")).output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "radius={r} accepted");
        assert!(stderr.contains("outside [0.05, 20]"), "radius={r}: {stderr}");
    }
    let ok = capmesh().args(["param", "--quiet"]).arg(&input).arg("-o").arg(dir.join("r.ply")).args(["--domain", "radius=2"]).output().unwrap();
    assert!(ok.status.success(), "{}", String::from_utf8_lossy(&ok.stderr));
}

/// `remesh` takes the parameterization options `param` takes (one set of flags,
/// `map_args.rs`): they reach the library (the report says so) and bad values are refused.
#[test]
fn remesh_takes_the_parameterization_options() {
    let dir = TempDir::new("cli-remesh_options");
    let input = data("closed_bunny_npm.obj.gz");
    let report = dir.join("report.json");
    let run = capmesh()
        .args(["--quiet", "remesh"])
        .arg(&input)
        .arg("-o")
        .arg(dir.join("bunny.ply"))
        .arg("--report")
        .arg(&report)
        .args(["--faces", "800", "--puncture-end", "top", "--search-sites", "0", "--smoothing", "0", "--area-refinement", "5", "--lambda", "0.3"])
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let json: serde_json::Value = serde_json::from_slice(&std::fs::read(&report).unwrap()).unwrap();
    let p = &json["parameterization"];
    assert_eq!(p["puncture_trials"].as_array().map(|a| a.len()), Some(0), "one end only");
    assert!(p["search_sites"].is_null(), "--search-sites 0 searches at full resolution");
    assert_eq!(p["smoothing_kappa"].as_f64(), Some(0.0));
    assert_eq!(p["area_refinement"]["sweeps"].as_u64(), Some(5));
    assert_eq!(p["flatten"]["lambda"].as_f64(), Some(0.3));
    let bad = capmesh().args(["--quiet", "remesh"]).arg(&input).arg("-o").arg(dir.join("bad.ply")).args(["--lambda", "2"]).output().unwrap();
    assert!(!bad.status.success());
    let err = String::from_utf8_lossy(&bad.stderr);
    assert!(err.contains("lambda") && err.contains("closed_bunny_npm"), "{err}");
}

/// `--threads` sets the worker threads, and the remeshes do not depend on them: a closed
/// surface (both puncture ends searched in parallel) and an open one remesh to the same
/// bytes on one, two and three threads. `--threads 0` is refused by name.
#[test]
fn results_do_not_depend_on_the_number_of_threads() {
    let dir = TempDir::new("cli-threads");
    for name in ["closed_bunny_npm.obj.gz", "open_lv_endo_rabbit_chaste.obj.gz"] {
        let outputs: Vec<Vec<u8>> = ["1", "2", "3"]
            .iter()
            .map(|threads| {
                let out = dir.join(format!("{threads}-{name}.ply"));
                let run = capmesh().args(["--threads", threads, "remesh", "--quiet"]).arg(data(name)).arg("-o").arg(&out).output().unwrap();
                assert!(run.status.success(), "{name} on {threads} threads: {}", String::from_utf8_lossy(&run.stderr));
                std::fs::read(&out).unwrap()
            })
            .collect();
        assert!(!outputs[0].is_empty());
        assert!(outputs.iter().all(|o| o == &outputs[0]), "{name}: the remesh depends on the number of threads");
    }
    let refused = capmesh().args(["--threads", "0", "check"]).arg(data("closed_bunny_npm.obj.gz")).output().unwrap();
    assert!(!refused.status.success());
    assert!(String::from_utf8_lossy(&refused.stderr).contains("--threads"), "{}", String::from_utf8_lossy(&refused.stderr));
}

/// The multilevel map (issue 27) is the same bytes on any number of threads too: the 12k brain
/// subdivided once, mapped through a decimated copy of 12.5k vertices (thresholds lowered from
/// their defaults so that a small mesh takes that path), on 1 and 2 threads.
#[test]
fn multilevel_maps_do_not_depend_on_the_number_of_threads() {
    let dir = TempDir::new("cli-multilevel");
    let fine = capmesh::mesh::subdivide_midpoint(&capmesh::io::read_mesh(&data("closed_brain12k_choi.obj.gz")).unwrap(), 1);
    let input = dir.join("brain12k_x1.ply");
    capmesh::io::write_mesh(&input, &fine).unwrap();
    let outputs: Vec<(Vec<u8>, serde_json::Value)> = ["1", "2"]
        .iter()
        .map(|threads| {
            let out = dir.join(format!("{threads}.ply"));
            let json = dir.join(format!("{threads}.json"));
            let run = capmesh()
                .args(["--threads", threads, "param", "--quiet", "--multilevel-above", "20000", "--coarse-vertices", "12500"])
                .arg(&input)
                .arg("-o")
                .arg(&out)
                .arg("--report")
                .arg(&json)
                .output()
                .unwrap();
            assert!(run.status.success(), "on {threads} threads: {}", String::from_utf8_lossy(&run.stderr));
            (std::fs::read(&out).unwrap(), serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap())
        })
        .collect();
    assert_eq!(outputs[0].1["multilevel"]["coarse_vertices"], 12500, "{}", outputs[0].1["multilevel"]);
    assert!(outputs[0].0 == outputs[1].0, "the multilevel map depends on the number of threads");
}

/// `capmesh metrics --json` has the shape figures (issue 26) beside the earlier keys, the
/// same report on one and three threads, and a mesh measured against itself has the input's
/// own self-intersection count and no Hausdorff distance.
#[test]
fn metrics_report_shape_and_self_intersections() {
    let dir = TempDir::new("cli-metrics");
    let input = data("closed_bunny_npm.obj.gz");
    let remeshed = dir.join("bunny.ply");
    let remesh_json = dir.join("bunny.json");
    let run = capmesh().args(["remesh", "--quiet"]).arg(&input).arg("-o").arg(&remeshed).args(["--faces", "2000", "--report"]).arg(&remesh_json).output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let report = |threads: &str, a: &Path, b: &Path| {
        let run = capmesh().args(["--threads", threads, "metrics", "--json"]).arg(a).arg(b).output().unwrap();
        assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
        run.stdout
    };
    let one = report("1", &input, &remeshed);
    assert_eq!(one, report("3", &input, &remeshed), "the metrics depend on the number of threads");
    let json: serde_json::Value = serde_json::from_slice(&one).unwrap();
    for key in [
        "faces",
        "d_face_relative",
        "d_surface_sampled_relative",
        "min_angle_deg",
        "zero_area_faces",
        "mean_min_angle_deg",
        "share_faces_angle_below_30",
        "max_angle_deg",
        "share_interior_valence_6",
        "self_intersecting_faces",
        "self_intersecting_faces_input",
        "hausdorff_distance",
        "hausdorff_distance_relative",
    ] {
        assert!(json.get(key).is_some_and(|v| v.is_number()), "metrics lack numeric {key}");
    }
    let f = |k: &str| json[k].as_f64().unwrap();
    assert!(f("min_angle_deg") <= f("mean_min_angle_deg") && f("mean_min_angle_deg") <= 60.0);
    assert!(f("max_angle_deg") >= 60.0 && f("max_angle_deg") <= 180.0);
    assert!((0.0..=1.0).contains(&f("share_faces_angle_below_30")) && (0.0..=1.0).contains(&f("share_interior_valence_6")));
    assert!(f("hausdorff_distance") >= f("d_surface_vertex") && f("hausdorff_distance_relative") < 0.1);
    assert_eq!(json["self_intersecting_faces_input"].as_u64(), Some(0), "the bunny does not intersect itself");
    // The remesh's own report has the same figures as `metrics` of the written mesh (the
    // angles to the precision the PLY's coordinates keep).
    let own: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&remesh_json).unwrap()).unwrap();
    for key in ["mean_min_angle_deg", "share_faces_angle_below_30", "max_angle_deg", "share_interior_valence_6", "hausdorff_distance_relative"] {
        let (a, b) = (own[key].as_f64(), json[key].as_f64());
        assert!(a.zip(b).is_some_and(|(a, b)| (a - b).abs() <= 1e-6 * b.abs().max(1.0)), "remesh report {key} {a:?} vs metrics {b:?}");
    }
    for key in ["self_intersecting_faces", "self_intersecting_faces_input", "faces"] {
        assert_eq!(own[key], json[key], "remesh report {key}");
    }
    let same: serde_json::Value = serde_json::from_slice(&report("2", &remeshed, &remeshed)).unwrap();
    assert_eq!(same["self_intersecting_faces"], json["self_intersecting_faces"]);
    assert_eq!(same["self_intersecting_faces_input"], json["self_intersecting_faces"]);
    assert!(same["hausdorff_distance"].as_f64().unwrap() < 1e-12);
}
