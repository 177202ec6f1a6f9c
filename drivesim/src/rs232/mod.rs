//! The Kinco RS-232 side of the simulator: a sans-I/O drive answering telegrams from the
//! parameters' `rs232` addresses, and a blocking loop over a serial line or pty.

pub mod in_process;
pub mod server;

pub use in_process::InProcessLine;
pub use server::{serve, Rs232Server};
