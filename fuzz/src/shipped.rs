//! The shipped descriptions, checked once per fuzzing process, for the targets that run the
//! simulator (a fresh drive per input keeps every run reproducible from its input alone).

use std::collections::BTreeMap;
use std::sync::{Mutex, OnceLock};

use drivegen::ir::Device;

/// The checked device of `descriptions/<name>`; panics if it does not check.
pub fn device(name: &'static str) -> &'static Device {
    static DEVICES: OnceLock<Mutex<BTreeMap<&'static str, &'static Device>>> = OnceLock::new();
    let mut devices = DEVICES
        .get_or_init(Default::default)
        .lock()
        .expect("not poisoned");
    devices.entry(name).or_insert_with(|| {
        let path = format!("{}/../descriptions/{name}", env!("CARGO_MANIFEST_DIR"));
        let checked = drivegen::check(path.as_ref());
        match checked.device {
            Some(device) => Box::leak(Box::new(device)),
            None => panic!("{name}: {}", checked.render()),
        }
    })
}
