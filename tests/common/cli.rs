//! Running the `capmesh` binary from a test: the command, and the `harmonics` run that asks for
//! every output (reconstruction, coefficients, report, cap mesh) that several tests read back.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The `capmesh` binary built for this test run.
pub fn capmesh() -> Command {
    // `option_env!`: test binaries that do not run the command line still compile without it.
    match option_env!("CARGO_BIN_EXE_capmesh") {
        Some(exe) => Command::new(exe),
        None => panic!("the capmesh binary is built with the `cli` feature (on by default)"),
    }
}

/// The output files of one `capmesh harmonics` run, in a test's directory.
pub struct HarmonicsFiles {
    /// `-o`: the reconstructed surface.
    pub output: PathBuf,
    /// `--coefficients`.
    pub coefficients: PathBuf,
    /// `--report`.
    pub report: PathBuf,
    /// `--cap-mesh`: the points at which the coefficients are evaluated.
    pub cap_mesh: PathBuf,
}

impl HarmonicsFiles {
    /// `output` (its extension picks the format), `c.json`, `r.json` and `cap.obj` in `dir`.
    pub fn in_dir(dir: &Path, output: &str) -> Self {
        HarmonicsFiles { output: dir.join(output), coefficients: dir.join("c.json"), report: dir.join("r.json"), cap_mesh: dir.join("cap.obj") }
    }
}

/// `capmesh harmonics --quiet ARGS INPUT` writing every file of `files`; the run's output
/// (the caller checks its status).
pub fn harmonics(input: &Path, args: &[&str], files: &HarmonicsFiles) -> Output {
    capmesh()
        .args(["harmonics", "--quiet"])
        .args(args)
        .arg(input)
        .arg("-o")
        .arg(&files.output)
        .arg("--coefficients")
        .arg(&files.coefficients)
        .arg("--report")
        .arg(&files.report)
        .arg("--cap-mesh")
        .arg(&files.cap_mesh)
        .output()
        .unwrap()
}
