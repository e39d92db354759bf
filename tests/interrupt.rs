//! Nothing is lost when a run is stopped or fails (real processes, no timing assertions):
//! `remesh` killed at random moments with SIGKILL or SIGTERM leaves its target absent, as it
//! was, or a complete mesh that `capmesh check` accepts; a write past `ulimit -f` and
//! unwritable paths fail with a named error and leave the earlier output intact; `shape`
//! stopped after a few rows and resumed writes byte for byte the CSV of an uninterrupted run.

mod common;

use common::{data, Rng, TempDir};

use std::path::{Path, PathBuf};
use std::process::{Child, Command, ExitStatus, Output, Stdio};
use std::time::Duration;

fn capmesh() -> Command {
    Command::new(env!("CARGO_BIN_EXE_capmesh"))
}

/// Send `signal` (`TERM`, `KILL`, `INT`) to `child` with the shell's `kill`.
fn signal(child: &Child, signal: &str) {
    // `kill` fails only when the process has already ended: nothing to check.
    let _ = Command::new("sh").arg("-c").arg(format!("kill -s {signal} {}", child.id())).stderr(Stdio::null()).status().unwrap();
}

/// Poll until `ready()` or the child ends; `true` when `ready()` held while it ran.
fn wait_until(child: &mut Child, mut ready: impl FnMut() -> bool) -> bool {
    loop {
        if ready() {
            return true;
        }
        if child.try_wait().unwrap().is_some() {
            return false;
        }
        std::thread::sleep(Duration::from_millis(5));
    }
}

/// Temporary files of capmesh's atomic writes in `dir`.
fn temporaries(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".capmesh-tmp-"))
        .collect()
}

fn stderr_of(child: Child) -> (ExitStatus, String) {
    let out = child.wait_with_output().unwrap();
    (out.status, String::from_utf8_lossy(&out.stderr).into_owned())
}

/// The signal that ended a process, if one did.
fn killed_by(status: &ExitStatus) -> Option<i32> {
    use std::os::unix::process::ExitStatusExt;
    status.signal()
}

/// A bumpy height-field disk of about 7000 vertices (the stage benchmark's open mesh).
fn synthetic_disk(dir: &Path) -> PathBuf {
    let mut mesh = capmesh::mesh::shapes::grid_disk(48);
    for p in &mut mesh.vertices {
        p[2] = 0.25 * (3.0 * p[0]).sin() * (4.0 * p[1]).cos() + 0.3 * p[0] * p[0];
    }
    let path = dir.join("disk.ply");
    capmesh::io::write_mesh(&path, &mesh).unwrap();
    path
}

