//! The CLI's progress bar: an [`indicatif`] bar on stderr implementing [`Progress`], which
//! also stops the run after `SIGINT` or `SIGTERM` ([`crate::interrupt`]).

use capmesh::progress::{Progress, Stage};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::ops::ControlFlow;
use std::sync::Mutex;

/// A progress bar (hidden with `--quiet` or when stderr is not a terminal).
pub struct Bar {
    bar: ProgressBar,
    /// The stage of the last report, for the line printed when interrupted.
    stage: Mutex<&'static str>,
}

impl Bar {
    /// A new bar.
    pub fn new(quiet: bool) -> Self {
        let bar = ProgressBar::new(1000);
        if quiet {
            bar.set_draw_target(ProgressDrawTarget::hidden());
        }
        if let Ok(style) = ProgressStyle::with_template("{spinner} [{elapsed_precise}] {bar:30} {prefix:>14}: {msg}") {
            bar.set_style(style);
        }
        Self { bar, stage: Mutex::new("reading") }
    }

    /// Clear the bar.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }

    /// The stage of the last report ("reading" before the first).
    pub fn stage(&self) -> &'static str {
        self.stage.lock().map_or("the run", |s| *s)
    }
}

impl Drop for Bar {
    fn drop(&mut self) {
        self.bar.finish_and_clear();
    }
}

impl Progress for Bar {
    fn report(&self, stage: Stage, fraction: f64, message: &str) -> ControlFlow<()> {
        if let Ok(mut s) = self.stage.lock() {
            *s = stage.name();
        }
        self.bar.set_prefix(stage.name());
        self.bar.set_position((fraction * 1000.0) as u64);
        self.bar.set_message(message.to_string());
        if crate::interrupt::requested() {
            return ControlFlow::Break(());
        }
        ControlFlow::Continue(())
    }
}
