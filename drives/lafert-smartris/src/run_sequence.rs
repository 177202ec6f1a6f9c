//! The Modbus-mode run sequence of the Modbus manual §4.2.1 (lines 1185-1222; user guide §7.6,
//! lines 6545-6611) as typed steps on the drive handle: verify the operation mode, enable
//! (T2/T5), set the speed or torque setpoint, and stop with the ramp, stop (T4) or go to standby
//! (T3/T6). Each step checks the drive status and says what is wrong when it cannot go on.
//!
//! The control word values and the states each command leaves come from the description's
//! `[state_machine]` (the generated [`modbus_run::MACHINE`]), not from this file. What a step
//! decides from what it read is a plain function here, which the blocking steps and their async
//! twins (`run_sequence_async.rs`, feature `async`) both call.
//!
//! The manual reads the drive status with "func. 0x03" (ERRATA.md M12); it is input register
//! 0x0060, read with FC 0x04, as the generated `drive_status` accessor does.

use core::fmt;

use drivebus::modbus::Modbus;
use drivebus::units::{AmperesRms, Rpm};
use drivebus::{Error, Link};

use crate::modbus_run::{self, MACHINE};
use crate::types::{ControlWord, DriveStatus, ErrorCode, OperationMode};
use crate::Smartris;

/// The two Modbus control modes the drive runs in (holding 0x0207, changed only by a store and a
/// reset: see [`Smartris::write_store_reset`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ControlMode {
    /// The drive follows the torque setpoint (holding 0x0047).
    Torque,
    /// The drive follows the speed setpoint (holding 0x0042).
    Velocity,
}

impl ControlMode {
    /// The operation mode register value of this mode.
    pub const fn operation_mode(self) -> OperationMode {
        match self {
            Self::Torque => OperationMode::TORQUE,
            Self::Velocity => OperationMode::VELOCITY,
        }
    }

    /// The drive status bit set while the drive runs in this mode.
    pub const fn run_status(self) -> DriveStatus {
        match self {
            Self::Torque => DriveStatus::RUN_TORQUE,
            Self::Velocity => DriveStatus::RUN_VELOCITY,
        }
    }
}

/// Why a run-sequence step could not be carried out.
#[derive(Debug, Clone, PartialEq)]
pub enum RunError {
    /// A request failed (bus, exception, or a value the drive refuses).
    Bus(Error),
    /// The drive is in alarm (drive status bit 4); `code` is its error code (input 0x0063), with
    /// `class()`, `led_code()` and `meaning()`.
    InAlarm {
        /// The active error code.
        code: ErrorCode,
    },
    /// The drive is in the SAFE state: STO is active and it cannot be enabled over Modbus.
    SafeTorqueOff,
    /// The drive runs in another operation mode; changing it needs a store and a reset.
    WrongMode {
        /// The mode the step needs.
        expected: OperationMode,
        /// The mode the drive reports (holding 0x0207).
        actual: OperationMode,
    },
    /// The drive is not in a state the step needs.
    WrongState {
        /// Any of these states would do.
        expected: DriveStatus,
        /// The drive status that was read.
        status: DriveStatus,
    },
}

impl From<Error> for RunError {
    fn from(error: Error) -> Self {
        Self::Bus(error)
    }
}

impl fmt::Display for RunError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Bus(e) => write!(f, "request failed: {e}"),
            Self::InAlarm { code } => {
                write!(f, "drive in alarm, error code {:#06x} ({code:?})", code.raw())?;
                if let Some(meaning) = code.meaning() {
                    write!(f, ": {meaning}")?;
                }
                Ok(())
            }
            Self::SafeTorqueOff => write!(f, "drive in SAFE state (STO active)"),
            Self::WrongMode { expected, actual } => write!(
                f,
                "drive is in operation mode {actual:?}, the step needs {expected:?} (store and reset to change it)"
            ),
            Self::WrongState { expected, status } => write!(
                f,
                "drive status {:#06x} ({status:?}), the step needs one of {expected:?}",
                status.bits()
            ),
        }
    }
}

impl core::error::Error for RunError {}

/// Step 3's verdict: the operation mode read (holding 0x0207) must be `mode`'s.
pub(crate) fn mode_verdict(mode: ControlMode, actual: OperationMode) -> Result<(), RunError> {
    if actual == mode.operation_mode() {
        Ok(())
    } else {
        Err(RunError::WrongMode {
            expected: mode.operation_mode(),
            actual,
        })
    }
}

/// What the drive status read says of a step that needs one of `expected`.
pub(crate) enum StatusVerdict {
    /// The drive is in one of the states.
    In(DriveStatus),
    /// The drive is in alarm: the error code (input 0x0063) is to be read and reported.
    Alarm,
    /// The step cannot go on.
    Refused(RunError),
}

