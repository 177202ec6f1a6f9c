//! `watch` as a table for people: one drive a line per sample, several drives a block of rows
//! per sample with a column per drive.

use super::sample::{Layout, Output, Sample};
use crate::drives;
use crate::error::CliError;
use crate::lines::Lines;

/// The table, printed as samples come.
pub struct LinesOutput {
    out: Lines,
    widths: Vec<usize>,
    name_width: usize,
}

impl LinesOutput {
    /// To standard output.
    pub fn new() -> Self {
        Self {
            out: Lines::stdout(),
            widths: Vec::new(),
            name_width: 0,
        }
    }

    /// A line of the several-drives table: time, parameter name, a cell per drive.
    fn block_line(&mut self, time: &str, name: &str, cells: &[String]) -> Result<(), CliError> {
        let name_width = self.name_width;
        let line = format!("{time:>8}  {name:<name_width$}  {}", self.cells(cells));
        self.out.write(line.trim_end())
    }

    /// `cells` padded to their columns' widths.
    fn cells(&self, cells: &[String]) -> String {
        let cells: Vec<String> = cells
            .iter()
            .zip(&self.widths)
            .map(|(cell, w)| format!("{cell:<w$}"))
            .collect();
        cells.join("  ")
    }
}

impl Output for LinesOutput {
    fn begin(&mut self, layout: &Layout<'_>) -> Result<(), CliError> {
        if layout.single() {
            let names: Vec<String> = layout.parameters.iter().map(|p| p.name.clone()).collect();
            self.widths = names.iter().map(|n| n.len().max(12)).collect();
            let header = format!("{:>8}  {}", "time", self.cells(&names));
            return self.out.write(&header);
        }
        self.name_width = layout
            .parameters
            .iter()
            .map(|p| p.name.len())
            .max()
            .unwrap_or(0);
        let names = layout.drive_names();
        self.widths = names.iter().map(|h| h.len().max(12)).collect();
        self.block_line("time", "parameter", &names)
    }

    fn sample(&mut self, layout: &Layout<'_>, sample: &Sample) -> Result<(), CliError> {
        if layout.single() {
            let cells: Vec<String> = match &sample.drives[0] {
                Ok(shown) => shown.iter().map(|s| s.text.clone()).collect(),
                Err(e) => vec![format!("error: {e}")],
            };
            let line = format!("{:>7.1}s  {}", sample.time, self.cells(&cells));
            return self.out.write(line.trim_end());
        }
        for (i, row) in drives::rows(layout.parameters, &sample.drives)
            .iter()
            .enumerate()
        {
            let time = if i == 0 {
                format!("{:.1}s", sample.time)
            } else {
                String::new()
            };
            self.block_line(&time, &row[0], &row[1..])?;
        }
        Ok(())
    }
}
