//! A simulated drive is one its description covers: the `[identity]` parameter starts at the
//! first covered value (unless the description gives it a default), so `verify_identity` and
//! `drivegen write` accept it. Tests preset another value to simulate a foreign firmware.

use drivegen::ir::Device;

/// The identity parameter and the value the simulated drive reports, if the description has one
/// and gives it no default.
pub fn covered_identity(device: &Device) -> Option<(String, i128)> {
    let identity = device.identity.as_ref()?;
    let parameter = device.parameter(identity.parameter.as_deref()?)?;
    let value = *identity.values.first()?;
    parameter
        .default
        .is_none()
        .then(|| (parameter.name.clone(), i128::from(value)))
}
