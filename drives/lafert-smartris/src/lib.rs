#![doc = include_str!("../README.md")]
#![no_std]

#[cfg(feature = "std")]
extern crate std;

include!(concat!(env!("OUT_DIR"), "/drive.rs"));

mod emcy;
mod run_sequence;
// With drivebus's `async` (which this crate's `async` enables): the run sequence awaited.
drivebus::if_async! { mod run_sequence_async; }
mod store;
mod wait;

pub use emcy::EmcyCodes;
pub use run_sequence::{ControlMode, RunError};
pub use store::StoreResetError;
#[cfg(feature = "std")]
pub use wait::StdClock;
pub use wait::{Clock, RebootWait};
