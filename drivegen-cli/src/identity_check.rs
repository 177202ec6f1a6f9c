//! `drivegen write` checks the drive's identity first: every `[identity]` parameter the bus
//! reaches (the firmware / configuration parameter; over CANopen also the vendor-ID, product code
//! and revision at 1018h) must hold a value the description covers, or nothing is written
//! (`--no-identity-check` skips this).

use drivegen::ir::Device;

use crate::codec;
use crate::connect::Session;
use crate::error::CliError;

/// Reads the identity parameters the session's bus reaches and fails with
/// [`CliError::IdentityMismatch`] at the first value not covered. A description without
/// `[identity]` has nothing to check.
pub fn verify(session: &mut Session, device: &Device) -> Result<(), CliError> {
    let mut checks = device.identity_checks();
    checks.retain(|c| session.can_read(c.parameter));
    for check in &checks {
        let bytes = session
            .read_many(&[check.parameter])?
            .pop()
            .unwrap_or_default();
        let shown = drivebus::interpret::show(device, check.parameter, &bytes);
        if codec::raw_json(&shown.raw)
            .as_i64()
            .is_some_and(|v| check.covered.contains(v.into()))
        {
            continue;
        }
        return Err(CliError::IdentityMismatch {
            parameter: check.parameter.name.clone(),
            expected: check.covered.clone(),
            found: codec::raw_json(&shown.raw).to_string(),
        });
    }
    Ok(())
}
