//! The run-time interpreter: a device model loaded at run time ([`Model`], implemented by
//! drivegen's IR) read and written by name through the same [`Scale`](crate::Scale), type and
//! range checks as generated code. Tools that read a description instead of compiling it (the
//! `drivegen` CLI, the simulator) use it: parameters read and written by name over any
//! [`Link`](crate::link::Link) ([`read()`], [`write()`], [`read_raw`], [`write_raw`]), values as
//! people type and read them ([`parse`], [`show`]), the one validity [`check`], and the bytes
//! and registers a described [`DataType`](crate::DataType) occupies ([`raw`], [`registers`]).

#[cfg(feature = "std")]
mod bounds_check;
#[cfg(feature = "std")]
mod input;
#[cfg(feature = "std")]
mod over_link;
#[cfg(feature = "std")]
pub use drivebus_model::raw;
#[cfg(feature = "std")]
pub mod registers;
#[cfg(feature = "std")]
mod shown;

#[cfg(feature = "std")]
pub use bounds_check::{check, Breach};
#[cfg(feature = "std")]
pub use drivebus_model::model::{
    Access, Addressed, BoundedBy, Described, Model, Symbols, Unreachable,
};
pub use drivebus_model::{Number, OutsideRange, Range, RawValue};
#[cfg(feature = "std")]
pub use input::{parse, InputError};
#[cfg(feature = "std")]
pub use over_link::{
    check_bounds, read, read_raw, waive_for_stop, write, write_checked, write_raw, InterpretError,
    Variant,
};
#[cfg(feature = "std")]
pub use shown::{show, Engineering, Presentation, Raw, Shown};
