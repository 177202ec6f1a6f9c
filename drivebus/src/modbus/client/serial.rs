//! Modbus RTU over a serial port (`serialport` crate).

use std::time::Duration;

use super::{Client, ClientConfig, SerialStream};
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

impl SerialStream {
    /// Opens `path` with the line settings of `config`.
    pub fn open(path: &str, config: &SerialConfig) -> Result<Self, BusError> {
        Self::open_8_bits(
            path,
            config.baud,
            match config.parity {
                Parity::None => serialport::Parity::None,
                Parity::Even => serialport::Parity::Even,
                Parity::Odd => serialport::Parity::Odd,
            },
            match config.stop_bits {
                StopBits::One => serialport::StopBits::One,
                StopBits::Two => serialport::StopBits::Two,
            },
            config.timeout,
        )
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
