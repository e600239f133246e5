//! Process-level settings for the command-line tool (not part of the C API).

/// Restores the default action of `SIGPIPE` (Rust ignores it, so that a write to a closed pipe
/// returns an error, and `println!` turns that error into a panic). With the default, the
/// command-line tool ends quietly when its reader goes away (`intrinsym detect … | head`), as
/// other Unix tools do.
pub fn default_sigpipe() {
    // SAFETY: setting a signal's disposition to SIG_DFL has no memory-safety preconditions;
    // it is done once, at start-up, before any thread exists.
    #[cfg(unix)]
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}
