//! The crate-wide error type.
//!
//! Each pipeline stage has its own error enum (`MeshError`, `SpectralError`, …) with a
//! `Display` that tells a user what to fix; [`Error`] wraps them so that `?` works across
//! stages. `src/ffi/status.rs` maps each variant to one `sym_status`.

use std::fmt;

use crate::mesh::{IoError, MeshError};
use crate::spectral::SpectralError;

/// Any error intrinsym can return.
#[derive(Debug)]
#[non_exhaustive]
pub enum Error {
    /// The input mesh is unusable (see [`MeshError`]).
    Mesh(MeshError),
    /// A mesh file could not be read or written.
    Io(IoError),
    /// The Laplace–Beltrami eigenproblem failed.
    Spectral(SpectralError),
    /// The progress callback asked to stop; `stage` is the pipeline stage that was running
    /// (or `"report"`, for a stop asked at the final call, fraction 1).
    Cancelled {
        /// The stage: "eigenbasis", "descriptors", "voting", "hypotheses", "refinement",
        /// "polish" or "report".
        stage: &'static str,
    },
    /// A detection was started from inside the progress callback of another detection on the
    /// same thread (the first holds the worker pool while it waits for the callback).
    Reentrant,
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Mesh(e) => write!(f, "invalid mesh: {e}"),
            Error::Io(e) => write!(f, "{e}"),
            Error::Spectral(e) => write!(f, "eigensolver: {e}"),
            Error::Cancelled { stage } => write!(f, "cancelled by the progress callback during the {stage} stage"),
            Error::Reentrant => write!(f, "a detection cannot start inside the progress callback of another detection on the same thread; start it after that detection returns"),
        }
    }
}

impl std::error::Error for Error {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Error::Mesh(e) => Some(e),
            Error::Io(e) => Some(e),
            Error::Spectral(e) => Some(e),
            Error::Cancelled { .. } | Error::Reentrant => None,
        }
    }
}

impl From<MeshError> for Error {
    fn from(e: MeshError) -> Self {
        Error::Mesh(e)
    }
}
impl From<IoError> for Error {
    fn from(e: IoError) -> Self {
        Error::Io(e)
    }
}
impl From<SpectralError> for Error {
    fn from(e: SpectralError) -> Self {
        match e {
            SpectralError::Cancelled => Error::Cancelled { stage: "eigenbasis" },
            e => Error::Spectral(e),
        }
    }
}
