#![doc = include_str!("../README.md")]
#![no_std]

#[cfg(feature = "std")]
extern crate std;

include!(concat!(env!("OUT_DIR"), "/drive.rs"));

#[cfg(doctest)]
mod compile_guarantees;
mod emcy;
pub mod safety_functions;
pub mod safety_settings;
#[cfg(feature = "std")]
mod velocity_mode;
mod wheel_speed;

pub use emcy::EmcyCodes;
pub use safety_settings::{SafetySettingError, UNSIGNED_SAFETY_SETTINGS};
#[cfg(feature = "std")]
pub use velocity_mode::{HALT, VL_OPERATION_ENABLED};
pub use wheel_speed::{motor_speed, wheel_speed};
