//! Speeds at the wheel (the gearbox output shaft) for the product models: the vl objects are rpm
//! at the motor shaft (6042h through the vl dimension factor 604Ch), and the wheel turns
//! `gear_ratio` times slower. The ratio is the per-model constant `gear_ratio` of the description
//! (section 3, lines 345-465: the exact value where the manual prints one, e.g. (63/17)² for
//! the standard SWD 150, line 465), fixed by the model the handle is opened with
//! (`Swd::with_model`).

#[cfg(feature = "std")]
use drivebus::canopen::{CanOpenLink, SdoBus};
use drivebus::units::Rpm;
use drivebus::Ratio;
#[cfg(feature = "std")]
use drivebus::{Error, ValueError};

use crate::Model;
#[cfg(feature = "std")]
use crate::Swd;

/// The name of the per-model constant (the description's `[[constant]]`).
const GEAR_RATIO: &str = "gear_ratio";

impl Model {
    /// The model's gearbox ratio (motor turns per wheel turn), exact.
    pub fn gear_ratio(self) -> Option<Ratio> {
        self.constants()
            .iter()
            .find(|(name, _)| *name == GEAR_RATIO)
            .map(|(_, ratio)| *ratio)
    }
}

/// The wheel speed of a motor speed through `gear_ratio`; `None` for a zero ratio.
pub fn wheel_speed(motor: Rpm, gear_ratio: Ratio) -> Option<Rpm> {
    let ratio = gear_ratio.to_f64();
    (ratio != 0.0).then(|| Rpm(motor.0 / ratio))
}

/// The motor speed that turns the wheel at `wheel` through `gear_ratio`.
pub fn motor_speed(wheel: Rpm, gear_ratio: Ratio) -> Rpm {
    Rpm(wheel.0 * gear_ratio.to_f64())
}

#[cfg(feature = "std")]
impl<B: SdoBus> Swd<CanOpenLink<B>> {
    /// The gear ratio of the model the handle was opened with; without a model,
    /// `ValueError::BadScale` naming `gear_ratio`.
    pub fn gear_ratio(&mut self) -> Result<Ratio, Error> {
        self.device()
            .given()
            .get(GEAR_RATIO)
            .filter(|ratio| ratio.numerator() != 0)
            .ok_or(Error::Value(ValueError::BadScale {
                parameter: GEAR_RATIO,
            }))
    }

    /// The speed setpoint in rpm at the wheel: the motor setpoint (6042h) is `wheel` times the
    /// model's gear ratio. Refused before anything is sent when no model is selected.
    pub fn set_wheel_speed(&mut self, wheel: Rpm) -> Result<(), Error> {
        let ratio = self.gear_ratio()?;
        self.set_motor_speed(motor_speed(wheel, ratio))
    }

    /// The speed setpoint (6042h) in rpm at the wheel.
    pub fn wheel_speed_setpoint(&mut self) -> Result<Rpm, Error> {
        let ratio = self.gear_ratio()?;
        let motor = self.vl_target_velocity().read()?;
        at_the_wheel(motor, ratio)
    }

    /// The measured wheel speed in rpm: the vl velocity actual value (6044h, rpm at the motor
    /// through the dimension factor 604Ch) divided by the model's gear ratio. Without a model,
    /// `ValueError::BadScale` naming `gear_ratio`, and nothing is read.
    pub fn wheel_speed_actual(&mut self) -> Result<Rpm, Error> {
        let ratio = self.gear_ratio()?;
        let motor = self.vl_velocity_actual_value().read()?;
        at_the_wheel(motor, ratio)
    }
}

/// `motor` at the wheel through `ratio`; a zero ratio is `ValueError::BadScale`.
#[cfg(feature = "std")]
fn at_the_wheel(motor: Rpm, ratio: Ratio) -> Result<Rpm, Error> {
    wheel_speed(motor, ratio).ok_or(Error::Value(ValueError::BadScale {
        parameter: GEAR_RATIO,
    }))
}
