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
mod model;
mod number;
#[cfg(feature = "std")]
mod over_link;
mod range;
#[cfg(feature = "std")]
pub mod raw;
mod raw_value;
#[cfg(feature = "std")]
pub mod registers;
#[cfg(feature = "std")]
mod shown;

#[cfg(feature = "std")]
pub use bounds_check::{check, Breach};
#[cfg(feature = "std")]
pub use input::{parse, InputError};
#[cfg(feature = "std")]
pub use model::{BoundedBy, Described, Model, Symbols};
pub use number::Number;
#[cfg(feature = "std")]
pub use over_link::{
    check_bounds, read, read_raw, waive_for_stop, write, write_checked, write_raw, Access,
    Addressed, InterpretError, Unreachable, Variant,
};
pub use range::Range;
pub use raw_value::RawValue;
#[cfg(feature = "std")]
pub use shown::{show, Engineering, Raw, Shown};