/// A remesh of the synthetic disk into 80 000 faces (a 4 MB OBJ), killed 20 times at random
/// moments: half by SIGKILL, half by SIGTERM, half of them while the output is being written
/// (up to 0.2 s after its temporary appears), half at a random delay (up to 1.5 s). The target is then absent, the
/// earlier file, or a complete mesh `capmesh check` accepts; after SIGTERM the command says
/// so in one line, exits 143 and leaves no temporary.
#[test]
fn remesh_killed_at_random_moments_leaves_no_partial_target() {
    let dir = TempDir::new("interrupt-remesh");
    let input = synthetic_disk(&dir);
    let target = dir.join("remesh.obj");
    let earlier_run = capmesh().args(["--quiet", "remesh"]).arg(&input).arg("-o").arg(&target).args(["--faces", "2000", "--optimize", "none"]).output().unwrap();
    assert!(earlier_run.status.success(), "{}", String::from_utf8_lossy(&earlier_run.stderr));
    let earlier = std::fs::read(&target).unwrap();

    let mut rng = Rng(29);
    let (mut interrupted, mut during_write, mut replaced) = (0, 0, 0);
    for round in 0..20 {
        let keep_earlier = round % 4 < 2;
        if keep_earlier {
            std::fs::write(&target, &earlier).unwrap();
        } else {
            let _ = std::fs::remove_file(&target);
        }
        let sig = if round % 2 == 0 { "KILL" } else { "TERM" };
        let mut child = capmesh()
            .args(["--quiet", "remesh"])
            .arg(&input)
            .arg("-o")
            .arg(&target)
            .args(["--faces", "80000", "--optimize", "none"])
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        if round % 4 == 1 || round % 4 == 2 {
            // While the output is written.
            if wait_until(&mut child, || !temporaries(&dir).is_empty()) {
                during_write += 1;
                // The write takes a few hundredths of a second: some kills land after the rename.
                std::thread::sleep(Duration::from_micros(rng.below(200_000) as u64));
            }
        } else {
            std::thread::sleep(Duration::from_millis(rng.below(1500) as u64));
        }
        signal(&child, sig);
        let own = format!(".capmesh-tmp-{}-", child.id());
        let (status, err) = stderr_of(child);

        match std::fs::read(&target) {
            Err(_) => assert!(!keep_earlier, "round {round}: the earlier output was removed"),
            Ok(bytes) if keep_earlier && bytes == earlier => {}
            Ok(_) => {
                replaced += 1;
                let check = capmesh().arg("check").arg(&target).output().unwrap();
                assert!(check.status.success(), "round {round} ({sig}): the target is not a complete mesh: {}", String::from_utf8_lossy(&check.stderr));
            }
        }
        if sig == "TERM" {
            match status.code() {
                Some(143) => {
                    interrupted += 1;
                    let last = err.lines().last().unwrap_or_default();
                    assert!(last.starts_with("capmesh: interrupted by SIGTERM: remesh of "), "round {round}: {err}");
                    // (A SIGKILL of an earlier round may have left its own.)
                    assert!(!temporaries(&dir).iter().any(|t| t.starts_with(&own)), "round {round}: temporaries left: {:?}", temporaries(&dir));
                }
                Some(0) => assert!(std::fs::read(&target).is_ok_and(|b| b != earlier), "round {round}: success without a new output"),
                // Before the handler was installed: the default action.
                _ => assert_eq!(killed_by(&status), Some(15), "round {round}: {status:?} {err}"),
            }
        }
    }
    eprintln!("{interrupted} of 10 SIGTERM runs stopped cleanly, {during_write} kills while writing, {replaced} complete new targets");
    assert!(interrupted > 0, "no SIGTERM run was interrupted by its handler");

    // A finished run removes the temporaries that SIGKILL left behind.
    let last = capmesh().args(["--quiet", "remesh"]).arg(&input).arg("-o").arg(&target).args(["--faces", "2000", "--optimize", "none"]).output().unwrap();
    assert!(last.status.success(), "{}", String::from_utf8_lossy(&last.stderr));
    assert!(temporaries(&dir).is_empty(), "{:?}", temporaries(&dir));
}

/// Ctrl-C (SIGINT) during a `param` of the hand (53k vertices): exit 130 and one line naming
/// the command, the file and the stage; no output, no temporary. A run that ends before the
/// signal, or gets it before its handler is installed, is tried again (at most five times).
#[test]
fn sigint_stops_param_with_130() {
    let dir = TempDir::new("interrupt-sigint");
    let target = dir.join("hand_cap.ply");
    let mut rng = Rng(130);
    let mut stopped = false;
    for _ in 0..5 {
        let child = capmesh().args(["--quiet", "param"]).arg(data("open_hand_choi.obj.gz")).arg("-o").arg(&target).stdout(Stdio::null()).stderr(Stdio::piped()).spawn().unwrap();
        std::thread::sleep(Duration::from_millis(300 + rng.below(700) as u64));
        signal(&child, "INT");
        let (status, err) = stderr_of(child);
        if status.code() == Some(130) {
            assert_eq!(err.lines().count(), 1, "{err}");
            assert!(err.starts_with("capmesh: interrupted by SIGINT: param of ") && err.contains("open_hand_choi.obj.gz") && err.contains("stopped during"), "{err}");
            assert!(!target.exists() && temporaries(&dir).is_empty());
            stopped = true;
            break;
        }
        let _ = std::fs::remove_file(&target);
    }
    assert!(stopped, "no run was stopped by its SIGINT handler");
}

