#![doc = include_str!("../README.md")]
#![no_std]

#[cfg(feature = "std")]
extern crate std;

include!(concat!(env!("OUT_DIR"), "/drive.rs"));

mod store;

pub use store::Store;
