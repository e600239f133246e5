//! The stable C ABI (`sym_` prefix): the only module with `extern "C"`, raw pointers and
//! `unsafe`. The header `include/intrinsym.h` is generated from it by cbindgen.
//!
//! Contract (DESIGN.md "C ABI"):
//! - every fallible function returns a [`sym_status`]; out-parameters are written only on
//!   success; every pointer is checked for NULL;
//! - no panic crosses the boundary: each body runs inside [`boundary::guard`]
//!   (`catch_unwind`), a panic becomes `SYM_STATUS_PANIC` with its message as the last error;
//! - results are opaque handles owned by the library; `sym_free(NULL)` is a no-op; pointers
//!   returned by [`sym_get_map`] stay valid until `sym_free`;
//! - parameters live in an opaque handle with setters, so the layout can grow without
//!   breaking the ABI; [`sym_symmetry`] carries its own size for the same reason;
//! - a detail message for the last failure on the calling thread is available from
//!   [`sym_last_error`]; independent calls on independent handles may run concurrently.

#![deny(missing_docs)]
#![allow(non_camel_case_types)]

mod boundary;
mod handle;
pub mod process;
mod status;
mod version;

pub use handle::*;
pub use status::*;
pub use version::*;
