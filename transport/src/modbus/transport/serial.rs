//! Modbus RTU over a serial port (`serialport` crate).

use std::boxed::Box;
use std::io::{ErrorKind, Read, Write};
use std::time::{Duration, Instant};

use serialport::{ClearBuffer, SerialPort};

use super::{io_error, ByteStream, Client, ClientConfig};
use crate::error::BusError;
use crate::modbus::retry::RetryPolicy;
use crate::modbus::rtu::{Parity, RtuFraming, StopBits, Timing};

/// Line settings and client behaviour for RTU over a serial port.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SerialConfig {
    /// Baud rate.
    pub baud: u32,
    /// Parity (8 data bits are implied, as RTU requires).
    pub parity: Parity,
    /// Stop bits.
    pub stop_bits: StopBits,
    /// How long to wait for each answer.
    pub timeout: Duration,
    /// Extra pause the device needs between its answer and the next request, on top of t3.5.
    pub turnaround: Duration,
    /// Which failed requests are repeated.
    pub retry: RetryPolicy,
}

impl SerialConfig {
    /// `baud` with even parity and one stop bit (the Modbus default), a 1 s timeout, no extra
    /// turnaround delay, reads retried twice.
    pub fn new(baud: u32) -> Self {
        Self {
            baud,
            parity: Parity::Even,
            stop_bits: StopBits::One,
            timeout: Duration::from_secs(1),
            turnaround: Duration::ZERO,
            retry: RetryPolicy::reads(2),
        }
    }

    /// The silent intervals of this line.
    pub fn timing(&self) -> Timing {
        Timing::new(self.baud, self.parity, self.stop_bits)
    }

    /// The client settings: the idle gap before a request is t3.5 or the turnaround, whichever
    /// is longer.
    pub fn client_config(&self) -> ClientConfig {
        ClientConfig {
            timeout: self.timeout,
            retry: self.retry,
            idle_gap: self.timing().t3_5.max(self.turnaround),
            max_in_flight: 1,
        }
    }
}

fn serial_error(error: serialport::Error) -> BusError {
    BusError::Io(match error.kind {
        serialport::ErrorKind::Io(kind) => kind,
        serialport::ErrorKind::NoDevice => ErrorKind::NotFound,
        serialport::ErrorKind::InvalidInput => ErrorKind::InvalidInput,
        serialport::ErrorKind::Unknown => ErrorKind::Other,
    })
}

/// A serial port as a [`ByteStream`].
pub struct SerialStream {
    port: Box<dyn SerialPort>,
}

impl core::fmt::Debug for SerialStream {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("SerialStream")
            .field("port", &self.port.name())
            .finish()
    }
}

impl SerialStream {
    /// Opens `path` with the line settings of `config`.
    pub fn open(path: &str, config: &SerialConfig) -> Result<Self, BusError> {
        let port = serialport::new(path, config.baud)
            .data_bits(serialport::DataBits::Eight)
            .parity(match config.parity {
                Parity::None => serialport::Parity::None,
                Parity::Even => serialport::Parity::Even,
                Parity::Odd => serialport::Parity::Odd,
            })
            .stop_bits(match config.stop_bits {
                StopBits::One => serialport::StopBits::One,
                StopBits::Two => serialport::StopBits::Two,
            })
            .flow_control(serialport::FlowControl::None)
            .timeout(config.timeout)
            .open()
            .map_err(serial_error)?;
        Ok(Self { port })
    }

    /// Wraps a port opened elsewhere.
    pub fn from_port(port: Box<dyn SerialPort>) -> Self {
        Self { port }
    }
}

/// Shortest read timeout handed to the port, so a nearly expired deadline still polls once.
const MIN_POLL: Duration = Duration::from_millis(1);

impl ByteStream for SerialStream {
    fn send(&mut self, bytes: &[u8]) -> Result<(), BusError> {
        self.port.write_all(bytes).map_err(io_error)?;
        self.port.flush().map_err(io_error)
    }

    fn receive(&mut self, buf: &mut [u8], deadline: Instant) -> Result<usize, BusError> {
        loop {
            let Some(left) = deadline.checked_duration_since(Instant::now()) else {
                return Ok(0);
            };
            self.port
                .set_timeout(left.max(MIN_POLL))
                .map_err(serial_error)?;
            match self.port.read(buf) {
                Ok(0) => std::thread::sleep(MIN_POLL),
                Ok(n) => return Ok(n),
                Err(e) if matches!(e.kind(), ErrorKind::TimedOut | ErrorKind::WouldBlock) => {}
                Err(e) if e.kind() == ErrorKind::Interrupted => {}
                Err(e) => return Err(io_error(e)),
            }
        }
    }

    fn discard_input(&mut self) -> Result<(), BusError> {
        self.port.clear(ClearBuffer::Input).map_err(serial_error)
    }
}

/// Modbus RTU over a serial port.
pub type SerialRtuClient = Client<SerialStream, RtuFraming>;

impl SerialRtuClient {
    /// Opens the serial port at `path` (`/dev/ttyUSB0`, `COM3`) as an RTU client.
    pub fn open(path: &str, config: &SerialConfig) -> Result<Self, BusError> {
        let stream = SerialStream::open(path, config)?;
        Ok(Client::new(stream, RtuFraming, config.client_config()))
    }
}
