//! The connection a poller owns: opened for the first drive of its line when a drive needs it,
//! then each drive reached through it with a session of its own (its id, its description, the
//! variant it reports). A drive that fails is reached again at its next poll without a new
//! connection; the connection itself is opened again only when every drive on it failed (a
//! restarted server, a replugged adapter).

use super::exposed::Drive;
use crate::connect::{Session, SharedCan};

/// A line's connection, open or not.
pub struct Connection<'d> {
    /// The drive whose bus options open it (the line's first).
    first: &'d Drive,
    /// Whether several CANopen nodes share it (through the network manager).
    several: bool,
    /// The bus, while open; each drive's session holds a clone of it.
    open: Option<Session<'d>>,
}

impl<'d> Connection<'d> {
    /// The connection of a line whose first drive is `first`, not opened yet.
    pub fn new(first: &'d Drive, several: bool) -> Self {
        Self {
            first,
            several,
            open: None,
        }
    }

    /// `drive`'s session, reached now through the connection (opened now if need be) when it
    /// has none; why not, when the bus or the drive cannot be reached.
    pub fn reach<'s>(
        &mut self,
        drive: &'d Drive,
        session: &'s mut Option<Session<'d>>,
    ) -> Result<&'s mut Session<'d>, String> {
        if let Some(session) = session {
            return Ok(session);
        }
        let unreachable = |e: crate::error::CliError| format!("cannot reach the drive: {e}");
        let open = match &mut self.open {
            Some(open) => open,
            None => {
                let first = self.first;
                let opened = Session::open_line(&first.bus, &first.device, self.several)
                    .map_err(unreachable)?;
                self.open.insert(opened)
            }
        };
        let reached = open
            .beside(&drive.bus, &drive.device)
            .map_err(unreachable)?;
        Ok(session.insert(reached))
    }

    /// The CAN bus itself, while the connection is open on one SDO client (a bus with PDO
    /// drives: its SYNCs go out on it).
    pub fn can(&self) -> Option<SharedCan> {
        let (bus, _) = self.open.as_ref()?.can()?;
        Some(bus)
    }

    /// Closes the connection (once the drives' sessions are dropped too); the next
    /// [`reach`](Self::reach) opens it again.
    pub fn close(&mut self) {
        self.open = None;
    }
}
