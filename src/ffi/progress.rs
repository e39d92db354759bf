//! The C progress callback as a [`Progress`].

use std::ffi::{c_char, c_void, CString};
use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, Ordering};
use std::thread::ThreadId;

use crate::progress::{Progress, Stage};

/// Progress callback: `stage` is one of `CAPMESH_V1_STAGE_*`, `fraction` in [0, 1] is the
/// completed part of that stage, `message` a short UTF-8 text valid during the call. Return
/// nonzero to cancel: the call then returns `CAPMESH_V1_CANCELLED` soon after. It is only
/// called on the thread that called capmesh, and must not unwind (throw) into capmesh.
#[allow(non_camel_case_types)]
pub type capmesh_v1_progress_fn =
    Option<unsafe extern "C" fn(user_data: *mut c_void, stage: i32, fraction: f64, message: *const c_char) -> i32>;

/// Progress stage: checking the input mesh.
pub const CAPMESH_V1_STAGE_VALIDATE: i32 = 0;
/// Progress stage: initial flattening onto the unit disk.
pub const CAPMESH_V1_STAGE_FLATTEN: i32 = 1;
/// Progress stage: search for the optimal disk radius.
pub const CAPMESH_V1_STAGE_RADIUS_SEARCH: i32 = 2;
/// Progress stage: optimal transport on the disk.
pub const CAPMESH_V1_STAGE_TRANSPORT: i32 = 3;
/// Progress stage: projection onto the cap and metrics.
pub const CAPMESH_V1_STAGE_PROJECT: i32 = 4;
/// Progress stage: remeshing through the cap.
pub const CAPMESH_V1_STAGE_REMESH: i32 = 5;
/// Progress stage: adaptive harmonics fit.
pub const CAPMESH_V1_STAGE_HARMONICS: i32 = 6;

/// The `CAPMESH_V1_STAGE_*` code of a stage.
pub(crate) fn stage_code(stage: Stage) -> i32 {
    match stage {
        Stage::Validate => CAPMESH_V1_STAGE_VALIDATE,
        Stage::Flatten => CAPMESH_V1_STAGE_FLATTEN,
        Stage::RadiusSearch => CAPMESH_V1_STAGE_RADIUS_SEARCH,
        Stage::Transport => CAPMESH_V1_STAGE_TRANSPORT,
        Stage::Project => CAPMESH_V1_STAGE_PROJECT,
        Stage::Remesh => CAPMESH_V1_STAGE_REMESH,
        Stage::Harmonics => CAPMESH_V1_STAGE_HARMONICS,
    }
}

/// Forwards reports to the C callback on the calling thread; reports from other threads only
/// see a cancellation already requested.
pub(crate) struct CallbackProgress {
    callback: capmesh_v1_progress_fn,
    user_data: *mut c_void,
    thread: ThreadId,
    cancelled: AtomicBool,
}

// SAFETY: `user_data` is only passed to the callback, and the callback is only invoked on the
// thread that created this value (checked in `report`); other threads read only the atomic.
unsafe impl Sync for CallbackProgress {}

impl CallbackProgress {
    pub(crate) fn new(callback: capmesh_v1_progress_fn, user_data: *mut c_void) -> Self {
        Self { callback, user_data, thread: std::thread::current().id(), cancelled: AtomicBool::new(false) }
    }
}

impl Progress for CallbackProgress {
    fn report(&self, stage: Stage, fraction: f64, message: &str) -> ControlFlow<()> {
        if let Some(callback) = self.callback {
            if std::thread::current().id() == self.thread && !self.cancelled.load(Ordering::Relaxed) {
                let text = CString::new(message.replace('\0', " ")).unwrap_or_default();
                // SAFETY: the caller provided a valid callback for `user_data`; `text` lives
                // for the duration of the call.
                let answer = unsafe { callback(self.user_data, stage_code(stage), fraction.clamp(0.0, 1.0), text.as_ptr()) };
                if answer != 0 {
                    self.cancelled.store(true, Ordering::Relaxed);
                }
            }
        }
        if self.cancelled.load(Ordering::Relaxed) {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    }
}
