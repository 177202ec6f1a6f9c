//! `drivegen write` checks the drive's identity first: the `[identity]` parameter must hold a
//! value the description covers, or nothing is written (`--no-identity-check` skips this).

use drivegen::ir::Device;

use crate::codec;
use crate::connect::Session;
use crate::error::CliError;

/// Reads the identity parameter and fails with [`CliError::IdentityMismatch`] when its value is
/// not covered. A description without an identity parameter has nothing to check.
pub fn verify(session: &mut Session, device: &Device) -> Result<(), CliError> {
    let Some(identity) = &device.identity else {
        return Ok(());
    };
    let Some(parameter) = identity
        .parameter
        .as_deref()
        .and_then(|name| device.parameter(name))
    else {
        return Ok(());
    };
    let bytes = session.read_many(&[parameter])?.pop().unwrap_or_default();
    let shown = codec::show(device, parameter, &bytes);
    if shown.raw.as_i64().is_some_and(|v| identity.covers_value(v)) {
        return Ok(());
    }
    Err(CliError::IdentityMismatch {
        parameter: parameter.name.clone(),
        expected: identity.values.clone(),
        found: shown.raw.to_string(),
    })
}
