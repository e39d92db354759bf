//! How a command fails, and the exit code of each way (README: "Exit codes").

use std::process::ExitCode;

/// A failed command.
pub enum Failure {
    /// Bad input, a failed computation, an unwritable output: exit 1.
    Error(String),
    /// The map is poor (the report says `quality: poor`) and `--allow-poor-map` was not given;
    /// the outputs are written: exit 3.
    PoorMap(String),
    /// Stopped by `SIGINT` or `SIGTERM`; nothing was written: exit 130 or 143.
    Interrupted(String),
}

/// Exit code of a poor map.
pub const EXIT_POOR_MAP: u8 = 3;

impl From<String> for Failure {
    fn from(message: String) -> Self {
        Failure::Error(message)
    }
}

impl From<capmesh::io::WriteError> for Failure {
    fn from(error: capmesh::io::WriteError) -> Self {
        Failure::Error(error.to_string())
    }
}

impl Failure {
    /// Print the one line on stderr and give the exit code.
    pub fn report(self) -> ExitCode {
        match self {
            Failure::Error(msg) => {
                eprintln!("error: {msg}");
                ExitCode::FAILURE
            }
            Failure::PoorMap(msg) => {
                eprintln!("error: {msg}");
                ExitCode::from(EXIT_POOR_MAP)
            }
            Failure::Interrupted(msg) => {
                let (name, code) = crate::interrupt::received().unwrap_or(("a signal", 130));
                eprintln!("capmesh: interrupted by {name}: {msg}");
                ExitCode::from(code)
            }
        }
    }
}

/// A library error of the run on `input` as a [`Failure`]: after a signal (the library then
/// stops with a cancellation) an interruption of `command` during `stage`; otherwise an
/// error naming the file.
pub fn of_pipeline(command: &str, input: &std::path::Path, stage: &str, error: capmesh::Error) -> Failure {
    if crate::interrupt::requested() {
        return Failure::Interrupted(format!(
            "{command} of {} stopped during {stage}; nothing written (earlier files untouched)",
            input.display()
        ));
    }
    Failure::Error(format!("{}: {error}", input.display()))
}
