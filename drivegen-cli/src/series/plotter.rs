//! A run's plot as it goes: samples pushed by parameter name, the file drawn again now and then
//! while the run lasts (so an interrupted `watch` or live `trace` leaves the plot of what it saw)
//! and once more at the end.

use std::time::{Duration, Instant};

use drivebus::interpret::Shown;
use drivegen::ir::{Device, Parameter};

use super::plot_file::PlotFile;
use super::Recording;
use crate::error::CliError;
use crate::frames::Sample;

/// How often a running plot is drawn again at most: a plot of a long capture costs more to draw
/// than a frame costs to decode.
const REDRAW: Duration = Duration::from_millis(500);

/// A plot being recorded.
#[derive(Debug)]
pub struct Plotter<'d> {
    file: PlotFile,
    device: &'d Device,
    title: String,
    recording: Recording,
    drawn: Option<Instant>,
    started: Instant,
    /// The whole seconds of the first frame time: frame times are taken relative to it.
    epoch: Option<i64>,
    /// Drawn again as the run goes, not only at the end.
    redrawn: bool,
}

impl<'d> Plotter<'d> {
    /// A plot of `device` into `file`, titled with the device's name and `command`; `parameters`
    /// get their panels from the start, in that order (others as they are first seen).
    pub fn new(
        file: PlotFile,
        device: &'d Device,
        command: &str,
        parameters: &[&Parameter],
    ) -> Self {
        Self {
            file,
            device,
            title: format!("{}: drivegen {command}", device.device.name),
            recording: Recording::of(device, parameters),
            drawn: None,
            started: Instant::now(),
            epoch: None,
            redrawn: true,
        }
    }

    /// Whether the plot is drawn again as the run goes (the default): a live run wants it, a
    /// capture read as fast as it decodes only needs its drawing at the end.
    pub fn redrawn(mut self, redrawn: bool) -> Self {
        self.redrawn = redrawn;
        self
    }

    /// Adds a sample; `time` in seconds (any origin) or `None` for the time since the plot began.
    pub fn sample(&mut self, parameter: &str, time: Option<f64>, value: f64) {
        let time = time.unwrap_or_else(|| self.started.elapsed().as_secs_f64());
        self.recording.push(self.device, parameter, time, value);
    }

    /// Adds one poll's values of `parameters` at `time` (seconds since watching began) and
    /// draws the file now and then.
    pub fn poll(
        &mut self,
        parameters: &[&Parameter],
        values: &[Shown],
        time: f64,
    ) -> Result<(), CliError> {
        for (parameter, shown) in parameters.iter().zip(values) {
            if let Some(value) = super::number(shown) {
                self.sample(&parameter.name, Some(time), value);
            }
        }
        self.now_and_then()
    }

    /// Adds a decoded frame's numeric samples at the frame's time text (see [`super::seconds`])
    /// and draws the file now and then.
    pub fn frame(&mut self, time: &str, samples: &[Sample<'_>]) -> Result<(), CliError> {
        let time = super::seconds(time).map(|(whole, fraction)| {
            let epoch = *self.epoch.get_or_insert(whole);
            (whole - epoch) as f64 + fraction
        });
        for sample in samples {
            // Only the description's parameters have values as numbers.
            if let (Some(parameter), Some(value)) = (sample.name(), sample.value()) {
                self.sample(parameter, time, value);
            }
        }
        self.now_and_then()
    }

    /// Draws the file if it was not drawn in the last [`REDRAW`].
    pub fn now_and_then(&mut self) -> Result<(), CliError> {
        if !self.redrawn || self.drawn.is_some_and(|at| at.elapsed() < REDRAW) {
            return Ok(());
        }
        self.finish()
    }

    /// Draws the file.
    pub fn finish(&mut self) -> Result<(), CliError> {
        self.drawn = Some(Instant::now());
        self.file.write(&self.title, self.recording.series())
    }
}
