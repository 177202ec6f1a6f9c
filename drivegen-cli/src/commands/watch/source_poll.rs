//! Samples by asking: every interval each drive is read, over Modbus with the planner's fewest
//! requests (`Session::read_many`), over CANopen and RS-232 an upload per parameter.

use std::time::{Duration, Instant};

use drivegen::ir::{Device, Parameter};

use super::interrupt::Interrupt;
use super::sample::{Sample, Source};
use crate::drives::Drives;
use crate::error::CliError;

/// Polls the drives.
pub struct Poll<'a, 'd> {
    drives: &'a mut Drives<'d>,
    device: &'d Device,
    parameters: &'a [&'d Parameter],
    interval: Duration,
    interrupt: Interrupt,
    start: Instant,
    last: Option<Instant>,
}

impl<'a, 'd> Poll<'a, 'd> {
    /// Polls `drives` for `parameters` every `interval` (the first at once).
    pub fn new(
        drives: &'a mut Drives<'d>,
        device: &'d Device,
        parameters: &'a [&'d Parameter],
        interval: Duration,
        interrupt: Interrupt,
    ) -> Self {
        Self {
            drives,
            device,
            parameters,
            interval,
            interrupt,
            start: Instant::now(),
            last: None,
        }
    }
}

impl Source for Poll<'_, '_> {
    fn next(&mut self) -> Result<Option<Sample>, CliError> {
        if let Some(last) = self.last {
            // The interval between the end of one poll and the start of the next, as before.
            if !self.interrupt.sleep_until(last + self.interval) {
                return Ok(None);
            }
        }
        let drives = self.drives.read_each(self.device, self.parameters);
        let time = self.start.elapsed().as_secs_f64();
        self.last = Some(Instant::now());
        Ok(Some(Sample { time, drives }))
    }
}
