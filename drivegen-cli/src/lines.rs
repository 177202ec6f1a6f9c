//! Lines to standard output as they come, for the commands that print until stopped (`trace`,
//! `watch`): a reader that went away (a closed pipe) ends the output quietly.

use std::io::Write;

use crate::error::CliError;

/// Standard output, line by line.
pub struct Lines {
    out: std::io::Stdout,
    closed: bool,
}

impl Lines {
    /// Standard output.
    pub fn stdout() -> Self {
        Self {
            out: std::io::stdout(),
            closed: false,
        }
    }

    /// Whether the reader went away.
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// Writes `line` and a line break; nothing once the reader went away.
    pub fn write(&mut self, line: &str) -> Result<(), CliError> {
        if self.closed {
            return Ok(());
        }
        match writeln!(self.out.lock(), "{line}") {
            Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => {
                self.closed = true;
                Ok(())
            }
            other => other.map_err(|e| CliError::Io(format!("standard output: {e}"))),
        }
    }
}
