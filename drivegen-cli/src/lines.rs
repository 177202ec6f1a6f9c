//! Lines to standard output, for the commands that print until stopped (`trace`, `watch`): a
//! reader that went away (a closed pipe) ends the output quietly. Each line reaches the reader
//! as it is written, except from [`Lines::buffered`] (a capture decoded as fast as it reads,
//! where a write per line cost more than the decoding: issue 33, docs/benchmarks.md).

use std::fmt::{self, Write as _};
use std::io::{BufWriter, Stdout, Write};

use crate::error::CliError;

/// Bytes buffered before a write to standard output.
const BUFFER: usize = 64 * 1024;

/// Standard output, line by line.
pub struct Lines {
    out: BufWriter<Stdout>,
    /// The line being formatted: one write of it costs less than one per piece.
    line: String,
    closed: bool,
    /// Each line is flushed as it is written.
    flush_each: bool,
}

impl Lines {
    /// Standard output, each line written as it comes.
    pub fn stdout() -> Self {
        Self {
            out: BufWriter::with_capacity(BUFFER, std::io::stdout()),
            line: String::new(),
            closed: false,
            flush_each: true,
        }
    }

    /// Standard output written when its buffer fills and at [`flush`](Self::flush).
    pub fn buffered() -> Self {
        Self {
            flush_each: false,
            ..Self::stdout()
        }
    }

    /// Whether the reader went away.
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// Writes `line` and a line break; nothing once the reader went away.
    pub fn write(&mut self, line: &str) -> Result<(), CliError> {
        self.line(format_args!("{line}"))
    }

    /// Writes the formatted `line` and a line break; nothing once the reader went away.
    pub fn line(&mut self, line: fmt::Arguments<'_>) -> Result<(), CliError> {
        if self.closed {
            return Ok(());
        }
        self.line.clear();
        // Formatting into a String cannot fail.
        let _ = self.line.write_fmt(line);
        self.line.push('\n');
        let written = self.out.write_all(self.line.as_bytes());
        let written = match written {
            Ok(()) if self.flush_each => self.out.flush(),
            other => other,
        };
        self.outcome(written)
    }

    /// Writes what is buffered.
    pub fn flush(&mut self) -> Result<(), CliError> {
        if self.closed {
            return Ok(());
        }
        let flushed = self.out.flush();
        self.outcome(flushed)
    }

    fn outcome(&mut self, result: std::io::Result<()>) -> Result<(), CliError> {
        match result {
            Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => {
                self.closed = true;
                Ok(())
            }
            other => other.map_err(|e| CliError::Io(format!("standard output: {e}"))),
        }
    }
}
