//! `watch --csv`: one header, then a row per sample: the time in seconds and a column per
//! parameter per drive, each headed by its name and unit (`bus_dc_link [V]`; several drives:
//! `node 1 bus_dc_link [V]`). A value is its engineering number, or the name of an enum value;
//! a drive that gave no value this time leaves its cells empty.

use drivebus::interpret::Shown;
use drivegen::ir::Parameter;

use super::sample::{Layout, Output, Sample};
use crate::codec;
use crate::csv;
use crate::error::CliError;
use crate::lines::Lines;

/// CSV rows, printed as samples come.
pub struct CsvOutput {
    out: Lines,
}

impl CsvOutput {
    /// To standard output.
    pub fn new() -> Self {
        Self {
            out: Lines::stdout(),
        }
    }
}

impl Output for CsvOutput {
    fn begin(&mut self, layout: &Layout<'_>) -> Result<(), CliError> {
        let mut header = vec!["time [s]".to_owned()];
        for drive in layout.drive_names() {
            for parameter in layout.parameters {
                let name = column(parameter);
                header.push(match layout.single() {
                    true => name,
                    false => format!("{drive} {name}"),
                });
            }
        }
        self.out.write(&csv::record(&header))
    }

    fn sample(&mut self, layout: &Layout<'_>, sample: &Sample) -> Result<(), CliError> {
        let mut row = vec![format!("{:.6}", sample.time)];
        for outcome in &sample.drives {
            match outcome {
                Ok(shown) => row.extend(shown.iter().map(cell)),
                Err(_) => row.extend(layout.parameters.iter().map(|_| String::new())),
            }
        }
        self.out.write(&csv::record(&row))
    }
}

/// A parameter's column name: its name, and its unit in brackets where it has one.
fn column(parameter: &Parameter) -> String {
    match parameter.unit.as_deref() {
        Some(unit) if !unit.is_empty() => format!("{} [{unit}]", parameter.name),
        _ => parameter.name.clone(),
    }
}

/// A value as a cell: the engineering number, else its text.
fn cell(shown: &Shown) -> String {
    match codec::value_json(&shown.value) {
        serde_json::Value::Number(n) => n.to_string(),
        serde_json::Value::String(text) => text,
        _ => shown.text.clone(),
    }
}
