//! What a watch source gives and an output shows: samples in time, one typed value per
//! parameter per drive. The one seam between how samples are got (`source_*.rs`) and how they
//! are shown (`output_*.rs`).

use drivegen::ir::Parameter;

use crate::drives::Outcome;

/// One sample of every drive watched.
pub struct Sample {
    /// Seconds since the watch began.
    pub time: f64,
    /// Each drive's values, in the order of [`Layout::drives`], each in the order of
    /// [`Layout::parameters`]; or why the drive gave none this time.
    pub drives: Vec<Outcome>,
}

/// What every sample of one watch holds.
pub struct Layout<'a> {
    /// The parameters watched.
    pub parameters: &'a [&'a Parameter],
    /// Each drive: `("unit", 3)`, `("node", 5)`.
    pub drives: Vec<(&'static str, u8)>,
}

impl Layout<'_> {
    /// Each drive's name: `unit 3`, `node 5`.
    pub fn drive_names(&self) -> Vec<String> {
        self.drives
            .iter()
            .map(|(kind, id)| format!("{kind} {id}"))
            .collect()
    }

    /// Whether one drive is watched: the outputs keep their one-drive form.
    pub fn single(&self) -> bool {
        self.drives.len() == 1
    }
}

/// Where samples come from: a poll of the drives, or their PDOs.
pub trait Source {
    /// The next sample, taken no sooner than the interval after the previous one; `None` when
    /// the watch was interrupted (Ctrl-C) while waiting for it.
    fn next(&mut self) -> Result<Option<Sample>, crate::error::CliError>;
}

/// Where samples go, as they come.
pub trait Output {
    /// Before the first sample (a header, where the format has one).
    fn begin(&mut self, layout: &Layout<'_>) -> Result<(), crate::error::CliError>;
    /// One sample.
    fn sample(
        &mut self,
        layout: &Layout<'_>,
        sample: &Sample,
    ) -> Result<(), crate::error::CliError>;
    /// After the last sample (a file written whole, where the output draws one).
    fn end(&mut self) -> Result<(), crate::error::CliError> {
        Ok(())
    }
}
