//! The EDS / DCF reader fed arbitrary bytes (any encoding).
//!
//! Input: the file's bytes. Asserts that a device read without errors satisfies
//! `fuzz::generated::check`: its code parses, its accessors are distinct, and its EDS
//! export reads back with the same objects.
#![no_main]

use fuzz::generated;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let read = generated::eds_device(bytes);
    if !read.has_errors {
        generated::check(&read.device);
    }
});
