//! Status codes and their mapping from [`crate::Error`].

use crate::spectral::SpectralError;
use crate::Error;

/// Result of every fallible `sym_` function.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum sym_status {
    /// Success.
    SYM_STATUS_OK = 0,
    /// A required pointer argument was NULL.
    SYM_STATUS_NULL_PARAMETER = 1,
    /// An argument is out of its valid range (a size, an index, a parameter value).
    SYM_STATUS_INVALID_ARGUMENT = 2,
    /// The mesh was refused (empty, NaN/inf, index out of range, repeated index, non-manifold, degenerate, disconnected).
    SYM_STATUS_INVALID_MESH = 3,
    /// The eigensolver failed or did not converge.
    SYM_STATUS_EIGENSOLVER_FAILED = 4,
    /// The progress callback asked to stop.
    SYM_STATUS_CANCELLED = 5,
    /// Memory could not be allocated.
    SYM_STATUS_OUT_OF_MEMORY = 6,
    /// An internal error (a caught panic); the library stays usable.
    SYM_STATUS_PANIC = 7,
}

/// Maps a library error to its status and message.
pub(crate) fn from_error(e: &Error) -> sym_status {
    match e {
        Error::Mesh(_) | Error::Io(_) => sym_status::SYM_STATUS_INVALID_MESH,
        Error::Spectral(SpectralError::Cancelled) | Error::Cancelled { .. } => sym_status::SYM_STATUS_CANCELLED,
        Error::Spectral(SpectralError::TooManyEigenpairs { .. }) | Error::Reentrant => sym_status::SYM_STATUS_INVALID_ARGUMENT,
        Error::Spectral(_) => sym_status::SYM_STATUS_EIGENSOLVER_FAILED,
        #[allow(unreachable_patterns)]
        _ => sym_status::SYM_STATUS_PANIC,
    }
}

/// A static, NUL-terminated description of `status` (never NULL; any other value, negative
/// or too large, gives "unknown status"). It takes an `int`, not the enum, so that a value
/// outside the enum is defined behaviour in Rust too (issue 16, item 7).
#[no_mangle]
pub extern "C" fn sym_status_str(status: std::ffi::c_int) -> *const std::ffi::c_char {
    let s: &'static [u8] = match status {
        0 => b"ok\0",
        1 => b"a required pointer argument is NULL\0",
        2 => b"an argument is out of range\0",
        3 => b"the mesh was refused\0",
        4 => b"the eigensolver failed\0",
        5 => b"cancelled by the progress callback\0",
        6 => b"out of memory\0",
        7 => b"internal error\0",
        _ => b"unknown status\0",
    };
    s.as_ptr().cast()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every status has its own description; values outside the enum are "unknown status".
    #[test]
    fn every_status_and_no_other_has_a_description() {
        // SAFETY: sym_status_str returns a static NUL-terminated string for every value.
        let text = |v: std::ffi::c_int| unsafe { std::ffi::CStr::from_ptr(sym_status_str(v)) }.to_str().unwrap().to_string();
        let known: Vec<String> = (0..=7).map(text).collect();
        assert!(known.iter().all(|t| t != "unknown status"));
        assert_eq!(known.iter().collect::<std::collections::HashSet<_>>().len(), known.len());
        assert_eq!(text(sym_status::SYM_STATUS_CANCELLED as std::ffi::c_int), "cancelled by the progress callback");
        for v in [-1, 8, 1_000_000, std::ffi::c_int::MIN, std::ffi::c_int::MAX] {
            assert_eq!(text(v), "unknown status");
        }
    }
}
