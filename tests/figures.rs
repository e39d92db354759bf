//! Figures (`capmesh::figures`, `--figures DIR`) of real meshes: every file is written, decodes
//! as a PNG of the stated size and is not blank; the histograms count exactly the values the
//! reports' statistics are of; the bytes are the same on every run and thread count; a bad
//! figure directory is a clear error.

mod common;

use capmesh::figures::{harmonics_figures, param_figures, remesh_figures, FigureKind, FigureOptions, FigureSet};
use capmesh::metrics::Stats;
use capmesh::{parameterize, read_mesh, remesh, CapGrid, NoProgress, ParamOptions, RemeshOptions, TriMesh};
use common::{data, TempDir};
use std::path::Path;
use std::process::Command;

fn mesh(name: &str) -> TriMesh {
    read_mesh(&data(name)).unwrap()
}

/// Width, height and RGB pixels of a PNG file.
fn decode(path: &Path) -> (u32, u32, Vec<u8>) {
    let file = std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut reader = png::Decoder::new(file).read_info().unwrap_or_else(|e| panic!("{} is not a PNG: {e}", path.display()));
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb, "{}", path.display());
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

/// Every figure of `set` exists, decodes at its stated size, differs from the white background
/// in at least 2% of its pixels; every SVG is an SVG; the index links every file.
fn check_files(set: &FigureSet) {
    let index = std::fs::read_to_string(&set.index).unwrap();
    for f in &set.figures {
        let (w, h, pixels) = decode(&f.png);
        assert_eq!((w, h), (f.width, f.height), "{}", f.png.display());
        let drawn = pixels.chunks(3).filter(|p| p != &[255, 255, 255]).count();
        let share = drawn as f64 / f64::from(w * h);
        assert!(share > 0.02, "{} is nearly blank: {:.2}% of its pixels drawn", f.png.display(), 100.0 * share);
        let name = f.png.file_name().unwrap().to_str().unwrap();
        assert!(index.contains(&format!("]({name})")), "index.md does not link {name}");
        if let Some(svg) = &f.svg {
            let text = std::fs::read_to_string(svg).unwrap();
            assert!(text.starts_with("<svg") && text.trim_end().ends_with("</svg>"), "{} is not an SVG", svg.display());
            assert!(index.contains(svg.file_name().unwrap().to_str().unwrap()));
        }
    }
}

fn all_bytes(set: &FigureSet) -> Vec<(String, Vec<u8>)> {
    let mut files: Vec<&Path> = set.figures.iter().flat_map(|f| std::iter::once(f.png.as_path()).chain(f.svg.as_deref())).collect();
    files.push(&set.index);
    files.iter().map(|p| (p.file_name().unwrap().to_string_lossy().into_owned(), std::fs::read(p).unwrap())).collect()
}

