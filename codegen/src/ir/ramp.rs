//! How fast the speed follows a setpoint (`[[ramp]]`): the parameters that hold a setpoint's
//! acceleration and deceleration, in one of the forms manuals give them. Lafert Smartris: the
//! speed ramp up / down in ms from 0 to the maximum velocity, switched by the ramp enable
//! (Modbus manual section 4.2, lines 1307-1325); CiA 402 profile velocity: profile acceleration
//! / deceleration (6083h / 6084h); CiA 402 velocity mode: delta speed over delta time (6048h /
//! 6049h). The simulator's motor model reads it; nothing is generated from it.

use serde::Serialize;

use super::Citation;
use crate::diagnostic::Span;

/// The ramp a setpoint is followed along.
#[derive(Debug, Clone, Serialize)]
pub struct Ramp {
    /// The setpoint parameter the ramp shapes.
    pub setpoint: String,
    /// How fast the speed moves away from zero.
    pub up: Slope,
    /// How fast it moves towards zero.
    pub down: Slope,
    /// The speed a [`Slope::Time`] ramp time refers to (from 0 to this parameter's value).
    pub full_scale: Option<String>,
    /// A parameter whose value 0 switches the ramp off (the speed then jumps).
    pub enable: Option<String>,
    /// The bit that reverses the setpoint while set (Lafert speed polarity, 0x0043).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub polarity: Option<Polarity>,
    /// Documentation.
    pub doc: Option<String>,
    /// Citation.
    pub source: Option<Citation>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

/// A bit that multiplies the setpoint by -1 while set: the motor turns the other way (Lafert
/// SPEED POLARITY 0x0043, "bit value = 1: multiply the demand value by -1", Modbus manual line
/// 1347).
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Polarity {
    /// The integer parameter holding the bit.
    pub parameter: String,
    /// The bit, 0 = least significant.
    pub bit: u32,
}

/// One direction of a ramp, as the manual gives it. Speeds are in the setpoint's units.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
#[serde(untagged)]
pub enum Slope {
    /// `{ time }`: the time the speed takes from 0 to the ramp's `full_scale` (or back).
    Time {
        /// A time parameter (unit `ms` or `s`).
        time: String,
    },
    /// `{ rate }`: setpoint units per second, or per the time unit `per` names.
    Rate {
        /// The rate parameter.
        rate: String,
        /// The time unit the rate is given per (`ms` or `s`); `None` is per second. Kinco FD:
        /// one acceleration DEC is one speed DEC per millisecond (manual lines 1978, 1984).
        #[serde(skip_serializing_if = "Option::is_none")]
        per: Option<String>,
    },
    /// `{ speed, time }`: `speed` setpoint units in `time`.
    Delta {
        /// The delta speed parameter.
        speed: String,
        /// The delta time parameter (unit `ms` or `s`).
        time: String,
    },
}

impl Slope {
    /// The parameters the slope names.
    pub fn parameters(&self) -> Vec<&str> {
        match self {
            Slope::Time { time } => vec![time],
            Slope::Rate { rate, .. } => vec![rate],
            Slope::Delta { speed, time } => vec![speed, time],
        }
    }

    /// The time parameter, if the slope has one.
    pub fn time(&self) -> Option<&str> {
        match self {
            Slope::Time { time } | Slope::Delta { time, .. } => Some(time),
            Slope::Rate { .. } => None,
        }
    }
}

impl Ramp {
    /// Both slopes.
    pub fn slopes(&self) -> [&Slope; 2] {
        [&self.up, &self.down]
    }

    /// Whether a slope is a time from 0 to the full scale (and so needs `full_scale`).
    pub fn needs_full_scale(&self) -> bool {
        self.slopes()
            .iter()
            .any(|s| matches!(s, Slope::Time { .. }))
    }
}

/// How many `unit`s make a second, for the units manuals give ramp times in (`ms`, `s`).
pub fn per_second(unit: &str) -> Option<f64> {
    match unit {
        "ms" => Some(1000.0),
        "s" => Some(1.0),
        _ => None,
    }
}
