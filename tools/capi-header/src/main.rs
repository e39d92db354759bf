//! Writes capmesh's C ABI header `cpp/include/capmesh.h` from `src/ffi/` with cbindgen, or,
//! with `--check`, fails when the committed header differs from what cbindgen generates.
//!
//! ```sh
//! cargo run --manifest-path tools/capi-header/Cargo.toml            # write
//! cargo run --manifest-path tools/capi-header/Cargo.toml -- --check # CI
//! ```

use std::path::{Path, PathBuf};
use std::process::ExitCode;

const HEADER: &str = "cpp/include/capmesh.h";

fn generate(root: &Path) -> Result<String, String> {
    let config = cbindgen::Config::from_file(root.join("cbindgen.toml")).map_err(|e| e.to_string())?;
    let bindings = cbindgen::Builder::new()
        .with_config(config)
        .with_src(root.join("src/ffi/mod.rs"))
        .generate()
        .map_err(|e| e.to_string())?;
    let mut out = Vec::new();
    bindings.write(&mut out);
    String::from_utf8(out).map_err(|e| e.to_string())
}

fn main() -> ExitCode {
    let root: PathBuf = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let check = std::env::args().any(|a| a == "--check");
    let text = match generate(&root) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("cbindgen failed: {e}");
            return ExitCode::FAILURE;
        }
    };
    let path = root.join(HEADER);
    if check {
        let committed = std::fs::read_to_string(&path).unwrap_or_default();
        if committed == text {
            println!("{HEADER} is up to date");
            ExitCode::SUCCESS
        } else {
            eprintln!(
                "{HEADER} is stale: it differs from what cbindgen generates from src/ffi/.\n\
                 Run `cargo run --manifest-path tools/capi-header/Cargo.toml` and commit the header."
            );
            ExitCode::FAILURE
        }
    } else {
        if let Err(e) = std::fs::write(&path, text) {
            eprintln!("cannot write {}: {e}", path.display());
            return ExitCode::FAILURE;
        }
        println!("wrote {HEADER}");
        ExitCode::SUCCESS
    }
}
