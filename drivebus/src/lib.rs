//! `drivebus`: the runtime that drivegen-generated drive crates call.
//!
//! The crate is layered so that the generated API stays protocol independent:
//!
//! * [`parameter`](mod@parameter) — the traits a generated parameter marker implements: identity, value codec and
//!   per-protocol read/write capabilities (a missing capability is a compile error).
//! * [`codec`] — the conversions between raw and engineering values parameters name.
//! * [`value`] — raw wire types and their little-endian codecs.
//! * [`scale`] / [`units`] — exact rational scaling and the unit newtypes values are returned in
//!   (from `drivebus-model`, the vocabulary this crate shares with the generator).
//! * [`link`] — the one trait a protocol binding implements; [`device`] drives it.
//! * [`indexed`] — members described once over a run of sub-indices: one marker, one indexed
//!   accessor with a range-checked sub-index.
//! * [`write_lock`] — a drive's write lock as a device handle tracks it: writes to a locked
//!   parameter are refused before sending.
//! * [`modbus`] / [`canopen`] / [`rs232`] — per protocol: addresses, the sans-I/O cores, the bus
//!   traits the blocking clients implement and, in each, the blocking client itself
//!   (`modbus::client`, `canopen::client`, `rs232::client`; each with its protocol's feature).
//! * `stream` (feature `std`) — the byte streams (serial port, TCP, test doubles) under the
//!   Modbus clients and the RS-232 host.
//! * [`interpret`] — raw values, and (feature `std`) byte and register codecs, for tools that read
//!   a description at run time (the CLI, the simulator).
//! * `asynch` (feature `async`) — the async API: [`Link`]'s async twin, the handle marker
//!   `Async<L>` and the timer the async clients take their time from.
//! * [`prelude`] — the names an application uses most, in one `use drivebus::prelude::*;`.
//!
//! The crate is the client side. The device side (Modbus PDU server codec, SDO server, CiA 402
//! device model), which simulators and test peers use, is behind feature `server`; the test doubles
//! (`testing`: `MemoryBus`, `SdoRecorder`, `RtuRecorder`) behind feature `testing`.
//!
//! The core is `#![no_std]`; the `std` feature adds the blocking clients and `std::error::Error`.
#![no_std]

// Tests use std (proptest, Vec) even when the crate is built without it.
#[cfg(any(feature = "std", test))]
extern crate std;

mod async_handle_macro;
#[cfg(feature = "async")]
pub mod asynch;
pub mod bus_error_kind;
pub mod canopen;
#[doc(hidden)] // the checks generated parameters call before sending
pub mod check;
pub mod codec;
pub mod control;
pub mod device;
pub mod error;
#[doc(hidden)] // the `flags!` macro's helpers; generated crates reach them through the macro
pub mod flags_macro;
pub mod given;
pub mod identity;
pub mod indexed;
pub mod interpret;
pub mod link;
pub mod locked_accessor;
pub mod modbus;
mod open_enum_macro;
pub mod parameter;
mod parameter_macro;
pub mod prelude;
pub mod read_set;
pub mod rs232;
#[cfg(feature = "std")]
pub mod stream;
#[cfg(feature = "testing")]
pub mod testing;
#[cfg(feature = "std")]
pub mod trace;
pub mod unlock_error;
pub mod value;
pub mod write_lock;

// The vocabulary lives in `drivebus-model`; it is re-exported at the paths generated code names.
pub use drivebus_model::{bound, data_type, error_class, scalable, scale, stop, units};

pub use bound::{Bound, OutsideBound};
pub use bus_error_kind::BusErrorKind;
pub use data_type::DataType;
pub use device::{Accessor, Device};
pub use error::{BusError, Error, ValueError, WriteRefusal};
pub use error_class::ErrorClass;
pub use identity::{Covered, IdentityCheck, IdentityChecks};
pub use link::Link;
pub use locked_accessor::{LockedAccessor, WritableWithoutUnlock};
pub use parameter::{BoundBy, Parameter, Placement, RawInteger, Readable, ValueOf, Writable};
pub use scale::{Ratio, Scale, ScaleError};
pub use stop::{StopPattern, Stops};
pub use unlock_error::UnlockError;

/// Re-exported so generated crates need no direct `bitflags` dependency.
pub use bitflags;

pub use drivebus_model::Protocol;

/// Index of a firmware or parameter-configuration variant, as numbered by the generated crate.
///
/// Variant 0 is always the description's default configuration.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct VariantId(pub u16);
