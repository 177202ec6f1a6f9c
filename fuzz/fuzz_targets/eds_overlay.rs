//! An EDS under a TOML overlay, both arbitrary.
//!
//! Input: the overlay's TOML, a NUL byte, then the EDS bytes. The overlay is `overlay.toml`,
//! the EDS `drive.eds` beside it (seeds name it with `eds = "drive.eds"`). Asserts that
//! checking renders its diagnostics, and that a valid device satisfies
//! `fuzz::generated::check`.
#![no_main]

use fuzz::{generated, scratch};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let (overlay, eds) = match bytes.iter().position(|&b| b == 0) {
        Some(nul) => (&bytes[..nul], &bytes[nul + 1..]),
        None => (bytes, &[][..]),
    };
    scratch::write("drive.eds", eds);
    let path = scratch::write("overlay.toml", overlay);
    let checked = drivegen::check(&path);
    let _ = checked.render();
    if let Some(device) = &checked.device {
        generated::check(device);
    }
});
