//! `drivegen watch --tui`: a live terminal scope. A chart per parameter over a rolling window,
//! the latest value with its unit in each chart's title; `space` pauses and resumes, `q` (or
//! `Esc`, or Ctrl-C, which raw mode delivers as a key) quits.
//!
//! Quitting returns from [`run`] like a `watch --count` that is done: the terminal is given back
//! by a guard's `Drop` first, then whatever the caller holds (a drive's PDO configuration to
//! restore, say) is dropped on the same way out.

mod draw;
mod terminal;

use std::time::{Duration, Instant};

use drivebus::interpret::Shown;
use drivegen::ir::{Device, Parameter};
use ratatui::crossterm::event::{self, Event, KeyCode, KeyEventKind, KeyModifiers};

use super::plotter::Plotter;
use super::{Recording, Series};
use crate::error::CliError;

/// How much time the charts show.
pub const WINDOW_S: f64 = 30.0;

/// How long the scope waits for a key when nothing is due: the screen follows a resize or a
/// paused scope's keys within this.
const IDLE: Duration = Duration::from_millis(250);

/// What the scope shows: the series, the latest values as text, and whether it is paused.
pub struct Scope {
    /// The title line's start: the device's name.
    pub title: String,
    /// The time between polls.
    pub interval: Duration,
    /// Each parameter's samples in the window.
    pub recording: Recording,
    /// Each parameter's latest value as text, with its unit (empty before the first poll).
    pub latest: Vec<String>,
    /// The last poll's error, shown until a poll succeeds.
    pub error: Option<String>,
    /// Polls taken.
    pub polls: u64,
    /// Seconds since the scope started, at the last poll.
    pub time: f64,
    /// No polls while paused: the screen holds still.
    pub paused: bool,
}

/// What a key asks for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Key {
    Quit,
    Pause,
    Other,
}

/// Runs the scope until `q`: `poll` reads the parameters (in order) every `interval`; every
/// poll's values also go to `plot`, drawn a last time on the way out.
pub fn run(
    device: &Device,
    parameters: &[&Parameter],
    interval: Duration,
    mut plot: Option<Plotter<'_>>,
    mut poll: impl FnMut() -> Result<Vec<Shown>, CliError>,
) -> Result<(), CliError> {
    let scoped = scope(device, parameters, interval, &mut plot, &mut poll);
    match plot {
        Some(mut plot) => scoped.and(plot.finish()),
        None => scoped,
    }
}

/// The scope's loop; the terminal is given back when it returns, whichever way.
fn scope(
    device: &Device,
    parameters: &[&Parameter],
    interval: Duration,
    plot: &mut Option<Plotter<'_>>,
    poll: &mut impl FnMut() -> Result<Vec<Shown>, CliError>,
) -> Result<(), CliError> {
    let mut scope = Scope {
        title: device.device.name.clone(),
        interval,
        recording: Recording::of(device, parameters),
        latest: vec![String::new(); parameters.len()],
        error: None,
        polls: 0,
        time: 0.0,
        paused: false,
    };
    let mut screen = terminal::Screen::enter()?;
    let start = Instant::now();
    let mut due = start;
    loop {
        if !scope.paused && Instant::now() >= due {
            scope.time = start.elapsed().as_secs_f64();
            let values = poll();
            if let (Some(plot), Ok(values)) = (plot.as_mut(), &values) {
                plot.poll(parameters, values, scope.time)?;
            }
            scope.take(device, parameters, values);
            due = Instant::now() + interval;
            if scope.polls == 1 {
                // A simulator the bus spawned may have written to the terminal while starting:
                // clear once so the diffing renderer does not keep its text in cells it thinks blank.
                let _ = screen.terminal.clear();
            }
        }
        screen
            .terminal
            .draw(|frame| draw::scope(frame, &scope))
            .map_err(|e| CliError::Io(format!("terminal: {e}")))?;
        let wait = if scope.paused {
            IDLE
        } else {
            due.saturating_duration_since(Instant::now()).min(IDLE)
        };
        match next_key(wait)? {
            Key::Quit => return Ok(()),
            Key::Pause => scope.paused = !scope.paused,
            Key::Other => {}
        }
    }
}

impl Scope {
    /// Records one poll: its numbers into the window, its texts as the latest values; a failed
    /// poll is shown and the next one tried (a scope outlives a timeout).
    fn take(
        &mut self,
        device: &Device,
        parameters: &[&Parameter],
        values: Result<Vec<Shown>, CliError>,
    ) {
        self.polls += 1;
        let values = match values {
            Ok(values) => values,
            Err(e) => {
                self.error = Some(e.to_string());
                return;
            }
        };
        self.error = None;
        for ((parameter, shown), latest) in parameters.iter().zip(&values).zip(&mut self.latest) {
            latest.clone_from(&shown.text);
            if let Some(value) = super::number(shown) {
                self.recording
                    .push(device, &parameter.name, self.time, value);
            }
        }
        self.recording.keep_since(self.time - WINDOW_S);
    }

    /// The series, in the parameters' order.
    pub fn series(&self) -> &[Series] {
        self.recording.series()
    }
}

/// The next key within `wait`, if any.
fn next_key(wait: Duration) -> Result<Key, CliError> {
    let failed = |e: std::io::Error| CliError::Io(format!("terminal: {e}"));
    if !event::poll(wait).map_err(failed)? {
        return Ok(Key::Other);
    }
    let Event::Key(key) = event::read().map_err(failed)? else {
        return Ok(Key::Other);
    };
    if key.kind != KeyEventKind::Press {
        return Ok(Key::Other);
    }
    Ok(match key.code {
        KeyCode::Char('q') | KeyCode::Esc => Key::Quit,
        KeyCode::Char('c') if key.modifiers.contains(KeyModifiers::CONTROL) => Key::Quit,
        KeyCode::Char(' ') => Key::Pause,
        _ => Key::Other,
    })
}
