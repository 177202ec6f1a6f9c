//! Modbus RTU through the proxy: between two pty pairs (client ⇄ proxy ⇄ simulator), frames
//! delimited by their function code's length rule, as the pty carries no timing.

use std::fs::{File, OpenOptions};
use std::io::{self, BufRead, BufReader};
use std::path::Path;

use super::{pump, Direction, Protocol};
use crate::fault::{FaultCounts, FaultPlan, Injector};
use crate::rng::Rng;

/// RTU framing of the requests and answers the soak exchanges (function codes 3, 6 and 16, and
/// exception answers).
#[derive(Debug)]
pub struct Rtu;

/// The length of a frame whose first `head` bytes are known, or how many bytes are needed first.
enum Length {
    Known(usize),
    Need(usize),
}

fn frame_length(head: &[u8], direction: Direction) -> io::Result<Length> {
    let Some(&function) = head.get(1) else {
        return Ok(Length::Need(2));
    };
    let with_count = |at: usize, extra: usize| match head.get(at) {
        Some(&count) => Length::Known(extra + usize::from(count)),
        None => Length::Need(at + 1),
    };
    Ok(match (direction, function) {
        (Direction::Request, 0x03 | 0x04 | 0x06) => Length::Known(8),
        (Direction::Request, 0x10) => with_count(6, 9),
        (Direction::Response, f) if f & 0x80 != 0 => Length::Known(5),
        (Direction::Response, 0x03 | 0x04) => with_count(2, 5),
        (Direction::Response, 0x06 | 0x10) => Length::Known(8),
        _ => return Err(io::Error::new(io::ErrorKind::InvalidData, "function code")),
    })
}

impl Protocol for Rtu {
    const TRUNCATE_ENDS_STREAM: bool = false;

    fn read_frame(
        &self,
        from: &mut dyn BufRead,
        direction: Direction,
    ) -> io::Result<Option<Vec<u8>>> {
        let mut frame = Vec::with_capacity(16);
        loop {
            let wanted = match frame_length(&frame, direction)? {
                Length::Known(len) if frame.len() >= len => return Ok(Some(frame)),
                Length::Known(len) | Length::Need(len) => len,
            };
            let start = frame.len();
            frame.resize(wanted, 0);
            if let Err(e) = from.read_exact(&mut frame[start..]) {
                return if e.kind() == io::ErrorKind::UnexpectedEof {
                    Ok(None)
                } else {
                    Err(e)
                };
            }
        }
    }

    /// The CRC-16 covers every byte and detects every single-byte error: any byte may change.
    fn corrupt(&self, frame: &mut Vec<u8>, rng: &mut Rng) {
        let at = rng.below(frame.len() as u64) as usize;
        frame[at] ^= 1 + rng.below(255) as u8;
    }
}

fn open(path: &Path) -> io::Result<File> {
    OpenOptions::new().read(true).write(true).open(path)
}

/// Relays between the pty end `client_side` (the client's pair) and `server_side` (the
/// simulator's pair) through the faults of `plan`.
pub fn start(
    client_side: &Path,
    server_side: &Path,
    plan: FaultPlan,
    seed: u64,
    counts: &'static FaultCounts,
) -> io::Result<()> {
    let (client, server) = (open(client_side)?, open(server_side)?);
    let directions = [
        (Direction::Request, client.try_clone()?, server.try_clone()?),
        (Direction::Response, server, client),
    ];
    for (direction, from, mut to) in directions {
        let rng = Rng::stream(seed, &format!("rtu {}", direction.name()));
        std::thread::spawn(move || {
            let mut injector = Injector::new(rng, plan, direction, counts);
            pump(
                &Rtu,
                direction,
                &mut BufReader::new(from),
                &mut to,
                &mut injector,
            )
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_are_split_by_their_function_code() {
        let read = [1, 0x03, 0x01, 0x00, 0x00, 0x02, 0xC5, 0xF7];
        let write = [
            1, 0x10, 0x01, 0x00, 0x00, 0x01, 0x02, 0xAB, 0xCD, 0x11, 0x22,
        ];
        let stream: Vec<u8> = read.iter().chain(&write).copied().collect();
        let mut from = &stream[..];
        assert_eq!(
            Rtu.read_frame(&mut from, Direction::Request)
                .unwrap()
                .unwrap(),
            read
        );
        assert_eq!(
            Rtu.read_frame(&mut from, Direction::Request)
                .unwrap()
                .unwrap(),
            write
        );
        assert_eq!(Rtu.read_frame(&mut from, Direction::Request).unwrap(), None);
        let answers = [
            1, 0x83, 0x02, 0xC0, 0xF1, 1, 0x03, 0x02, 0x12, 0x34, 0xB5, 0x33,
        ];
        let mut from = &answers[..];
        assert_eq!(
            Rtu.read_frame(&mut from, Direction::Response)
                .unwrap()
                .unwrap()
                .len(),
            5
        );
        assert_eq!(
            Rtu.read_frame(&mut from, Direction::Response)
                .unwrap()
                .unwrap()
                .len(),
            7
        );
    }
}