#[test]
fn param_figures_of_an_open_surface() {
    let m = mesh("open_meg_helmet_babysquid_mne.obj.gz");
    let map = parameterize(&m, &ParamOptions::default(), &NoProgress).unwrap();
    let dir = TempDir::new("figures-param");
    let options = FigureOptions::default().with_view_size(200).with_chart_size(500, 320);
    let set = param_figures(&dir.path("figs"), "helmet", &m, &map, &options).unwrap();
    let kinds: Vec<FigureKind> = set.figures.iter().map(|f| f.kind).collect();
    assert_eq!(kinds, [FigureKind::AreaDistortion, FigureKind::AngleDistortion, FigureKind::RadiusCurve, FigureKind::Input, FigureKind::CapAreaDistortion]);
    check_files(&set);
    // The stated sizes: charts as asked, three 200 px views under a 44 px title strip, the
    // cap's with a 110 px colour bar.
    assert_eq!((set.figures[0].width, set.figures[0].height), (500, 320));
    assert_eq!((set.figures[3].width, set.figures[3].height), (600, 244));
    assert_eq!((set.figures[4].width, set.figures[4].height), (710, 244));
    // The per-face values are the report's, and the histograms count all of them.
    let r = &map.report;
    assert_eq!(Stats::of(map.face_area_distortion.iter().copied()), r.area_distortion);
    assert_eq!(Stats::of(map.corner_angle_distortion.iter().copied()), r.angle_distortion);
    let area = &set.get(FigureKind::AreaDistortion).unwrap().histograms[0];
    let angle = &set.get(FigureKind::AngleDistortion).unwrap().histograms[0];
    assert_eq!(area.counts.len(), 50);
    assert_eq!(area.total(), r.area_distortion.count);
    assert_eq!(area.total(), m.n_faces());
    assert_eq!(angle.total(), r.angle_distortion.count);
    assert_eq!(angle.total(), 3 * m.n_faces());
    // The histogram spans the values: its ends are the smallest and largest d_area.
    assert!((area.hi.max(-area.lo) - r.area_distortion.max_abs).abs() < 1e-12);
    let index = std::fs::read_to_string(&set.index).unwrap();
    assert!(index.contains(&format!("| Z* | {:.4} |", r.z_star.unwrap())), "{index}");
    assert!(index.contains(&format!("({})", r.area_distortion.count)), "{index}");
    // Drawn again: the same bytes.
    let again = param_figures(&dir.path("again"), "helmet", &m, &map, &options).unwrap();
    assert_eq!(all_bytes(&set), all_bytes(&again));
}

#[test]
fn closed_surface_histograms_leave_out_the_punctured_quad() {
    let m = mesh("closed_bunny_npm.obj.gz");
    let map = parameterize(&m, &ParamOptions::default(), &NoProgress).unwrap();
    let dir = TempDir::new("figures-closed");
    let set = param_figures(&dir, "bunny", &m, &map, &FigureOptions::default().with_svg(false)).unwrap();
    check_files(&set);
    assert!(set.figures.iter().all(|f| f.svg.is_none()));
    let r = &map.report;
    assert_eq!(map.bottom_faces.len(), 2);
    assert!(map.bottom_faces.iter().all(|&f| map.face_area_distortion[f].is_nan()));
    let area = &set.get(FigureKind::AreaDistortion).unwrap().histograms[0];
    assert_eq!(area.total(), r.area_distortion.count);
    assert_eq!(area.total(), m.n_faces() - 2);
    assert_eq!(set.get(FigureKind::AngleDistortion).unwrap().histograms[0].total(), r.angle_distortion.count);
    assert_eq!(Stats::of(map.face_area_distortion.iter().copied()), r.area_distortion);
}

#[test]
fn remesh_figures_compare_with_the_input() {
    let m = mesh("open_meg_helmet_babysquid_mne.obj.gz");
    let options = RemeshOptions::default().with_grid(CapGrid::Uniform { faces: 1500 });
    let (out, rep) = remesh(&m, &options, &NoProgress).unwrap();
    let dir = TempDir::new("figures-remesh");
    let set = remesh_figures(&dir, "helmet", &m, &out, &rep, &FigureOptions::default()).unwrap();
    check_files(&set);
    for kind in [FigureKind::FaceAreas, FigureKind::SmallestAngles] {
        let h = &set.get(kind).unwrap().histograms;
        assert_eq!(h.len(), 2, "{kind:?}");
        assert_eq!((h[0].label.as_str(), h[0].total()), ("input", m.n_faces()), "{kind:?}");
        assert_eq!((h[1].label.as_str(), h[1].total()), ("remesh", rep.quality.faces), "{kind:?}");
    }
    // The smallest angles' mean is the report's.
    let angles = capmesh::figures::smallest_angles(&out);
    let mean = angles.iter().sum::<f64>() / angles.len() as f64;
    assert!((mean - rep.quality.mean_min_angle_deg).abs() < 1e-6 * mean, "{mean} vs {}", rep.quality.mean_min_angle_deg);
    assert!(set.get(FigureKind::Remesh).is_some() && set.get(FigureKind::RadiusCurve).is_some());
    let index = std::fs::read_to_string(&set.index).unwrap();
    assert!(index.contains(&format!("| faces (input) | {} ({}) |", rep.quality.faces, m.n_faces())), "{index}");
}

