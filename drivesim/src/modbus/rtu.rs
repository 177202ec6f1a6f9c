//! Modbus RTU: a server on a serial line (or a pty), over any [`ByteStream`].
//!
//! Requests are delimited by their function code's length rule (FC 0x01-0x06: 8 bytes;
//! FC 0x0F / 0x10: 9 + byte count); other function codes end at the line's silence. Bytes that
//! cannot start a valid frame are dropped one at a time, so the server resynchronises after noise.

use std::time::{Duration, Instant};

use drivebus::modbus::client::ByteStream;
use drivebus::modbus::crc::check;
use drivebus::modbus::pdu::function;
use drivebus::modbus::rtu::{seal, MAX_ADU};
use drivebus::modbus::UnitId;
use drivebus::BusError;

use super::Units;
use crate::Simulator;

/// Silence after which buffered bytes are treated as a complete frame (far above t3.5 at any
/// baud rate, as a pty has no timing).
const SILENCE: Duration = Duration::from_millis(50);

/// What the head of the receive buffer holds.
#[derive(Debug, PartialEq, Eq)]
enum Head {
    /// A frame of this length with a good CRC.
    Frame(usize),
    /// Not enough bytes yet.
    Incomplete,
    /// The first byte cannot start a frame.
    Garbage,
}

/// The length of the request at the start of `buf`, from its function code.
fn request_len(buf: &[u8]) -> Option<usize> {
    match *buf.get(1)? {
        function::READ_COILS..=function::WRITE_SINGLE_REGISTER => Some(8),
        function::WRITE_MULTIPLE_COILS | function::WRITE_MULTIPLE_REGISTERS => {
            Some(9 + usize::from(*buf.get(6)?))
        }
        _ => None,
    }
}

fn head(buf: &[u8], silent: bool) -> Head {
    let len = match request_len(buf) {
        Some(len) => len,
        None if buf.len() < 2 => return Head::Incomplete,
        None if silent && (4..=MAX_ADU).contains(&buf.len()) => buf.len(),
        // No frame is longer than an ADU: a peer that never falls silent cannot make the buffer
        // grow past one.
        None if silent || buf.len() >= MAX_ADU => return Head::Garbage,
        None => return Head::Incomplete,
    };
    match buf.get(..len) {
        Some(frame) if check(frame) => Head::Frame(len),
        Some(_) => Head::Garbage,
        None if silent => Head::Garbage,
        None => Head::Incomplete,
    }
}

/// Serves `unit` on `stream` until the stream fails; broadcasts (unit 0) are executed without an
/// answer when the description accepts them (`[modbus] broadcast`), else ignored.
pub fn serve<S: ByteStream>(sim: &Simulator, stream: &mut S, unit: UnitId) -> Result<(), BusError> {
    serve_units(&Units::one(sim.clone(), unit), stream)
}

/// Serves every drive of `units` on one line until the stream fails, as drives sharing an RS-485
/// bus: each answers for its own unit id, other ids get no answer, broadcasts (unit 0) are
/// executed without an answer by every drive that accepts them.
pub fn serve_units<S: ByteStream>(units: &Units, stream: &mut S) -> Result<(), BusError> {
    let mut buf: Vec<u8> = Vec::with_capacity(2 * MAX_ADU);
    let mut chunk = [0u8; MAX_ADU];
    let mut response = [0u8; MAX_ADU];
    loop {
        let n = stream.receive(&mut chunk, Instant::now() + SILENCE)?;
        buf.extend_from_slice(&chunk[..n]);
        let silent = n == 0;
        loop {
            match head(&buf, silent) {
                Head::Incomplete => break,
                Head::Garbage => {
                    buf.remove(0);
                }
                Head::Frame(len) => {
                    let frame: Vec<u8> = buf.drain(..len).collect();
                    let to = frame[0];
                    response[0] = to;
                    let pdu = &frame[1..len - 2];
                    let Some(pdu_len) = units.handle(to, pdu, &mut response[1..]) else {
                        continue;
                    };
                    if pdu_len > 0 {
                        let total = seal(&mut response, 1 + pdu_len)?;
                        stream.send(&response[..total])?;
                    }
                }
            }
            if buf.is_empty() {
                break;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sealed(bytes: &[u8]) -> Vec<u8> {
        let mut out = bytes.to_vec();
        out.extend([0, 0]);
        let len = bytes.len();
        seal(&mut out, len).unwrap();
        out
    }

    #[test]
    fn frames_are_found_by_their_function_code() {
        let frame = sealed(&[1, 0x04, 0x00, 0x64, 0x00, 0x01]);
        assert_eq!(head(&frame, false), Head::Frame(8));
        assert_eq!(head(&frame[..5], false), Head::Incomplete);
        let mut noisy = vec![0x55];
        noisy.extend(&frame);
        assert_eq!(head(&noisy, false), Head::Garbage);
    }

    #[test]
    fn noise_without_silence_is_dropped_once_it_is_longer_than_an_adu() {
        let mut noise = vec![1, 0x2B];
        noise.resize(MAX_ADU - 1, 0x55);
        assert_eq!(head(&noise, false), Head::Incomplete);
        noise.push(0x55);
        assert_eq!(head(&noise, false), Head::Garbage);
        noise.push(0x55);
        assert_eq!(head(&noise, true), Head::Garbage);
    }

    #[test]
    fn unknown_functions_end_at_silence() {
        let frame = sealed(&[1, 0x2B, 0x0E, 0x01]);
        assert_eq!(head(&frame, false), Head::Incomplete);
        assert_eq!(head(&frame, true), Head::Frame(frame.len()));
    }
}
