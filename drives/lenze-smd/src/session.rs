//! Unlocking and locking as a typed session (sections 4.5 and 4.6, lines 405-425). Writes that
//! need an unlock go through a [`Session`], which exists only between a successful unlock and its
//! end: [`Session::lock`] (register #1 bit 1), or dropping it, which locks too. What the session
//! allows is in its type: commands and the serial speed with controls unlocked (#48 = 0),
//! parameter writes with parameters unlocked (#49 = C94), both with #48 = C94.
//!
//! Before unlocking, the preconditions the drive can report are checked and nothing is sent when
//! one fails: register #50 must name a known configuration (line 314), and for controls C01 must
//! be 10 or 11 (line 411). An unlock also ends without the master's doing when C01 changes, on
//! power-down or on a serial timeout (lines 414, 425): the next write then fails with
//! [`SmdError::Locked`] (exception 0x01, line 416) and a new unlock is needed.
//!
//! A parameters-only session cannot command the drive; this does not compile:
//!
//! ```compile_fail
//! # use drivebus::memory::MemoryBus;
//! # use drivebus::modbus::UnitId;
//! # fn f(drive: &mut lenze_smd::LenzeSmd<drivebus::modbus::ModbusLink<MemoryBus>>) {
//! let mut session = drive.unlock_parameter_writing(0).unwrap();
//! session.command(lenze_smd::Command::Start); // no `command` on Session<Parameters>
//! # }
//! ```
//!
//! and a controls-only session cannot write parameters:
//!
//! ```compile_fail
//! # use drivebus::memory::MemoryBus;
//! # use drivebus::units::Seconds;
//! # fn f(drive: &mut lenze_smd::LenzeSmd<drivebus::modbus::ModbusLink<MemoryBus>>) {
//! let mut session = drive.unlock_controls().unwrap();
//! session.write::<lenze_smd::params::AccelerationTime>(Seconds(1.0));
//! # }
//! ```

use core::marker::PhantomData;

use drivebus::modbus::{Modbus, ModbusLink, RegisterBus};
use drivebus::units::Hertz;
use drivebus::Writable;

use crate::command::Command;
use crate::error::SmdError;
use crate::types::ControlSource;
use crate::{LenzeSmd, Trigger};

mod access {
    /// What a session may write; sealed.
    pub trait Access {}
}
use access::Access;

/// Controls unlocked (#48 = 0): drive commands (#1) and the serial speed (#40).
#[derive(Debug)]
pub enum Controls {}
/// Controls and parameters unlocked (#48 = password C94).
#[derive(Debug)]
pub enum ControlsAndParameters {}
/// Parameters unlocked (#49 = password C94): every writable register except #1.
#[derive(Debug)]
pub enum Parameters {}

impl Access for Controls {}
impl Access for ControlsAndParameters {}
impl Access for Parameters {}

/// Sessions that may command the drive and set the serial speed.
pub trait CanCommand: Access {}
impl CanCommand for Controls {}
impl CanCommand for ControlsAndParameters {}

/// Sessions that may write programming parameters.
pub trait CanWriteParameters: Access {}
impl CanWriteParameters for ControlsAndParameters {}
impl CanWriteParameters for Parameters {}

/// An unlocked drive. Locks the drive when dropped (best effort; [`Session::lock`] reports).
#[derive(Debug)]
pub struct Session<'d, B: RegisterBus, A: Access> {
    drive: &'d mut LenzeSmd<ModbusLink<B>>,
    locked: bool,
    access: PhantomData<A>,
}

/// Control sources (C01) that allow serial control (Table 4, lines 333-334).
const SERIAL_CONTROL: [ControlSource; 2] =
    [ControlSource::ANALOG_MODBUS, ControlSource::C40_MODBUS];

impl<B: RegisterBus> LenzeSmd<ModbusLink<B>> {
    /// Unlocks controls (#48 = 0): commands and the serial speed, not parameters.
    pub fn unlock_controls(&mut self) -> Result<Session<'_, B, Controls>, SmdError> {
        self.check_serial_control()?;
        self.unlock_commands().write(0)?;
        Ok(Session::new(self))
    }

    /// Unlocks controls and parameters with the programming password C94 (#48 = password).
    pub fn unlock_all(
        &mut self,
        password: u16,
    ) -> Result<Session<'_, B, ControlsAndParameters>, SmdError> {
        self.check_serial_control()?;
        self.unlock_commands().write(password)?;
        Ok(Session::new(self))
    }

    /// Unlocks parameter writing only (#49 = password C94), for when no drive control is needed.
    pub fn unlock_parameter_writing(
        &mut self,
        password: u16,
    ) -> Result<Session<'_, B, Parameters>, SmdError> {
        self.detect_variant()?.writable()?;
        self.unlock_parameters().write(password)?;
        Ok(Session::new(self))
    }

    /// The configuration is known and C01 allows serial control.
    fn check_serial_control(&mut self) -> Result<(), SmdError> {
        self.detect_variant()?.writable()?;
        let control_source = self.control_source().read()?;
        if SERIAL_CONTROL.contains(&control_source) {
            Ok(())
        } else {
            Err(SmdError::NotSerialControl { control_source })
        }
    }
}

impl<'d, B: RegisterBus, A: Access> Session<'d, B, A> {
    fn new(drive: &'d mut LenzeSmd<ModbusLink<B>>) -> Self {
        Self {
            drive,
            locked: false,
            access: PhantomData,
        }
    }

    /// The drive, for reads (always allowed, line 417).
    pub fn drive(&mut self) -> &mut LenzeSmd<ModbusLink<B>> {
        self.drive
    }

    /// Locks controls and parameters (#1 = 0x0002, lines 415, 446 and 801) and ends the
    /// session. A drive that answers exception 01 is locked already (its unlock ended): that is
    /// success too.
    pub fn lock(mut self) -> Result<(), SmdError> {
        self.locked = true;
        match self.write_lock() {
            Err(SmdError::Locked { .. }) => Ok(()),
            other => other,
        }
    }

    fn write_lock(&mut self) -> Result<(), SmdError> {
        Ok(self.drive.lock_security().trigger()?)
    }
}

impl<B: RegisterBus, A: CanCommand> Session<'_, B, A> {
    /// Writes one command to register #1.
    pub fn command(&mut self, command: Command) -> Result<(), SmdError> {
        Ok(self.drive.trigger(command)?)
    }

    /// Writes the serial speed command (#40) after checking it against the drive's current C10
    /// (minimum) and C11 (maximum output frequency) (Table 6, line 501): the generated bounded
    /// write of the description's `bounds`.
    pub fn set_serial_speed(&mut self, speed: Hertz) -> Result<(), SmdError> {
        Ok(self.drive.write_serial_speed_command(speed)?)
    }
}

impl<B: RegisterBus, A: CanWriteParameters> Session<'_, B, A> {
    /// Writes programming parameter `P` (range-checked against the description first).
    pub fn write<P: Writable<Modbus>>(&mut self, value: P::Value) -> Result<(), SmdError> {
        Ok(self.drive.device().write::<P>(value)?)
    }
}

impl<B: RegisterBus, A: Access> Drop for Session<'_, B, A> {
    fn drop(&mut self) {
        if !self.locked {
            // Best effort: a failure here is reported by the next write as `Locked` or a bus error.
            let _ = self.write_lock();
        }
    }
}
