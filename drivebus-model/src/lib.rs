//! `drivebus-model`: the vocabulary drive descriptions, the generator and the runtime share.
//!
//! `drivegen` builds its model of a description from these types and `drivebus` re-exports each
//! of them at the path generated code names (`drivebus::DataType`, `drivebus::modbus::Table`,
//! `drivebus::control::Machine`, ...), so a description, the code generated from it and the
//! runtime that code calls agree by construction. The crate is `#![no_std]` and allocates
//! nothing except behind the `alloc` feature.
//!
//! * [`data_type`], [`scale`] / [`scalable`], [`units`], [`bound`], [`error_class`], [`stop`]:
//!   what a description says of one value.
//! * [`Number`], [`Range`], [`RawValue`], [`raw`] (feature `alloc`): raw values as a description
//!   and a person write them.
//! * [`model`] (feature `alloc`): the device model the run-time interpreter reads, which
//!   `drivegen`'s IR implements.
//! * [`modbus`], [`canopen`], [`rs232`]: protocol markers, addresses, limits and codes.
//! * [`control`]: drive state machines as tables, and their pure planner.
//! * [`write_lock`]: a drive's write lock as a table.
//!
//! The tables ([`modbus::ModbusLimits`], [`control::Machine`], [`write_lock::WriteLock`]) borrow
//! their slices: generated code holds `'static` instances, a tool that loads a description at run
//! time lends views of its own model.
#![no_std]

#[cfg(feature = "alloc")]
extern crate alloc;
// Tests use std (proptest, formatting) even when the crate is built without `alloc`.
#[cfg(test)]
extern crate std;

pub mod bound;
pub mod canopen;
pub mod control;
pub mod data_type;
pub mod error_class;
pub mod modbus;
#[cfg(feature = "alloc")]
pub mod model;
mod number;
mod outside_range;
mod range;
#[cfg(feature = "alloc")]
pub mod raw;
mod raw_value;
pub mod rs232;
pub mod scalable;
pub mod scale;
pub mod stop;
pub mod units;
pub mod write_lock;

pub use bound::{Bound, OutsideBound};
pub use data_type::DataType;
pub use error_class::ErrorClass;
pub use number::Number;
pub use outside_range::OutsideRange;
pub use range::Range;
pub use raw_value::RawValue;
pub use scalable::Scalable;
pub use scale::{Ratio, Scale, ScaleError};
pub use stop::{StopPattern, Stops};

/// Most bytes one parameter value may occupy on the wire.
pub const MAX_VALUE_BYTES: usize = 64;

/// The protocol a link speaks; selects which address a parameter is reached at.
pub trait Protocol: 'static {
    /// How a parameter is addressed on this protocol.
    type Address: Copy + core::fmt::Debug + PartialEq + 'static;
    /// Human-readable protocol name used in diagnostics.
    const NAME: &'static str;
}
