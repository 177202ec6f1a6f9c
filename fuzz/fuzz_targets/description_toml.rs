//! The TOML description loader fed arbitrary bytes: load, lower, validate, and for a valid
//! description generate code and export an EDS.
//!
//! Input: the bytes of `device.toml` (not necessarily UTF-8). It may include files beside it
//! (only itself exists there) or elsewhere on the machine. Asserts that checking renders its
//! diagnostics, and that a valid device satisfies `fuzz::generated::check`.
#![no_main]

use fuzz::{generated, scratch};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let path = scratch::write("device.toml", bytes);
    let checked = drivegen::check(&path);
    let _ = checked.render();
    if let Some(device) = &checked.device {
        generated::check(device);
    }
});
