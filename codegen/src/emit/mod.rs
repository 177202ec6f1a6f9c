//! Emitters: turn a valid IR into artifacts. Only Rust for now; every emitter reads the IR alone.

pub mod rust;

mod doc;
