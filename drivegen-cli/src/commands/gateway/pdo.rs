//! A drive's values by TPDO (`pdo = true`, CANopen): the parameters a TPDO can carry come from
//! one at each SYNC the gateway sends, through `watch --pdo`'s own code (its plan, its TPDO
//! programming and its restore when the gateway stops, a signal included); the others are
//! polled by SDO as before, and the log says why each one is.

use std::time::Duration;

use drivebus::interpret::Shown;
use drivegen::ir::Parameter;

use super::exposed::Drive;
use crate::commands::read;
use crate::commands::watch::interrupt::Interrupt;
use crate::commands::watch::pdo_plan::{self, Trigger};
use crate::commands::watch::sample::Source;
use crate::commands::watch::source_pdo::{PdoWatch, Settings};
use crate::connect::Session;
use crate::error::CliError;

/// The most bytes one PDO carries.
const PDO_BYTES: usize = 8;

/// A drive's parameters split between its TPDO and SDO polls, and the TPDO watch once begun.
pub struct ByPdo<'d> {
    /// The places (among the drive's parameters) of those the TPDO carries.
    mapped: Vec<usize>,
    /// The places of those polled by SDO.
    polled: Vec<usize>,
    settings: Settings,
    /// The watch, begun at the first poll after the drive was reached (ended, and the TPDO
    /// restored, when it is dropped).
    watch: Option<PdoWatch<'d>>,
}

impl<'d> ByPdo<'d> {
    /// Splits `parameters` of `drive`: each that a TPDO can carry, while they fit in one, by
    /// TPDO; the others by SDO, each logged with the reason.
    pub fn plan(drive: &Drive, parameters: &[&'d Parameter]) -> Self {
        let (mut mapped, mut polled, mut bytes) = (Vec::new(), Vec::new(), 0);
        for (place, parameter) in parameters.iter().enumerate() {
            let why = match pdo_plan::entries(&[*parameter]) {
                Ok(entries) => {
                    let size: usize = entries.iter().map(|e| usize::from(e.bits) / 8).sum();
                    if bytes + size <= PDO_BYTES {
                        bytes += size;
                        mapped.push(place);
                        continue;
                    }
                    format!("the TPDO is full ({bytes} of {PDO_BYTES} bytes)")
                }
                Err(refused) => refused.join("; "),
            };
            tracing::info!(drive = %drive.name, parameter = %parameter.name, "polled by SDO, not by PDO: {why}");
            polled.push(place);
        }
        let settings = Settings {
            trigger: Trigger::Sync,
            interval: Duration::from_millis(drive.interval_ms.into()),
            timeout: Duration::from_millis(drive.bus.timeout_ms),
            start: drive.pdo_start,
        };
        Self {
            mapped,
            polled,
            settings,
            watch: None,
        }
    }

    /// The drive's values, in the order of `parameters`: the TPDO's next sample (the watch
    /// begun first if need be), and the rest read by SDO. A drive that has no TPDO to take them
    /// is polled by SDO whole from then on (logged).
    pub fn read(
        &mut self,
        drive: &'d Drive,
        session: &mut Session<'d>,
        parameters: &[&'d Parameter],
    ) -> Result<Vec<Shown>, CliError> {
        let by_pdo = self.sample(drive, session, parameters)?;
        let polled: Vec<&Parameter> = self.polled.iter().map(|&i| parameters[i]).collect();
        let by_sdo = read::read_all(session, &drive.device, &polled)?;
        let mut values: Vec<Option<Shown>> = parameters.iter().map(|_| None).collect();
        let places = self.mapped.iter().zip(by_pdo);
        for (&place, shown) in places.chain(self.polled.iter().zip(by_sdo)) {
            values[place] = Some(shown);
        }
        values
            .into_iter()
            .map(|v| v.ok_or_else(|| CliError::Io("a value is missing from the sample".into())))
            .collect()
    }

    /// The TPDO's next sample of the mapped parameters (none when none are).
    fn sample(
        &mut self,
        drive: &'d Drive,
        session: &Session<'d>,
        parameters: &[&'d Parameter],
    ) -> Result<Vec<Shown>, CliError> {
        if self.mapped.is_empty() {
            return Ok(Vec::new());
        }
        let watch = match &mut self.watch {
            Some(watch) => watch,
            None => match self.begin(drive, session, parameters)? {
                Some(watch) => self.watch.insert(watch),
                None => return Ok(Vec::new()),
            },
        };
        let sample = watch.next()?;
        let outcome = sample.and_then(|mut s| s.drives.pop());
        match outcome {
            Some(Ok(values)) => Ok(values),
            Some(Err(e)) => {
                // Begun again (after the restore) at the next poll that reaches the drive.
                self.watch = None;
                Err(e)
            }
            None => Err(CliError::Io("no TPDO sample".into())),
        }
    }

    /// Begins the watch of the mapped parameters; `None` (and every parameter polled by SDO
    /// from now on) when the drive cannot send them by TPDO.
    fn begin(
        &mut self,
        drive: &'d Drive,
        session: &Session<'d>,
        parameters: &[&'d Parameter],
    ) -> Result<Option<PdoWatch<'d>>, CliError> {
        let mapped: Vec<&Parameter> = self.mapped.iter().map(|&i| parameters[i]).collect();
        let sessions = std::slice::from_ref(session);
        match PdoWatch::begin(
            sessions,
            &drive.device,
            &mapped,
            self.settings,
            Interrupt::manual(),
        ) {
            Ok(watch) => {
                tracing::info!(drive = %drive.name, "values by TPDO: {}", names(&mapped));
                Ok(Some(watch))
            }
            Err(CliError::Usage(why)) => {
                tracing::warn!(drive = %drive.name, "polled by SDO, not by PDO: {why}");
                self.polled.append(&mut self.mapped);
                self.polled.sort_unstable();
                Ok(None)
            }
            Err(e) => Err(e),
        }
    }

    /// Ends the watch (its TPDO restored), to begin again once the drive answers.
    pub fn end(&mut self) {
        self.watch = None;
    }
}

fn names(parameters: &[&Parameter]) -> String {
    let names: Vec<&str> = parameters.iter().map(|p| p.name.as_str()).collect();
    names.join(", ")
}
