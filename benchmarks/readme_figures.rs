//! Writes the README's figure set, `docs/img/bunny/`: the figures of `capmesh param
//! --figures` for the bundled bunny, drawn small (160 px views, 480 x 300 charts, no SVG) to
//! keep the repository light.
//!
//! `cargo run --release --example readme_figures`

use capmesh::figures::{param_figures, FigureOptions};
use capmesh::{parameterize, read_mesh, NoProgress, ParamOptions};
use std::path::Path;

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let run = || -> Result<(), String> {
        let mesh = read_mesh(&root.join("tests/data/closed_bunny_npm.obj.gz")).map_err(|e| e.to_string())?;
        let map = parameterize(&mesh, &ParamOptions::default(), &NoProgress).map_err(|e| e.to_string())?;
        let options = FigureOptions::default().with_view_size(160).with_chart_size(480, 300).with_svg(false);
        let set = param_figures(&root.join("docs/img/bunny"), "closed_bunny_npm.obj.gz", &mesh, &map, &options).map_err(|e| e.to_string())?;
        println!("{}", set.index.display());
        Ok(())
    };
    if let Err(e) = run() {
        eprintln!("readme_figures: {e}");
        std::process::exit(1);
    }
}
