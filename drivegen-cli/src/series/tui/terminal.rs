//! The terminal while the scope runs: raw mode and the alternate screen, given back when the
//! guard is dropped: on `q`, on an error, and on a panic unwinding through the scope alike.

use std::io::Stdout;

use ratatui::backend::CrosstermBackend;
use ratatui::crossterm::execute;
use ratatui::crossterm::terminal::{
    disable_raw_mode, enable_raw_mode, EnterAlternateScreen, LeaveAlternateScreen,
};
use ratatui::Terminal;

use crate::error::CliError;

/// A terminal in raw mode on the alternate screen.
pub struct Screen {
    /// What the scope draws on.
    pub terminal: Terminal<CrosstermBackend<Stdout>>,
}

impl Screen {
    /// Takes the terminal over; fails (and leaves it as it was) when standard output is not one.
    pub fn enter() -> Result<Self, CliError> {
        let failed = |e: std::io::Error| CliError::Io(format!("--tui needs a terminal: {e}"));
        enable_raw_mode().map_err(failed)?;
        let entered = execute!(std::io::stdout(), EnterAlternateScreen)
            .and_then(|()| Terminal::new(CrosstermBackend::new(std::io::stdout())));
        match entered {
            Ok(terminal) => Ok(Self { terminal }),
            Err(e) => {
                restore();
                Err(failed(e))
            }
        }
    }
}

impl Drop for Screen {
    fn drop(&mut self) {
        let _ = self.terminal.show_cursor();
        restore();
    }
}

/// Leaves the alternate screen and raw mode. Errors are ignored: there is nothing left to give
/// them to, and the other half must still be tried.
fn restore() {
    let _ = execute!(std::io::stdout(), LeaveAlternateScreen);
    let _ = disable_raw_mode();
}
