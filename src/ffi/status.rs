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
        Error::Spectral(SpectralError::Cancelled) => sym_status::SYM_STATUS_CANCELLED,
        Error::Spectral(SpectralError::TooManyEigenpairs { .. }) => sym_status::SYM_STATUS_INVALID_ARGUMENT,
        Error::Spectral(_) => sym_status::SYM_STATUS_EIGENSOLVER_FAILED,
        #[allow(unreachable_patterns)]
        _ => sym_status::SYM_STATUS_PANIC,
    }
}

/// A static, NUL-terminated description of `status` (never NULL; unknown values give
/// "unknown status").
#[no_mangle]
pub extern "C" fn sym_status_str(status: sym_status) -> *const std::ffi::c_char {
    let s: &'static [u8] = match status {
        sym_status::SYM_STATUS_OK => b"ok\0",
        sym_status::SYM_STATUS_NULL_PARAMETER => b"a required pointer argument is NULL\0",
        sym_status::SYM_STATUS_INVALID_ARGUMENT => b"an argument is out of range\0",
        sym_status::SYM_STATUS_INVALID_MESH => b"the mesh was refused\0",
        sym_status::SYM_STATUS_EIGENSOLVER_FAILED => b"the eigensolver failed\0",
        sym_status::SYM_STATUS_CANCELLED => b"cancelled by the progress callback\0",
        sym_status::SYM_STATUS_OUT_OF_MEMORY => b"out of memory\0",
        sym_status::SYM_STATUS_PANIC => b"internal error\0",
    };
    s.as_ptr().cast()
}
