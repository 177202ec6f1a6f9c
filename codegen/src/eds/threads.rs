//! Two threads for large files: the stages of a read whose work splits into independent halves
//! (INI lines, object sections) run one half on a second thread. Both paths give the same result,
//! byte for byte; the second thread only pays off on large files, since starting one costs tens of
//! microseconds.

use std::thread;

/// How many threads reading an EDS may use.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Threads {
    /// Two for files of [`Threads::TWO_FROM`] bytes or more, one for smaller ones.
    #[default]
    Auto,
    /// The calling thread only.
    One,
    /// Two whatever the size (to compare the paths on small files).
    Two,
}

impl Threads {
    /// The size from which [`Threads::Auto`] uses two threads, found by measurement: below it, the
    /// second thread's start costs about what it saves.
    pub const TWO_FROM: usize = 64 * 1024;

    /// Whether to use two threads for a file of `len` bytes.
    pub(super) fn two_for(self, len: usize) -> bool {
        match self {
            Threads::Auto => len >= Self::TWO_FROM,
            Threads::One => false,
            Threads::Two => true,
        }
    }
}

/// Runs `a` on a second thread while `b` runs on this one; `None`, with neither run, when the
/// system cannot start a thread (the caller then does the work on its own).
///
/// The work is the reader's own, which reports bad input as values and does not panic; should
/// `a` panic all the same, the panic goes on in the caller as if `a` had run there.
pub(super) fn join<A: Send, B>(
    a: impl FnOnce() -> A + Send,
    b: impl FnOnce() -> B,
) -> Option<(A, B)> {
    thread::scope(|scope| {
        let worker = thread::Builder::new().spawn_scoped(scope, a).ok()?;
        let b = b();
        match worker.join() {
            Ok(a) => Some((a, b)),
            Err(panic) => std::panic::resume_unwind(panic),
        }
    })
}
