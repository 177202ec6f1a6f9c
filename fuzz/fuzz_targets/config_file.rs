//! The configuration backup reader (`drivegen config push` / `compare`) fed arbitrary bytes.
//!
//! Input: the bytes of a `config pull` file (not necessarily UTF-8). Asserts that reading never
//! panics, and that a file it accepts renders to text it reads back to the same rendering.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let Ok(text) = std::str::from_utf8(bytes) else {
        return;
    };
    let Ok(file) = drivegen::config_file::parse(text) else {
        return;
    };
    let rendered = drivegen::config_file::render(&file);
    let again = drivegen::config_file::parse(&rendered).expect("a rendered file reads back");
    assert_eq!(drivegen::config_file::render(&again), rendered);
});