#[test]
fn harmonics_figures_show_the_reconstruction() {
    let m = mesh("closed_bird_skull_CPallidusA_choi.obj.gz");
    let map = parameterize(&m, &ParamOptions::default(), &NoProgress).unwrap();
    let output = capmesh::harmonics::analyze_map(&m, &map, &capmesh::harmonics::HarmonicsOptions::default().with_order(4), &NoProgress).unwrap();
    let dir = TempDir::new("figures-harmonics");
    let set = harmonics_figures(&dir, "skull", &m, &map, &output, &FigureOptions::default().with_view_size(150)).unwrap();
    check_files(&set);
    let rec = set.get(FigureKind::Reconstruction).unwrap();
    assert_eq!((rec.width, rec.height), (450, 194));
    assert!(set.get(FigureKind::ReconstructionError).is_some() && set.get(FigureKind::CapAreaDistortion).is_some());
    assert_eq!(set.get(FigureKind::AreaDistortion).unwrap().histograms[0].total(), output.report.param.area_distortion.count);
    let index = std::fs::read_to_string(&set.index).unwrap();
    assert!(index.contains(&format!("| order-1 aspect ratio | {:.4} |", output.report.aspect_ratio)), "{index}");
}

fn capmesh() -> Command {
    Command::new(env!("CARGO_BIN_EXE_capmesh"))
}

#[test]
fn cli_figures_are_the_same_bytes_on_one_or_more_threads() {
    let dir = TempDir::new("figures-cli");
    let input = data("open_meg_helmet_babysquid_mne.obj.gz");
    let run = |threads: &str, figs: &str| {
        let out = capmesh().args(["--quiet", "--threads", threads, "param"]).arg(&input).arg("-o").arg(dir.path("cap.obj")).arg("--figures").arg(dir.path(figs)).output().unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        assert!(String::from_utf8_lossy(&out.stdout).contains("index.md (5 figures)"));
    };
    run("1", "one");
    run("2", "two");
    let mut names: Vec<_> = std::fs::read_dir(dir.path("one")).unwrap().map(|e| e.unwrap().file_name()).collect();
    names.sort();
    assert_eq!(names.len(), 9, "{names:?}");
    for n in &names {
        assert_eq!(std::fs::read(dir.path("one").join(n)).unwrap(), std::fs::read(dir.path("two").join(n)).unwrap(), "{n:?} differs");
    }
    let (w, h, _) = decode(&dir.path("one").join("cap_area_distortion.png"));
    assert_eq!((w, h), (1010, 344));
}

#[test]
fn cli_figure_directory_that_is_a_file_is_a_clear_error() {
    let dir = TempDir::new("figures-bad");
    let blocker = dir.file("taken", b"not a directory");
    let out = capmesh().args(["--quiet", "harmonics", "--order", "2"]).arg(data("open_meg_helmet_babysquid_mne.obj.gz")).arg("-o").arg(dir.path("rec.obj")).arg("--figures").arg(&blocker).output().unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("figures: cannot write") && err.contains("taken"), "{err}");
    assert_eq!(std::fs::read(&blocker).unwrap(), b"not a directory");
}

#[test]
fn sizes_out_of_range_are_errors_that_say_the_range() {
    let m = mesh("open_meg_helmet_babysquid_mne.obj.gz");
    let map = parameterize(&m, &ParamOptions::default(), &NoProgress).unwrap();
    let dir = TempDir::new("figures-sizes");
    let err = param_figures(&dir, "helmet", &m, &map, &FigureOptions::default().with_chart_size(100, 50)).unwrap_err();
    assert!(err.to_string().contains("area_distortion.png") && err.to_string().contains("160 x 120 to 8192 x 8192"), "{err}");
    let err = param_figures(&dir, "helmet", &m, &map, &FigureOptions::default().with_view_size(8)).unwrap_err();
    assert!(err.to_string().contains("input.png") && err.to_string().contains("16 to 4096"), "{err}");
}
