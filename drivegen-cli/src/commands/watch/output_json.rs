//! `watch --json`: one JSON object per sample, `{"time": 0.5, "values": {...}}` for one drive,
//! `{"time": 0.5, "drives": [{"node": 1, "values": {...}}, ...]}` for several.

use drivebus::interpret::Shown;
use drivegen::ir::Parameter;

use super::sample::{Layout, Output, Sample};
use crate::commands::read;
use crate::drives::Outcome;
use crate::error::CliError;
use crate::lines::Lines;

/// JSON lines, printed as samples come.
pub struct JsonOutput {
    out: Lines,
}

impl JsonOutput {
    /// To standard output.
    pub fn new() -> Self {
        Self {
            out: Lines::stdout(),
        }
    }
}

impl Output for JsonOutput {
    fn begin(&mut self, _: &Layout<'_>) -> Result<(), CliError> {
        Ok(())
    }

    fn sample(&mut self, layout: &Layout<'_>, sample: &Sample) -> Result<(), CliError> {
        let line = match (layout.single(), &sample.drives[..]) {
            (true, [Ok(shown)]) => serde_json::json!({
                "time": sample.time,
                "values": by_name(layout.parameters, shown),
            }),
            _ => serde_json::json!({
                "time": sample.time,
                "drives": drives_json(layout, &sample.drives),
            }),
        };
        self.out.write(&line.to_string())
    }
}

/// Each drive's outcome: `{"unit": 3, "values": ...}` or `{"unit": 5, "error": ...}`.
fn drives_json(layout: &Layout<'_>, outcomes: &[Outcome]) -> serde_json::Value {
    layout
        .drives
        .iter()
        .zip(outcomes)
        .map(|(&(kind, id), outcome)| {
            let mut object = serde_json::Map::new();
            object.insert(kind.into(), id.into());
            match outcome {
                Ok(shown) => object.insert("values".into(), by_name(layout.parameters, shown)),
                Err(e) => object.insert("error".into(), e.to_string().into()),
            };
            serde_json::Value::Object(object)
        })
        .collect()
}

/// One drive's values of one sample, by parameter name.
fn by_name(parameters: &[&Parameter], shown: &[Shown]) -> serde_json::Value {
    let fields: serde_json::Map<String, serde_json::Value> = parameters
        .iter()
        .zip(shown)
        .map(|(p, s)| (p.name.clone(), read::to_json(p, s)))
        .collect();
    fields.into()
}
