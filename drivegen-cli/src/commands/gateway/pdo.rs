//! A drive's values by TPDO (`pdo`, CANopen): the parameters a TPDO can carry come from one the
//! drive sends at each SYNC of its bus ([`PdoBus`]) or by its event timer, set up through
//! `watch --pdo`'s own code (its plan, its TPDO programming, and its restore when the drive
//! goes offline or the gateway stops, a signal included); the others are polled by SDO as
//! before, and the log says why each one is.

use std::time::{Duration, Instant};

use drivebus::interpret::Shown;
use drivegen::gateway_file::PdoUse;
use drivegen::ir::Parameter;

use super::exposed::Drive;
use super::pdo_bus::PdoBus;
use crate::commands::read;
use crate::commands::watch::pdo_plan::{self, Trigger};
use crate::commands::watch::tpdo_notice::{Notice, Severity};
use crate::commands::watch::tpdo_setup::TpdoSetup;
use crate::connect::Session;
use crate::error::CliError;

/// The most bytes one PDO carries.
const PDO_BYTES: usize = 8;

/// A drive's parameters split between its TPDO and SDO polls, and its TPDO once set up.
pub struct ByPdo<'d> {
    /// The places (among the drive's parameters) of those the TPDO carries.
    mapped: Vec<usize>,
    /// The places of those polled by SDO.
    polled: Vec<usize>,
    /// At SYNC, or by the event timer every `interval_ms`.
    trigger: Trigger,
    /// How long the drive has to send its TPDO.
    timeout: Duration,
    /// NMT Start before, Enter Pre-Operational after.
    start: bool,
    /// The TPDO, set up at the first poll after the drive was reached (put back when it is
    /// dropped).
    setup: Option<TpdoSetup<'d>>,
    /// The number of the last TPDO taken (each is taken once).
    taken: u64,
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
        // The file refuses an event timer beyond its 16 bits.
        let event_ms = u16::try_from(drive.interval_ms).unwrap_or(u16::MAX);
        Self {
            mapped,
            polled,
            trigger: match drive.pdo {
                PdoUse::Event => Trigger::EventTimer(event_ms),
                _ => Trigger::Sync,
            },
            timeout: Duration::from_millis(drive.bus.timeout_ms),
            start: drive.pdo_start,
            setup: None,
            taken: 0,
        }
    }

    /// The CAN identifier its TPDO goes out on, once set up: no other drive on the bus may
    /// take it.
    pub fn can_id(&self) -> Option<u16> {
        let setup = self.setup.as_ref()?;
        setup.nodes().first().map(|node| node.choice.can_id())
    }

    /// The drive's values, in the order of `parameters`: from its next TPDO on `bus` (set up
    /// first if need be, on a CAN identifier none of `taken` is), and the rest read by SDO. A
    /// drive that has no TPDO to take them is polled by SDO whole from then on (logged).
    pub fn read(
        &mut self,
        drive: &'d Drive,
        session: &mut Session<'d>,
        parameters: &[&'d Parameter],
        bus: &mut PdoBus,
        taken: &[u16],
    ) -> Result<Vec<Shown>, CliError> {
        let by_pdo = self.sample(drive, session, parameters, bus, taken)?;
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

    /// The mapped parameters from the drive's next TPDO (none when none are mapped): at SYNC,
    /// one that came after the bus's last SYNC; by event timer, one that came after the last
    /// taken. None within the timeout: the TPDO is put back (set up again at the next poll
    /// that reaches the drive) and the poll fails.
    fn sample(
        &mut self,
        drive: &'d Drive,
        session: &Session<'d>,
        parameters: &[&'d Parameter],
        bus: &mut PdoBus,
        taken: &[u16],
    ) -> Result<Vec<Shown>, CliError> {
        if self.mapped.is_empty() {
            return Ok(Vec::new());
        }
        let setup = match self.setup.take() {
            Some(setup) => self.setup.insert(setup),
            None => {
                let Some(begun) = self.begin(drive, session, parameters, taken)? else {
                    return Ok(Vec::new());
                };
                // What came before (the drive's TPDO as it was mapped) is never taken.
                self.taken = bus.mark(begun.bus())?;
                self.setup.insert(begun)
            }
        };
        let Some(node) = setup.nodes().first() else {
            return Err(CliError::Io("no node set up".into()));
        };
        let can = setup.bus();
        let since = match self.trigger {
            Trigger::Sync => Some(bus.last_sync(can)?),
            Trigger::EventTimer(_) => None,
        };
        let deadline = Instant::now() + self.timeout;
        let can_id = node.choice.can_id();
        match bus.take(can, can_id, self.taken, since, deadline)? {
            Some((payload, seq)) => {
                self.taken = seq;
                setup.values(node, &payload)
            }
            None => {
                let why = format!(
                    "no TPDO {} (COB-ID {can_id:03X}h) from node {} within {} ms",
                    node.choice.watched.number,
                    node.id.0,
                    self.timeout.as_millis()
                );
                // Put back (as far as the drive answers) and set up again once it answers.
                self.setup = None;
                Err(CliError::Io(why))
            }
        }
    }

    /// Sets up the TPDO of the mapped parameters; `None` (and every parameter polled by SDO
    /// from now on) when the drive cannot send them by TPDO.
    fn begin(
        &mut self,
        drive: &'d Drive,
        session: &Session<'d>,
        parameters: &[&'d Parameter],
        taken: &[u16],
    ) -> Result<Option<TpdoSetup<'d>>, CliError> {
        let mapped: Vec<&Parameter> = self.mapped.iter().map(|&i| parameters[i]).collect();
        let sessions = std::slice::from_ref(session);
        let setup = TpdoSetup::begin(
            sessions,
            &drive.device,
            &mapped,
            self.trigger,
            self.start,
            taken,
            in_the_log,
        );
        match setup {
            Ok(setup) => {
                let how = match self.trigger {
                    Trigger::Sync => "at SYNC".to_owned(),
                    Trigger::EventTimer(ms) => format!("by event timer every {ms} ms"),
                };
                tracing::info!(drive = %drive.name, "values by TPDO ({how}): {}", names(&mapped));
                Ok(Some(setup))
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

    /// Puts the TPDO back, to set it up again once the drive answers.
    pub fn end(&mut self) {
        self.setup = None;
    }
}

/// The gateway's way to show what a TPDO set-up tells: in its log, at the notice's level.
fn in_the_log(notice: &Notice) {
    match notice.severity() {
        Severity::Info => tracing::info!("{notice}"),
        Severity::Warning => tracing::warn!("{notice}"),
        Severity::Error => tracing::error!("{notice}"),
    }
}

fn names(parameters: &[&Parameter]) -> String {
    let names: Vec<&str> = parameters.iter().map(|p| p.name.as_str()).collect();
    names.join(", ")
}