/// `param` under `ulimit -f 16` (8 KiB): the cap mesh does not fit, the command names the
/// file and the limit, exits 1, and the earlier mesh and report are unchanged, with no
/// temporary left.
#[test]
fn writes_past_the_file_size_limit_fail_cleanly() {
    let dir = TempDir::new("interrupt-ulimit");
    let input = data("closed_bunny_npm.obj.gz");
    let (target, report) = (dir.join("cap.ply"), dir.join("report.json"));
    let first = capmesh().args(["--quiet", "param"]).arg(&input).arg("-o").arg(&target).arg("--report").arg(&report).output().unwrap();
    assert!(first.status.success(), "{}", String::from_utf8_lossy(&first.stderr));
    let (mesh_before, report_before) = (std::fs::read(&target).unwrap(), std::fs::read(&report).unwrap());
    let limited = Command::new("sh")
        .arg("-c")
        .arg("ulimit -f 16; exec \"$0\" --quiet param \"$1\" -o \"$2\" --report \"$3\" --puncture-end top")
        .arg(env!("CARGO_BIN_EXE_capmesh"))
        .arg(&input)
        .arg(&target)
        .arg(&report)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&limited.stderr);
    assert_eq!(limited.status.code(), Some(1), "{err}");
    assert!(err.contains("cannot write") && err.contains("cap.ply") && err.contains("ulimit -f"), "{err}");
    assert_eq!(std::fs::read(&target).unwrap(), mesh_before);
    assert_eq!(std::fs::read(&report).unwrap(), report_before);
    assert!(temporaries(&dir).is_empty(), "{:?}", temporaries(&dir));
}

/// Outputs that cannot be written are named errors saying what to do, before or after the
/// computation, and touch nothing (root may write anywhere, so no permission case).
#[test]
fn unwritable_outputs_are_named_errors() {
    let dir = TempDir::new("interrupt-paths");
    let input = data("open_meg_helmet_babysquid_mne.obj.gz");
    std::fs::create_dir(dir.join("out.obj")).unwrap();
    let file = dir.file("plain.txt", b"not a directory\n");
    for (output, expected) in [
        (dir.join("out.obj"), "the path is a directory"),
        (file.join("cap.obj"), "not a directory"),
        (dir.join("missing/cap.obj"), "the directory does not exist"),
    ] {
        let out = capmesh().args(["--quiet", "param"]).arg(&input).arg("-o").arg(&output).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{err}");
        assert!(err.contains(&format!("cannot write {}", output.display())) && err.contains(expected), "{err}");
    }
    assert_eq!(std::fs::read(&file).unwrap(), b"not a directory\n");
    assert!(temporaries(&dir).is_empty());
    let same = capmesh().args(["--quiet", "param"]).arg(&input).arg("-o").arg(dir.join("a.obj")).arg("--report").arg(dir.join("a.obj")).output().unwrap();
    assert!(String::from_utf8_lossy(&same.stderr).contains("two outputs name the same file"), "{}", String::from_utf8_lossy(&same.stderr));
}

/// The lines of a file (0 when absent).
fn line_count(path: &Path) -> usize {
    std::fs::read_to_string(path).map_or(0, |t| t.lines().count())
}

fn shape(cohort: &Path, csv: &Path, extra: &[&str]) -> Command {
    let mut c = capmesh();
    c.args(["--quiet", "shape"]).arg(cohort).arg("--csv").arg(csv).args(extra).stdout(Stdio::piped()).stderr(Stdio::piped());
    c
}

fn run(mut c: Command) -> (Output, String) {
    let out = c.output().unwrap();
    let text = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    (out, text)
}

