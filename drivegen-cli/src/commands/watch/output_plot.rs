//! `--plot FILE`: the samples also drawn into an SVG or HTML file (`crate::series`), beside the
//! output that prints them. One drive only (checked before the bus opens).

use super::sample::{Layout, Output, Sample};
use crate::error::CliError;
use crate::series::plotter::Plotter;

/// Another output, and the plot.
pub struct PlotOutput<'d> {
    /// The output that prints.
    pub printed: Box<dyn Output + 'd>,
    /// The plot drawn.
    pub plotter: Plotter<'d>,
}

impl Output for PlotOutput<'_> {
    fn begin(&mut self, layout: &Layout<'_>) -> Result<(), CliError> {
        self.printed.begin(layout)
    }

    fn sample(&mut self, layout: &Layout<'_>, sample: &Sample) -> Result<(), CliError> {
        self.printed.sample(layout, sample)?;
        match sample.drives.first() {
            Some(Ok(values)) => self.plotter.poll(layout.parameters, values, sample.time),
            _ => Ok(()),
        }
    }

    fn end(&mut self) -> Result<(), CliError> {
        self.printed.end()?;
        self.plotter.finish()
    }
}
