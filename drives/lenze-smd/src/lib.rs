#![doc = include_str!("../README.md")]
#![no_std]

#[cfg(feature = "std")]
extern crate std;

include!(concat!(env!("OUT_DIR"), "/drive.rs"));

mod command;
mod configuration;
mod error;
#[cfg(feature = "std")]
mod keep_alive;
// With drivebus's `async`: the keep-alive as steps of an async task.
#[cfg(feature = "std")]
drivebus::if_async! {
    mod keep_alive_async;
    pub use keep_alive_async::AsyncKeepAlive;
}
mod status_block;

pub use command::Command;
pub use error::SmdError;
#[cfg(feature = "std")]
pub use keep_alive::{KeepAlive, KeepAliveReport, MissedDeadline};
pub use status_block::{StatusBlock, STATUS_BLOCK_START, STATUS_BLOCK_WORDS};