/// The verdict on `status` for a step that needs one of `expected`.
pub(crate) fn status_verdict(status: DriveStatus, expected: DriveStatus) -> StatusVerdict {
    if status.contains(DriveStatus::ALARM) {
        StatusVerdict::Alarm
    } else if status.contains(DriveStatus::SAFE) {
        StatusVerdict::Refused(RunError::SafeTorqueOff)
    } else if status.intersects(expected) {
        StatusVerdict::In(status)
    } else {
        StatusVerdict::Refused(RunError::WrongState { expected, status })
    }
}

/// The states a command leads from straight into `target`, as drive status bits.
pub(crate) fn commanded_from(target: modbus_run::State) -> DriveStatus {
    let to = MACHINE.state_index(target.name());
    let sources = to.into_iter().flat_map(|to| MACHINE.commanded_from(to));
    let shown = sources.flat_map(|state| state.patterns).map(|p| p.value);
    DriveStatus::from_bits_retain(shown.fold(0, |all, bits| all | bits))
}

/// The control word of the described transition from `status` (one of `expected`, the states
/// [`commanded_from`] gives) straight into `target`.
pub(crate) fn command_into(
    target: modbus_run::State,
    status: DriveStatus,
    expected: DriveStatus,
) -> Result<ControlWord, RunError> {
    let to = MACHINE.state_index(target.name());
    MACHINE
        .recognise(status.bits())
        .zip(to)
        .and_then(|(from, to)| MACHINE.command_between(from, to))
        .map(ControlWord::from_bits_retain)
        .ok_or(RunError::WrongState { expected, status })
}

impl<L: Link<Protocol = Modbus>> Smartris<L> {
    /// Step 3: the drive's operation mode (holding 0x0207) must be `mode`.
    pub fn check_operation_mode(&mut self, mode: ControlMode) -> Result<(), RunError> {
        mode_verdict(mode, self.operation_mode().read()?)
    }

    /// Steps 3-6: checks the mode and that the drive is switched on (standby) or stopped without
    /// an alarm, writes RUN + STOP disabled (control word 0x0003, T2 / T5), and checks that the
    /// drive now runs in `mode`. Returns the drive status read last.
    pub fn enable(&mut self, mode: ControlMode) -> Result<DriveStatus, RunError> {
        self.check_operation_mode(mode)?;
        self.command_into(modbus_run::State::Run)?;
        self.status_in(mode.run_status())
    }

    /// Step 7, velocity mode: writes the speed setpoint (holding 0x0042) while the drive runs in
    /// velocity mode. Range-checked against the description, and against ± the full-scale
    /// velocity (read first), before anything is sent.
    pub fn set_speed(&mut self, speed: Rpm) -> Result<(), RunError> {
        self.status_in(DriveStatus::RUN_VELOCITY)?;
        Ok(self.speed_setpoint().write(speed)?)
    }

    /// Step 7, torque mode: writes the torque setpoint (holding 0x0047) while the drive runs in
    /// torque mode.
    pub fn set_torque(&mut self, torque: AmperesRms) -> Result<(), RunError> {
        self.status_in(DriveStatus::RUN_TORQUE)?;
        Ok(self.torque_setpoint().write(torque)?)
    }

    /// Step 9, "stop the motor with ramp": speed setpoint 0 in velocity mode; the drive stays
    /// enabled.
    pub fn stop_with_ramp(&mut self) -> Result<(), RunError> {
        self.set_speed(Rpm(0.0))
    }

    /// Step 9, stop command (T4): control word 0x0001 (RUN, STOP enabled) while running; the
    /// drive stops at once with maximum torque, like a quick stop, and must report STOP.
    pub fn stop(&mut self) -> Result<DriveStatus, RunError> {
        self.command_into(modbus_run::State::Stop)?;
        self.status_in(DriveStatus::STOP)
    }

    /// Step 9, standby command (T3 from run, T6 from stop; the manual labels it T4, ERRATA.md
    /// M14): control word 0x0002; the drive is disabled and must report STANDBY.
    pub fn standby(&mut self) -> Result<DriveStatus, RunError> {
        self.command_into(modbus_run::State::Standby)?;
        self.status_in(DriveStatus::STANDBY)
    }

    /// Writes the control word of the described transition from the drive's present state
    /// straight into `target`; refuses (nothing written) in alarm, on STO, or in a state no
    /// command leads from into `target`.
    fn command_into(&mut self, target: modbus_run::State) -> Result<(), RunError> {
        let expected = commanded_from(target);
        let status = self.status_in(expected)?;
        let command = command_into(target, status, expected)?;
        self.control_word().write(command)?;
        Ok(())
    }

    /// Reads the drive status; fails with the decoded error code in alarm, on STO, or when none
    /// of the `expected` states is set.
    fn status_in(&mut self, expected: DriveStatus) -> Result<DriveStatus, RunError> {
        match status_verdict(self.drive_status().read()?, expected) {
            StatusVerdict::In(status) => Ok(status),
            StatusVerdict::Alarm => Err(RunError::InAlarm {
                code: self.error_code().read()?,
            }),
            StatusVerdict::Refused(error) => Err(error),
        }
    }
}
