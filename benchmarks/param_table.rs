//! Prints the paper's open-surface table (Table 1) for the bundled meshes: mean |d_area| /
//! mean |d_angle| (radians) for the adaptive cap, the planar disk OMT and the hemisphere,
//! with Z* and seconds. Closed meshes get the closed-surface table (Table 2: adaptive,
//! sphere, hemisphere).
//!
//! `cargo run --release --example param_table > benchmarks/results/param_table.md`

use capmesh::cap::Domain;
use capmesh::param::{parameterize, ParamOptions};
use capmesh::io::read_mesh;
use capmesh::progress::NoProgress;
use std::path::Path;

fn cell(mesh: &capmesh::TriMesh, domain: Domain) -> (String, f64) {
    match parameterize(mesh, &ParamOptions::default().with_domain(domain), &NoProgress) {
        Ok(map) => {
            let r = &map.report;
            let z = r.z_star.map_or("-".to_string(), |z| format!("{z:.3}"));
            (
                format!("{:.3} / {:.3} (Z* {z}, {} folds, {:.1} s)", r.area_distortion.mean_abs, r.angle_distortion.mean_abs, r.flipped_faces, r.seconds),
                r.seconds,
            )
        }
        Err(e) => (format!("error: {e}"), 0.0),
    }
}

fn table(names: &[&str], domains: &[(Domain, &str)]) {
    print!("| surface | V |");
    for (_, label) in domains {
        print!(" {label} |");
    }
    println!();
    print!("|---|---:|");
    for _ in domains {
        print!("---|");
    }
    println!();
    for name in names {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(format!("{name}.obj.gz"));
        let mesh = match read_mesh(&path) {
            Ok(m) => m,
            Err(e) => {
                println!("| {name} | - | error: {e} |");
                continue;
            }
        };
        print!("| {name} | {} |", mesh.n_vertices());
        for (d, _) in domains {
            print!(" {} |", cell(&mesh, *d).0);
        }
        println!();
    }
}

fn main() {
    let open = [
        "open_face_choi",
        "open_hand_choi",
        "open_hippocampus_sheet_hippunfold",
        "open_lv_endo_rabbit_chaste",
        "open_meg_helmet_babysquid_mne",
    ];
    let closed = [
        "closed_bunny_npm",
        "closed_bird_skull_CPallidusA_choi",
        "closed_hippocampus_choi",
        "closed_brain12k_choi",
        "closed_lung_rml_chaste",
        "closed_brain_choi",
    ];
    println!("### Open surfaces: mean |d_area| / mean |d_angle| (radians)\n");
    table(&open, &[(Domain::Adaptive, "adaptive"), (Domain::Disk, "disk OMT"), (Domain::Hemisphere, "hemisphere")]);
    println!("\n### Closed surfaces: mean |d_area| / mean |d_angle| (radians)\n");
    table(&closed, &[(Domain::Adaptive, "adaptive"), (Domain::Sphere, "sphere"), (Domain::Hemisphere, "hemisphere")]);
}
