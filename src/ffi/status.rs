//! Status codes, the thread-local last-error text and the panic guard of every entry point.

use std::cell::RefCell;
use std::ffi::{c_char, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};

use crate::error::Error;
use crate::flatten::FlattenError;
use crate::harmonics::HarmonicsError;
use crate::omt::OmtError;

/// Result of every fallible `capmesh_v1_*` call. `capmesh_v1_last_error()` has the text.
#[allow(non_camel_case_types)]
#[repr(i32)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum capmesh_v1_status {
    /// Success.
    CAPMESH_V1_OK = 0,
    /// A NULL pointer, a count that overflows, an option out of range.
    CAPMESH_V1_INVALID_ARGUMENT = 1,
    /// The mesh cannot be used: empty, index out of range, NaN, non-manifold, several
    /// components, genus > 0, several boundary loops, ...
    CAPMESH_V1_INVALID_MESH = 2,
    /// A solver failed (transport did not converge, singular system, ...).
    CAPMESH_V1_NUMERICAL = 3,
    /// Valid input asking for something not supported.
    CAPMESH_V1_UNSUPPORTED = 4,
    /// The progress callback returned nonzero.
    CAPMESH_V1_CANCELLED = 5,
    /// A bug in capmesh (a caught panic); please report it with the last error text.
    CAPMESH_V1_INTERNAL = 6,
}

use capmesh_v1_status as S;

/// A failed call: its status and its message.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Failure {
    pub status: capmesh_v1_status,
    pub message: String,
}

impl Failure {
    pub(crate) fn new(status: capmesh_v1_status, message: impl Into<String>) -> Self {
        Self { status, message: message.into() }
    }

    pub(crate) fn invalid_argument(message: impl Into<String>) -> Self {
        Self::new(S::CAPMESH_V1_INVALID_ARGUMENT, message)
    }
}

/// The status a library error maps to.
pub(crate) fn status_of(error: &Error) -> capmesh_v1_status {
    match error {
        Error::Read(_) | Error::Mesh(_) => S::CAPMESH_V1_INVALID_MESH,
        Error::Write(_) => S::CAPMESH_V1_INTERNAL,
        Error::Flatten(FlattenError::LambdaOutOfRange { .. }) => S::CAPMESH_V1_INVALID_ARGUMENT,
        Error::Flatten(FlattenError::Mesh(_) | FlattenError::BoundaryTooShort { .. } | FlattenError::NoPuncture) => {
            S::CAPMESH_V1_INVALID_MESH
        }
        Error::Flatten(_) => S::CAPMESH_V1_NUMERICAL,
        Error::Transport(OmtError::Cancelled(_)) => S::CAPMESH_V1_CANCELLED,
        Error::Transport(_) => S::CAPMESH_V1_NUMERICAL,
        Error::Inverse(_) => S::CAPMESH_V1_INVALID_ARGUMENT,
        Error::Unsupported(_) => S::CAPMESH_V1_UNSUPPORTED,
        Error::InvalidOption(_) => S::CAPMESH_V1_INVALID_ARGUMENT,
        Error::Cancelled(_) => S::CAPMESH_V1_CANCELLED,
        Error::Internal(_) => S::CAPMESH_V1_INTERNAL,
        Error::Harmonics(
            HarmonicsError::OrderTooLarge { .. }
            | HarmonicsError::TooFewPoints { .. }
            | HarmonicsError::TooLarge { .. }
            | HarmonicsError::InvalidResample { .. },
        ) => S::CAPMESH_V1_INVALID_ARGUMENT,
        Error::Harmonics(_) => S::CAPMESH_V1_NUMERICAL,
    }
}

impl From<Error> for Failure {
    fn from(error: Error) -> Self {
        Failure::new(status_of(&error), error.to_string())
    }
}

thread_local! {
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
}

fn set_last_error(message: &str) {
    let text = CString::new(message.replace('\0', " ")).unwrap_or_default();
    LAST_ERROR.with(|e| *e.borrow_mut() = text);
}

/// Run an entry point's body: reset the last error, catch panics, record failures.
pub(crate) fn guard(body: impl FnOnce() -> Result<(), Failure>) -> capmesh_v1_status {
    set_last_error("");
    let outcome = catch_unwind(AssertUnwindSafe(body)).unwrap_or_else(|panic| {
        let what = panic
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| panic.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown panic payload".into());
        Err(Failure::new(S::CAPMESH_V1_INTERNAL, format!("internal error (a capmesh bug, please report it): {what}")))
    });
    match outcome {
        Ok(()) => S::CAPMESH_V1_OK,
        Err(failure) => {
            set_last_error(&failure.message);
            failure.status
        }
    }
}

/// The message of the last failed `capmesh_v1_*` call on this thread, `""` if the last
/// status-returning call succeeded. Never NULL. The text stays valid until the next
/// status-returning `capmesh_v1_*` call on this thread.
#[no_mangle]
pub extern "C" fn capmesh_v1_last_error() -> *const c_char {
    LAST_ERROR.with(|e| e.borrow().as_ptr())
}

/// The library version, e.g. `"0.1.0"` (static storage, never freed).
#[no_mangle]
pub extern "C" fn capmesh_v1_version() -> *const c_char {
    concat!(env!("CARGO_PKG_VERSION"), "\0").as_ptr().cast()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::ffi::CStr;

    fn last() -> String {
        unsafe { CStr::from_ptr(capmesh_v1_last_error()) }.to_string_lossy().into_owned()
    }

    #[test]
    fn a_panic_becomes_internal_with_its_message() {
        let status = guard(|| panic!("boom at face 7"));
        assert_eq!(status, S::CAPMESH_V1_INTERNAL);
        assert!(last().contains("boom at face 7"), "{}", last());
        // The next successful call clears it.
        assert_eq!(guard(|| Ok(())), S::CAPMESH_V1_OK);
        assert_eq!(last(), "");
    }

    #[test]
    fn failures_keep_status_and_text() {
        let status = guard(|| Err(Failure::invalid_argument("options is NULL")));
        assert_eq!(status, S::CAPMESH_V1_INVALID_ARGUMENT);
        assert_eq!(last(), "options is NULL");
        let status = guard(|| Err(Error::Cancelled(crate::progress::Cancelled).into()));
        assert_eq!(status, S::CAPMESH_V1_CANCELLED);
        assert!(!last().is_empty());
    }

    #[test]
    fn version_is_the_crate_version() {
        let v = unsafe { CStr::from_ptr(capmesh_v1_version()) };
        assert_eq!(v.to_str().unwrap(), env!("CARGO_PKG_VERSION"));
    }
}
