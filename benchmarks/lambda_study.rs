//! The paper's lambda experiment (Sec. 4, "effect of lambda"): the adaptive parameterization
//! of the shared closed meshes for lambda in [0, 1], mean |d_area| recorded for each, with and
//! without our face-level area refinement (`area_refinement = 0` is the paper's map).
//!
//! `cargo run --release --example lambda_study > benchmarks/results/lambda_study.json`, then
//! `benchmarks/.venv/bin/python benchmarks/plot_lambda_study.py` writes the table and the plot.

use capmesh::param::{parameterize, ParamOptions};
use capmesh::io::read_mesh;
use capmesh::progress::NoProgress;
use std::path::Path;

const LAMBDAS: [f64; 13] = [0.0, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 1.0];

fn main() {
    // The 48k brain is left out: 26 runs of about a minute each.
    let meshes = ["closed_brain12k_choi", "closed_lung_rml_chaste", "closed_hippocampus_choi", "closed_bunny_npm", "closed_bird_skull_CPallidusA_choi"];
    let mut rows = Vec::new();
    for name in meshes {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(format!("{name}.obj.gz"));
        let mesh = match read_mesh(&path) {
            Ok(m) => m,
            Err(e) => {
                eprintln!("{name}: {e}");
                continue;
            }
        };
        for lambda in LAMBDAS {
            for refinement in [0, capmesh::param::DEFAULT_AREA_REFINEMENT] {
                let mut options = ParamOptions::default();
                options.closed.flatten.lambda = lambda;
                options.refinement.area_refinement = refinement;
                let row = match parameterize(&mesh, &options, &NoProgress) {
                    Ok(map) => {
                        let r = &map.report;
                        serde_json::json!({
                            "mesh": name, "lambda": lambda, "area_refinement": refinement,
                            "z_star": r.z_star, "mean_abs_d_area": r.area_distortion.mean_abs,
                            "mean_abs_d_angle": r.angle_distortion.mean_abs, "flipped_faces": r.flipped_faces,
                            "folded_before_repair": r.untangle.folded_before, "seconds": r.seconds,
                        })
                    }
                    Err(e) => serde_json::json!({ "mesh": name, "lambda": lambda, "area_refinement": refinement, "error": e.to_string() }),
                };
                eprintln!("{row}");
                rows.push(row);
            }
        }
    }
    println!("{}", serde_json::to_string_pretty(&serde_json::json!({ "lambdas": LAMBDAS, "runs": rows })).unwrap_or_default());
}
