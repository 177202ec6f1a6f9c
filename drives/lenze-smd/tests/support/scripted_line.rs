//! A byte stream that plays a drive from a script of RTU answers and records every frame the
//! client sends: the bytes on the RS-485 wire, both ways, without a serial port.

// Each test binary uses a part of the double.
#![allow(dead_code)]

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use drivebus::modbus::client::{ByteStream, Client, ClientConfig};
use drivebus::modbus::retry::RetryPolicy;
use drivebus::modbus::rtu::RtuFraming;
use drivebus::BusError;

/// The scripted line: `answers[i]` is sent back after the i-th request (none: silence).
#[derive(Debug, Default)]
pub struct ScriptedLine {
    pub sent: Vec<Vec<u8>>,
    pub answers: VecDeque<Vec<u8>>,
    pending: Vec<u8>,
}

impl ScriptedLine {
    pub fn answering(answers: impl IntoIterator<Item = Vec<u8>>) -> Self {
        Self {
            answers: answers.into_iter().collect(),
            ..Self::default()
        }
    }
}

impl ByteStream for ScriptedLine {
    fn send(&mut self, bytes: &[u8]) -> Result<(), BusError> {
        self.sent.push(bytes.to_vec());
        self.pending = self.answers.pop_front().unwrap_or_default();
        Ok(())
    }

    fn receive(&mut self, buf: &mut [u8], _deadline: Instant) -> Result<usize, BusError> {
        let n = self.pending.len().min(buf.len());
        buf[..n].copy_from_slice(&self.pending[..n]);
        self.pending.drain(..n);
        Ok(n)
    }

    fn discard_input(&mut self) -> Result<(), BusError> {
        self.pending.clear();
        Ok(())
    }
}

/// An RTU client over `line` that never repeats a request.
pub fn client(line: ScriptedLine) -> Client<ScriptedLine, RtuFraming> {
    let config = ClientConfig {
        timeout: Duration::from_millis(20),
        retry: RetryPolicy::NONE,
        ..ClientConfig::default()
    };
    Client::new(line, RtuFraming, config)
}

/// CRC-16/MODBUS (poly 0xA001 reflected, init 0xFFFF), bit by bit, sharing nothing with the
/// table-driven implementation under test.
pub fn crc16_modbus(bytes: &[u8]) -> u16 {
    let mut crc = 0xFFFFu16;
    for &byte in bytes {
        crc ^= u16::from(byte);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xA001
            } else {
                crc >> 1
            };
        }
    }
    crc
}

/// The manual's frame bytes (up to its "CRCH CRCL" placeholder) with the CRC, low byte first
/// (ERRATA.md E4).
pub fn with_crc(bytes: &[u8]) -> Vec<u8> {
    let mut frame = bytes.to_vec();
    frame.extend_from_slice(&crc16_modbus(bytes).to_le_bytes());
    frame
}

/// The same bytes with the CRC in the order the manual prints it, "CRCH CRCL".
pub fn with_crc_as_printed(bytes: &[u8]) -> Vec<u8> {
    let mut frame = bytes.to_vec();
    frame.extend_from_slice(&crc16_modbus(bytes).to_be_bytes());
    frame
}
