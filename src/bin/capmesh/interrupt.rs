//! `SIGINT` and `SIGTERM` stop a command cleanly: the signal only sets a flag, the progress
//! bar ([`crate::cli_progress::Bar`]) and [`Stop`] return `ControlFlow::Break` at the next
//! progress report, the library stops with `Error::Cancelled`, the staged outputs are dropped
//! (their temporaries removed, earlier files untouched, see `capmesh::io::atomic`), and the
//! command exits with 130 (`SIGINT`) or 143 (`SIGTERM`) after one line on stderr. A second
//! signal exits at once.
//!
//! `SIGXFSZ` (a write past `ulimit -f`) is caught too, so that the write fails with `EFBIG`
//! and is reported like a full disk instead of killing the process mid-file.

use crate::failure::Failure;
use capmesh::progress::{Progress, Stage};
use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// The signal received (0: none).
static SIGNAL: AtomicUsize = AtomicUsize::new(0);
/// Set by the first signal: the next one exits at once.
static ARMED: AtomicBool = AtomicBool::new(false);
/// Set by `SIGXFSZ` (nothing reads it; catching the signal is what matters).
static FILE_TOO_LARGE: AtomicBool = AtomicBool::new(false);

/// Catch the signals (commands that write files call this first).
pub fn install() -> Result<(), String> {
    use signal_hook::consts::signal::{SIGINT, SIGTERM};
    let failed = |e: std::io::Error| format!("cannot install the signal handlers: {e}");
    for signal in [SIGINT, SIGTERM] {
        // The shutdown must be registered first: it sees the flag of an earlier signal.
        signal_hook::flag::register_conditional_shutdown(signal, 128 + signal, &ARMED).map_err(failed)?;
        signal_hook::flag::register(signal, &ARMED).map_err(failed)?;
        signal_hook::flag::register_usize(signal, &SIGNAL, signal as usize).map_err(failed)?;
    }
    #[cfg(unix)]
    signal_hook::flag::register(signal_hook::consts::signal::SIGXFSZ, &FILE_TOO_LARGE).map_err(failed)?;
    Ok(())
}

/// `true` once `SIGINT` or `SIGTERM` arrived.
pub fn requested() -> bool {
    SIGNAL.load(Ordering::SeqCst) != 0
}

/// The signal's name and the exit code that goes with it (`128 + signal`).
pub fn received() -> Option<(&'static str, u8)> {
    use signal_hook::consts::signal::{SIGINT, SIGTERM};
    match SIGNAL.load(Ordering::SeqCst) as i32 {
        0 => None,
        s if s == SIGINT => Some(("SIGINT", 130)),
        s if s == SIGTERM => Some(("SIGTERM", 143)),
        _ => Some(("a signal", 130)),
    }
}

/// `Err(Failure::Interrupted)` describing `what` when a signal arrived.
pub fn check(what: impl FnOnce() -> String) -> Result<(), Failure> {
    if requested() {
        return Err(Failure::Interrupted(what()));
    }
    Ok(())
}

/// A [`Progress`] that only stops the run when a signal arrived (for `shape`'s meshes).
pub struct Stop;

impl Progress for Stop {
    fn report(&self, _stage: Stage, _fraction: f64, _message: &str) -> ControlFlow<()> {
        if requested() {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    }
}
