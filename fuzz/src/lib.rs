//! Helpers the fuzz targets share: a cursor that turns the fuzzer's bytes into the parameters of
//! a target (so that seeds are plain bytes a person can write, see `fuzz/seeds/README.md`), and
//! the scratch folder the file-based loaders read from.
#![deny(missing_docs)]

pub mod can_input;
pub mod chunks;
pub mod cursor;
pub mod generated;
pub mod modbus_request;
pub mod scan_check;
pub mod scratch;
pub mod shipped;

pub use cursor::Cursor;
