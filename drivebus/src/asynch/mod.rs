//! The async API (feature `async`): the same typed drives, awaited.
//!
//! A generated handle over [`Async<L>`] (an [`AsyncLink`] `L`) has the very accessors of the
//! blocking handle, returning futures: `drive.bus_dc_link().read().await?`. The protocol cores
//! are the sans-I/O ones the blocking clients drive; only the I/O differs. Nothing here names
//! an executor: time comes from a [`Timer`] the application supplies (tokio's behind feature
//! `tokio`, an embassy timer, a test clock), so the async API builds for `no_std` targets.
//!
//! [`Device<Async<L>>`](crate::Device) has `read`, `read_raw`, `write`, `write_raw` and
//! `read_many` ([`AsyncReadSet`]); the accessors ([`Accessor`](crate::Accessor),
//! [`Indexed`](crate::indexed::Indexed), [`LockedAccessor`](crate::LockedAccessor)) have their
//! blocking twins' methods, awaited. Everything but the I/O is the blocking device's code: the
//! checks before a request and the decoding after it are functions both call, and a run-time
//! scale (generated as blocking code over a `Device`) is replayed over the answers of async
//! reads, one more run per input it reads, rather than generated twice. The procedures a handle
//! runs on connect ([`Device::verify_identity`](crate::Device::verify_identity), the generated
//! `verify_identity_async` and `detect_variant_async`) conclude from what they read with the
//! blocking procedure's own functions: only the reads are awaited.
//!
//! An async unlock guard cannot write the lock command in `Drop`: one dropped without
//! `lock().await` leaves the lock owed ([`Device::owe_write`](crate::Device::owe_write)), and
//! the device's next async request sends it first.

mod accessor;
pub(crate) mod alarm;
mod device;
mod identity;
pub(crate) mod io_error;
mod link;
mod owed_lock;
pub(crate) mod race;
mod read_set;
mod replay;
mod timer;

pub use alarm::{within_alarm, Alarm};
pub use link::{Async, AsyncLink};
pub use owed_lock::OwedLock;
pub use read_set::AsyncReadSet;
pub use timer::{within, Elapsed, Timer};
#[cfg(feature = "tokio")]
pub use timer::{TokioAlarm, TokioTimer};
