//! The async API (feature `async`): the same typed drives, awaited.
//!
//! A generated handle over [`Async<L>`] (an [`AsyncLink`] `L`) has the very accessors of the
//! blocking handle, returning futures: `drive.bus_dc_link().read().await?`. The protocol cores
//! are the sans-I/O ones the blocking clients drive; only the I/O differs. Nothing here names
//! an executor: time comes from a [`Timer`] the application supplies (tokio's behind feature
//! `tokio`, an embassy timer, a test clock), so the async API builds for `no_std` targets.

pub(crate) mod io_error;
mod link;
pub(crate) mod race;
mod timer;

pub use link::{Async, AsyncLink};
#[cfg(feature = "tokio")]
pub use timer::TokioTimer;
pub use timer::{within, Elapsed, Timer};
