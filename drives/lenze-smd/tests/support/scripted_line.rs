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
