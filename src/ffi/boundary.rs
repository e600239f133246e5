//! Panic containment and the per-thread last-error message.

use std::cell::RefCell;
use std::panic::{catch_unwind, AssertUnwindSafe};

use super::status::sym_status;

thread_local! {
    static LAST_ERROR: RefCell<String> = const { RefCell::new(String::new()) };
}

/// Records `message` as the calling thread's last error.
pub(crate) fn set_error(message: impl Into<String>) {
    LAST_ERROR.with(|e| *e.borrow_mut() = message.into());
}

/// The calling thread's last error.
pub(crate) fn last_error() -> String {
    LAST_ERROR.with(|e| e.borrow().clone())
}

/// Runs `body`, turning an error into its status (with the message recorded) and a panic into
/// `SYM_STATUS_PANIC`. The last error always describes this call: empty after a success, even
/// when the body called back into user code that made failing calls (issue 16, item 12).
pub(crate) fn guard(body: impl FnOnce() -> Result<(), (sym_status, String)>) -> sym_status {
    set_error("");
    match catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(())) => {
            set_error("");
            sym_status::SYM_STATUS_OK
        }
        Ok(Err((status, message))) => {
            set_error(message);
            status
        }
        Err(payload) => {
            let message = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".to_string());
            set_error(format!("internal error (panic): {message}"));
            sym_status::SYM_STATUS_PANIC
        }
    }
}

/// Runs a body that returns a plain value; a panic yields `fallback`.
pub(crate) fn guard_value<T>(fallback: T, body: impl FnOnce() -> T) -> T {
    catch_unwind(AssertUnwindSafe(body)).unwrap_or(fallback)
}
