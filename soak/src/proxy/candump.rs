//! SDO over candump text through the proxy: one line per CAN frame on a pipe-like stream
//! between the client's [`CandumpBus`](drivebus::canopen::can::candump::CandumpBus) and the
//! simulated node's.

use std::io::{self, BufRead, BufReader, Read};
use std::os::unix::net::UnixStream;

use super::{pump, Direction, Protocol};
use crate::fault::{FaultCounts, FaultPlan, Injector};
use crate::rng::Rng;

/// Longest line the proxy relays; candump frame lines are at most 20 bytes.
const MAX_LINE: u64 = 64;

/// candump compact lines (`605#2B00210034120000`).
#[derive(Debug)]
pub struct CandumpLines;

impl Protocol for CandumpLines {
    const TRUNCATE_ENDS_STREAM: bool = false;

    fn read_frame(&self, from: &mut dyn BufRead, _: Direction) -> io::Result<Option<Vec<u8>>> {
        let mut line = Vec::with_capacity(24);
        match <&mut dyn BufRead as Read>::take(from, MAX_LINE).read_until(b'\n', &mut line)? {
            0 => Ok(None),
            _ => Ok(Some(line)),
        }
    }

    /// A CAN controller drops a frame whose CRC fails: what can reach a reader is a damaged line
    /// of text, which no parser may take for a frame.
    fn corrupt(&self, frame: &mut Vec<u8>, rng: &mut Rng) {
        let text = frame.len().saturating_sub(1).max(1);
        let at = rng.below(text as u64) as usize;
        frame[at] = b'Z';
    }

    /// The line ends early: a frame with fewer data bytes, or an odd number of hex digits.
    fn truncate(&self, frame: &[u8], rng: &mut Rng) -> Vec<u8> {
        let text = frame.len().saturating_sub(1).max(2);
        let keep = 1 + rng.below(text as u64 - 1) as usize;
        let mut cut = frame[..keep].to_vec();
        cut.push(b'\n');
        cut
    }
}

/// Relays between the client's stream and the node's through the faults of `plan`.
pub fn start(
    client: UnixStream,
    node: UnixStream,
    plan: FaultPlan,
    seed: u64,
    counts: &'static FaultCounts,
) -> io::Result<()> {
    let directions = [
        (Direction::Request, client.try_clone()?, node.try_clone()?),
        (Direction::Response, node, client),
    ];
    for (direction, from, mut to) in directions {
        let rng = Rng::stream(seed, &format!("sdo {}", direction.name()));
        std::thread::spawn(move || {
            let mut injector = Injector::new(rng, plan, direction, counts);
            pump(
                &CandumpLines,
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
    use drivebus::canopen::can::candump::parse_line;

    use super::*;

    const LINE: &[u8] = b"585#4B00210034120000\n";

    #[test]
    fn a_corrupted_line_is_never_a_frame() {
        let mut rng = Rng::new(7);
        for _ in 0..200 {
            let mut line = LINE.to_vec();
            CandumpLines.corrupt(&mut line, &mut rng);
            assert!(
                parse_line(&line).is_err(),
                "{}",
                String::from_utf8_lossy(&line)
            );
        }
    }

    #[test]
    fn a_truncated_line_is_malformed_or_carries_fewer_bytes() {
        let whole = parse_line(LINE).unwrap().unwrap().frame;
        let mut rng = Rng::new(7);
        for _ in 0..200 {
            let line = CandumpLines.truncate(LINE, &mut rng);
            assert!(line.len() < LINE.len() && line.ends_with(b"\n"));
            if let Ok(Some(record)) = parse_line(&line) {
                assert!(record.frame.dlc() < whole.dlc());
            }
        }
    }
}
