//! Parameter values over time, as `watch` and `trace` collect them, and the ways they are shown:
//! a plot file (`--plot FILE.svg` / `FILE.html`) and the terminal scope (`watch --tui`).
//!
//! The seam between getting samples and showing them is [`Recording`]: whoever reads the bus
//! pushes `(time, value)` samples by parameter name; the writers only ever see [`Series`].

pub mod axis;
pub mod decimate;
pub mod html;
pub mod plot_file;
pub mod plotter;
pub mod svg;
pub mod tui;

use std::collections::BTreeMap;

use drivebus::interpret::{Engineering, Raw, Shown};
use drivegen::ir::{Device, Parameter};

use crate::error::CliError;

/// One parameter's samples: its name, unit, `(seconds, value)` pairs in the order taken, and
/// for an enumeration the names of its raw values.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// The parameter's name (or `INDEX:SUB` for an object the description does not have).
    pub parameter: String,
    /// The unit the values are in, if the parameter has one.
    pub unit: Option<String>,
    /// `(seconds since the recording's first sample, value)`.
    pub samples: Vec<(f64, f64)>,
    /// An enumeration's names by raw value (empty for a number): a plot labels its axis with
    /// them instead of numbers.
    pub names: BTreeMap<i64, String>,
}

impl Series {
    /// An empty series of `parameter` of `device`, with its unit and enumeration names.
    pub fn of(device: &Device, parameter: &Parameter) -> Self {
        let names = parameter
            .enumeration
            .as_deref()
            .and_then(|name| device.enums.iter().find(|e| e.name == name))
            .map(|e| e.values.iter().map(|v| (v.value, v.name.clone())).collect())
            .unwrap_or_default();
        Self {
            parameter: parameter.name.clone(),
            unit: parameter.unit.clone(),
            samples: Vec::new(),
            names,
        }
    }

    /// An empty series of a name the description does not have: no unit, no names.
    pub fn unknown(name: &str) -> Self {
        Self {
            parameter: name.to_owned(),
            unit: None,
            samples: Vec::new(),
            names: BTreeMap::new(),
        }
    }

    /// The series' title: `name (unit)`, or the name alone.
    pub fn title(&self) -> String {
        match &self.unit {
            Some(unit) => format!("{} ({unit})", self.parameter),
            None => self.parameter.clone(),
        }
    }
}

/// The series of one run, in the order their parameters were first named or seen; times are
/// relative to the first sample.
#[derive(Debug, Clone, Default)]
pub struct Recording {
    series: Vec<Series>,
    origin: Option<f64>,
}

impl Recording {
    /// A recording of exactly these parameters (`watch`: the ones asked for, in that order).
    pub fn of(device: &Device, parameters: &[&Parameter]) -> Self {
        Self {
            series: parameters.iter().map(|p| Series::of(device, p)).collect(),
            origin: None,
        }
    }

    /// Adds a sample of `parameter` at `time` (seconds, any origin); a parameter not seen
    /// before gets its series, from `device` when it describes it.
    pub fn push(&mut self, device: &Device, parameter: &str, time: f64, value: f64) {
        let origin = *self.origin.get_or_insert(time);
        let at = match self.series.iter().position(|s| s.parameter == parameter) {
            Some(at) => at,
            None => {
                self.series.push(match device.parameter(parameter) {
                    Some(p) => Series::of(device, p),
                    None => Series::unknown(parameter),
                });
                self.series.len() - 1
            }
        };
        // A NaN or infinite reading (a float register can hold one) has no place on an axis,
        // nor has a time whose distance from the first overflows `f64`; its parameter keeps
        // its panel.
        let since_origin = time - origin;
        if value.is_finite() && since_origin.is_finite() {
            self.series[at].samples.push((since_origin, value));
        }
    }

    /// Drops the samples taken before `time` (same origin as [`Recording::push`]): a rolling
    /// window.
    pub fn keep_since(&mut self, time: f64) {
        let since = time - self.origin.unwrap_or(0.0);
        for series in &mut self.series {
            series.samples.retain(|(t, _)| *t >= since);
        }
    }

    /// The series, in order.
    pub fn series(&self) -> &[Series] {
        &self.series
    }
}

/// Refuses a live output (`flag`: `--plot`, `--tui`) that was `asked` for several drives: it
/// shows one, so a repeated `--unit` or `--node-id` is refused (before the bus opens).
pub fn one_drive(bus: &crate::connect::BusArgs, asked: bool, flag: &str) -> Result<(), CliError> {
    if asked && (bus.unit.len() > 1 || bus.node_id.len() > 1) {
        return Err(CliError::Usage(format!(
            "{flag} shows one drive: give --unit or --node-id once"
        )));
    }
    Ok(())
}

/// A decoded value as a number to plot: the engineering value, or an enumeration's or flags
/// word's raw value; `None` for text and bytes.
pub fn number(shown: &Shown) -> Option<f64> {
    match (&shown.value, &shown.raw) {
        (Engineering::Int(i), _) => Some(*i as f64),
        (Engineering::Float(f), _) => Some(*f),
        (_, Raw::Number(raw)) => Some(raw.as_f64()),
        _ => None,
    }
}

/// A capture's time text as `(whole seconds, fraction)`: `seconds.micros` (candump, kernel
/// timestamps) or `Nms` (an adapter's clock); `None` for anything else (no timestamp). Kept in
/// two parts because an epoch time in one `f64` has lost its microseconds.
pub fn seconds(time: &str) -> Option<(i64, f64)> {
    if let Some(ms) = time.strip_suffix("ms") {
        let ms = ms.parse::<i64>().ok()?;
        return Some((ms.div_euclid(1000), ms.rem_euclid(1000) as f64 / 1000.0));
    }
    let (whole, fraction) = time.split_once('.').unwrap_or((time, ""));
    let whole = whole.parse::<i64>().ok()?;
    let fraction = if fraction.is_empty() {
        0.0
    } else if fraction.bytes().all(|b| b.is_ascii_digit()) {
        format!("0.{fraction}").parse::<f64>().ok()?
    } else {
        return None;
    };
    Some((whole, fraction))
}

/// The Kinco description, loaded once for the tests of the series and their writers.
#[cfg(test)]
pub fn kinco() -> &'static Device {
    static DEVICE: std::sync::LazyLock<Device> = std::sync::LazyLock::new(|| {
        let path =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../descriptions/kinco-fd");
        drivegen::check(&path).device.unwrap()
    });
    &DEVICE
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn capture_times_keep_their_microseconds() {
        assert_eq!(seconds("1700000000.010000"), Some((1_700_000_000, 0.01)));
        assert_eq!(seconds("1234ms"), Some((1, 0.234)));
        assert_eq!(seconds(""), None);
        assert_eq!(seconds("12.-3"), None);
    }
}
