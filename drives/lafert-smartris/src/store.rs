//! Store to E2PROM and reset: how settings marked "after store + reset" take effect (Modbus manual
//! §4.2: STORE E2PROM DATA 0x0000, SYSTEM RESET 0xA5A5, "wait about 2 sec for new communication").

use core::fmt;
use core::time::Duration;

use drivebus::modbus::Modbus;
use drivebus::{BusError, Error, Link, Parameter, Writable};

use crate::wait::{Clock, RebootWait};
use crate::Smartris;

/// The value written to a command register. The manual needs "no specific value"; its frames write
/// 1 (section 1.2.1, lines 163 and 168).
const COMMAND_TRIGGER: u16 = 1;

/// Which step of a store-and-reset failed, with the cause.
#[derive(Debug, Clone, PartialEq)]
pub enum StoreResetError {
    /// Writing the new value failed; nothing was stored.
    Write(Error),
    /// The store command (holding 0x0000) failed; the drive was not reset.
    Store(Error),
    /// The reset command (holding 0xA5A5) was refused.
    Reset(Error),
    /// The drive did not answer again before the deadline.
    NoAnswerAfterReset {
        /// Time from the reset command to the last attempt.
        waited: Duration,
        /// Why the last attempt failed.
        last: Error,
    },
}

impl fmt::Display for StoreResetError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Write(e) => write!(f, "writing the value failed, nothing stored: {e}"),
            Self::Store(e) => write!(f, "the store command (0x0000) failed: {e}"),
            Self::Reset(e) => write!(f, "the reset command (0xA5A5) failed: {e}"),
            Self::NoAnswerAfterReset { waited, last } => write!(
                f,
                "no answer {} ms after the reset: {last}",
                waited.as_millis()
            ),
        }
    }
}

impl core::error::Error for StoreResetError {}

impl<L: Link<Protocol = Modbus>> Smartris<L> {
    /// Writes `value` to `P`, stores it in E2PROM, resets the drive and waits until it answers
    /// again; for parameters that take effect only after a store and a reset (operation mode,
    /// Modbus address, baud rate, ...). Returns how long the drive took to come back.
    pub fn write_store_reset<P: Writable<Modbus>>(
        &mut self,
        value: <P as Parameter>::Value,
        wait: RebootWait,
        clock: &mut impl Clock,
    ) -> Result<Duration, StoreResetError> {
        self.device()
            .write::<P>(value)
            .map_err(StoreResetError::Write)?;
        self.store_and_reset(wait, clock)
    }

    /// Stores the parameters in E2PROM, resets the drive and polls the drive status until the
    /// drive answers or `wait.deadline` has passed. Returns how long the drive took to come back.
    pub fn store_and_reset(
        &mut self,
        wait: RebootWait,
        clock: &mut impl Clock,
    ) -> Result<Duration, StoreResetError> {
        self.store_eeprom()
            .write(COMMAND_TRIGGER)
            .map_err(StoreResetError::Store)?;
        let reset_at = clock.now();
        match self.system_reset().write(COMMAND_TRIGGER) {
            // The drive may reboot before its answer is out; the wait below tells whether it did.
            Err(error) if error.bus() != Some(&BusError::Timeout) => {
                return Err(StoreResetError::Reset(error))
            }
            _ => {}
        }
        self.wait_for_answer(reset_at, wait, clock)
    }

    /// Polls the drive status until a read succeeds or the deadline passes.
    fn wait_for_answer(
        &mut self,
        reset_at: Duration,
        wait: RebootWait,
        clock: &mut impl Clock,
    ) -> Result<Duration, StoreResetError> {
        loop {
            clock.sleep(wait.poll_interval);
            let attempt = self.drive_status().read_raw();
            let waited = clock.now().saturating_sub(reset_at);
            match attempt {
                Ok(_) => return Ok(waited),
                Err(last) if waited >= wait.deadline => {
                    return Err(StoreResetError::NoAnswerAfterReset { waited, last })
                }
                Err(_) => {}
            }
        }
    }
}
