//! The run-time interpreter's codecs: parameter values as the bytes and registers a described
//! [`DataType`](crate::DataType) occupies, for tools that read a description at run time (the
//! `drivegen` CLI, the simulator) instead of compiling it. Scaling is the same
//! [`Scale`](crate::Scale) generated code uses.

#[cfg(feature = "std")]
pub mod raw;
mod raw_value;
#[cfg(feature = "std")]
pub mod registers;

pub use raw_value::RawValue;
