//! Reading many parameters from a live drive so that one that fails does not hide the others:
//! all in one batch, and where that fails, one by one with each failure's reason.

use drivegen::ir::Parameter;

use crate::connect::Session;
use crate::error::CliError;

/// The raw bytes of one parameter.
pub fn read_one(session: &mut Session, parameter: &Parameter) -> Result<Vec<u8>, CliError> {
    Ok(session.read_many(&[parameter])?.pop().unwrap_or_default())
}

/// The raw bytes of each parameter, or why it could not be read.
pub fn read_each(session: &mut Session, parameters: &[&Parameter]) -> Vec<Result<Vec<u8>, String>> {
    if parameters.is_empty() {
        return Vec::new();
    }
    if let Ok(values) = session.read_many(parameters) {
        return values.into_iter().map(Ok).collect();
    }
    parameters
        .iter()
        .map(|p| {
            read_one(session, p)
                // The reason stands in a file or a report: what was sent is said there.
                .map_err(|e| e.to_string().replace(" (nothing was sent)", ""))
        })
        .collect()
}
