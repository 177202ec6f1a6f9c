//! Emitters: turn a valid IR into artifacts. Only Rust for now; every emitter reads the IR alone.

/// The naming policy, kept at the crate root ([`crate::names`]) so that validation and the EDS
/// reader share it without reaching into the emitter.
pub use crate::names as ident;
pub mod rust;

mod doc;
