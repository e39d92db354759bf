//! A Python callable `progress(stage, fraction, message)` as the library's [`Progress`].
//!
//! The library calls [`Progress::report`] on the thread that called it (see the library's
//! `pool` module), which is the Python thread that released the GIL: the report takes the GIL
//! back, checks for signals (Ctrl-C cancels) and calls the callable. It returning `False`
//! cancels (the call raises `capmesh.Cancelled`); it raising cancels too, and that exception
//! is the one the call raises. Reports from other threads only see a cancellation already
//! asked for.

use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;
use std::thread::ThreadId;

use capmesh::{Progress, Stage};
use pyo3::prelude::*;
use pyo3::types::PyBool;

/// Forwards reports to an optional Python callable.
pub struct PyProgress {
    callback: Option<Py<PyAny>>,
    thread: ThreadId,
    cancelled: AtomicBool,
    raised: Mutex<Option<PyErr>>,
}

impl PyProgress {
    /// A sink calling `callback` (or only checking signals when `None`).
    pub fn new(callback: Option<Py<PyAny>>) -> Self {
        Self { callback, thread: std::thread::current().id(), cancelled: AtomicBool::new(false), raised: Mutex::new(None) }
    }

    /// The exception the callback (or a signal handler) raised, if any: it replaces the
    /// library's `Cancelled` error.
    pub fn take_raised(&self) -> Option<PyErr> {
        self.raised.lock().ok().and_then(|mut r| r.take())
    }

    /// Whether a report asked the library to stop (its error may then be a stage's error
    /// wrapping the cancellation).
    pub fn cancelled(&self) -> bool {
        self.cancelled.load(Ordering::SeqCst)
    }

    fn cancel(&self, error: Option<PyErr>) -> ControlFlow<()> {
        if let (Some(e), Ok(mut slot)) = (error, self.raised.lock()) {
            slot.get_or_insert(e);
        }
        self.cancelled.store(true, Ordering::SeqCst);
        ControlFlow::Break(())
    }
}

impl Progress for PyProgress {
    fn report(&self, stage: Stage, fraction: f64, message: &str) -> ControlFlow<()> {
        if self.cancelled.load(Ordering::SeqCst) {
            return ControlFlow::Break(());
        }
        if std::thread::current().id() != self.thread {
            return ControlFlow::Continue(());
        }
        Python::with_gil(|py| {
            if let Err(e) = py.check_signals() {
                return self.cancel(Some(e));
            }
            let Some(callback) = &self.callback else { return ControlFlow::Continue(()) };
            match callback.call1(py, (stage.name(), fraction, message)) {
                Err(e) => self.cancel(Some(e)),
                Ok(result) => match result.bind(py).downcast::<PyBool>() {
                    Ok(b) if !b.is_true() => self.cancel(None),
                    _ => ControlFlow::Continue(()),
                },
            }
        })
    }
}