/// `shape` over seven bundled meshes (one of them the genus-2 skull, a failed row): stopped by
/// SIGTERM after two rows, resumed and killed by SIGKILL after four, then resumed to the end,
/// it writes the bytes of an uninterrupted run. Resuming again keeps every row; a touched file
/// is analysed again by modification time but kept by hash; --retry-failed retries the skull.
#[test]
fn shape_stopped_and_resumed_writes_the_uninterrupted_csv() {
    let dir = TempDir::new("interrupt-shape");
    let cohort = dir.join("cohort");
    std::fs::create_dir(&cohort).unwrap();
    for name in [
        "bad_genus2_bird_skull_choi",
        "closed_bird_skull_CPallidusA_choi",
        "closed_bunny_npm",
        "closed_hippocampus_choi",
        "open_lv_endo_rabbit_chaste",
        "open_meg_helmet_babysquid_mne",
        "open_hippocampus_sheet_hippunfold",
    ] {
        std::fs::copy(data(&format!("{name}.obj.gz")), cohort.join(format!("{name}.obj.gz"))).unwrap();
    }
    let full = dir.join("full.csv");
    let (out, text) = run(shape(&cohort, &full, &["--jobs", "2"]));
    assert_eq!(out.status.code(), Some(1), "the genus-2 skull fails the run: {text}");
    let expected = std::fs::read(&full).unwrap();
    assert_eq!(line_count(&full), 8);

    let csv = dir.join("resumed.csv");
    let partial = dir.join("resumed.csv.partial");
    // SIGTERM after two rows: the rows stay in the partial file, the CSV is not written.
    let mut child = shape(&cohort, &csv, &["--jobs", "1"]).spawn().unwrap();
    let reached = wait_until(&mut child, || line_count(&partial) >= 3);
    signal(&child, "TERM");
    let (status, err) = stderr_of(child);
    if reached && status.code() == Some(143) {
        assert!(err.contains("interrupted by SIGTERM") && err.contains("--resume") && err.contains("resumed.csv.partial"), "{err}");
        assert!(!csv.exists() && line_count(&partial) >= 3);
    }
    // SIGKILL after four rows of a resumed run (or at its end, if it is quicker).
    let mut child = shape(&cohort, &csv, &["--jobs", "1", "--resume"]).spawn().unwrap();
    wait_until(&mut child, || line_count(&partial) >= 5);
    signal(&child, "KILL");
    let _ = child.wait().unwrap();
    // To the end, on two jobs.
    let (out, text) = run(shape(&cohort, &csv, &["--jobs", "2", "--resume"]));
    assert_eq!(out.status.code(), Some(1), "{text}");
    assert!(text.contains("kept from an earlier run"), "{text}");
    assert_eq!(std::fs::read(&csv).unwrap(), expected, "resumed CSV differs: {text}");
    assert!(!partial.exists());

    // Everything kept; then one file touched (same content, new modification time).
    let (_, text) = run(shape(&cohort, &csv, &["--resume"]));
    assert!(text.contains("7 meshes, 0 analysed, 7 kept"), "{text}");
    let bunny = cohort.join("closed_bunny_npm.obj.gz");
    let bytes = std::fs::read(&bunny).unwrap();
    std::thread::sleep(Duration::from_millis(20));
    std::fs::write(&bunny, &bytes).unwrap();
    let (_, text) = run(shape(&cohort, &csv, &["--resume=hash"]));
    assert!(text.contains("0 analysed, 7 kept"), "by hash the touched file is unchanged: {text}");
    let (_, text) = run(shape(&cohort, &csv, &["--resume"]));
    assert!(text.contains("1 analysed, 6 kept"), "by time the touched file runs again: {text}");
    let (_, text) = run(shape(&cohort, &csv, &["--resume", "--retry-failed"]));
    assert!(text.contains("1 analysed, 6 kept") && text.contains("1 failed"), "the failed row runs again: {text}");
    let rows: Vec<String> = std::fs::read_to_string(&csv).unwrap().lines().map(|l| l.split(',').next().unwrap().to_string()).collect();
    let mut sorted = rows[1..].to_vec();
    sorted.sort();
    assert_eq!(rows[1..], sorted[..], "rows sorted by file");
}
