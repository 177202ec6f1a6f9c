//! The quick start's velocity-mode start-up (manual appendix "SWD - Quick start", lines
//! 4072-4181, method A): velocity mode, the CiA 402 state machine to *operation enabled*, then the
//! vl ramp opened so the motor follows 6042h; halt on controlword bit 8.
//!
//! Decided against the printed frames (see ERRATA.md): the quick start enables operation with
//! 000Fh, which in velocity mode keeps the ramp closed (bits 4-6, lines 2634-2636); the crate
//! sends 007Fh. Its "Halt" frame writes 0040h (bit 6, ramp reference); halt is bit 8 (0100h).

use drivebus::canopen::{CanOpenLink, SdoBus};
use drivebus::control::driver::{ControlError, Instant};
use drivebus::units::Rpm;
use drivebus::Error;

use crate::types::{Controlword as Bits, OperatingMode};
use crate::Swd;

/// Controlword in velocity mode with operation enabled and the vl ramp enabled (bit 4), unlocked
/// (bit 5) and following the setpoint (bit 6): 007Fh.
pub const VL_OPERATION_ENABLED: u16 = 0x007F;

/// Controlword halt bit (bit 8, line 2319): the motor stops as the halt option code 605Dh says.
pub const HALT: u16 = 0x0100;

impl<B: SdoBus> Swd<CanOpenLink<B>> {
    /// Velocity mode, *operation enabled*, vl ramp open (controlword 007Fh): the drive then
    /// follows [`Swd::set_motor_speed`]. The setpoint is set to 0 first so the motor does not
    /// start on a stale value.
    pub fn start_velocity_mode(&mut self, deadline: Instant) -> Result<(), ControlError> {
        self.vl_target_velocity().write_raw(0)?;
        self.set_mode(OperatingMode::VELOCITY, deadline)?;
        self.enable_operation(deadline)?;
        self.controlword()
            .write(Bits::from_bits_retain(VL_OPERATION_ENABLED))?;
        Ok(())
    }

    /// The speed setpoint in rpm at the motor shaft (6042h, through the vl dimension factor
    /// 604Ch): the wheel turns at this speed divided by the gearbox ratio of the product.
    pub fn set_motor_speed(&mut self, speed: Rpm) -> Result<(), Error> {
        self.vl_target_velocity().write(speed)
    }

    /// Sets or clears halt (controlword bit 8), keeping the other bits.
    pub fn halt(&mut self, halt: bool) -> Result<(), Error> {
        self.controlword().modify(|word| {
            let halt_bit = Bits::from_bits_retain(HALT);
            if halt {
                word | halt_bit
            } else {
                word.difference(halt_bit)
            }
        })
    }
}
