//! The fault-injecting proxy: two pumps per connection, one per direction, each reading whole
//! frames of its protocol and passing them on — or corrupting, truncating, duplicating, delaying,
//! dropping or reordering them as its [`Injector`] decides.

pub mod candump;
pub mod mbap;
pub mod rtu;

use std::io::{self, BufRead, Write};

use crate::fault::{Fault, Injector};
use crate::rng::Rng;

/// Which way a frame travels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// Client to server.
    Request,
    /// Server to client.
    Response,
}

impl Direction {
    /// The name of its fault stream.
    pub fn name(self) -> &'static str {
        match self {
            Direction::Request => "request",
            Direction::Response => "response",
        }
    }
}

/// How a protocol's frames are delimited and damaged.
pub trait Protocol: Sync {
    /// Whether a truncated frame ends the connection (a reliable byte stream cannot lose its
    /// tail without the connection ending).
    const TRUNCATE_ENDS_STREAM: bool;

    /// The next whole frame travelling in `direction`; `None` at the end of the stream.
    fn read_frame(
        &self,
        from: &mut dyn BufRead,
        direction: Direction,
    ) -> io::Result<Option<Vec<u8>>>;

    /// Changes the frame the way the line can: only where the protocol detects the damage.
    fn corrupt(&self, frame: &mut Vec<u8>, rng: &mut Rng);

    /// A proper prefix of the frame.
    fn truncate(&self, frame: &[u8], rng: &mut Rng) -> Vec<u8> {
        let keep = 1 + rng.below(frame.len().saturating_sub(1).max(1) as u64) as usize;
        frame[..keep.min(frame.len())].to_vec()
    }
}

/// Why a pump stopped.
#[derive(Debug, PartialEq, Eq)]
pub enum PumpEnd {
    /// The source ended or a side failed.
    Closed,
    /// A frame was cut short on a stream that cannot go on after that.
    Cut,
}

/// Moves frames from `from` to `to` until either side ends, injecting faults.
pub fn pump<P: Protocol>(
    protocol: &P,
    direction: Direction,
    from: &mut dyn BufRead,
    to: &mut dyn Write,
    injector: &mut Injector<'_>,
) -> PumpEnd {
    let mut held: Option<Vec<u8>> = None;
    loop {
        let mut frame = match protocol.read_frame(from, direction) {
            Ok(Some(frame)) => frame,
            Ok(None) | Err(_) => return PumpEnd::Closed,
        };
        let sent = match injector.next_fault() {
            None => send(to, &frame),
            Some(Fault::Corrupt) => {
                protocol.corrupt(&mut frame, &mut injector.rng);
                send(to, &frame)
            }
            Some(Fault::Truncate) => {
                let prefix = protocol.truncate(&frame, &mut injector.rng);
                let sent = send(to, &prefix);
                if P::TRUNCATE_ENDS_STREAM {
                    return PumpEnd::Cut;
                }
                sent
            }
            // Back to back, in one write: as a repeater's echo arrives.
            Some(Fault::Duplicate) => send(to, &[&frame[..], &frame[..]].concat()),
            Some(Fault::Delay) => {
                std::thread::sleep(injector.delay());
                send(to, &frame)
            }
            Some(Fault::Drop) => Ok(()),
            Some(Fault::Reorder) if held.is_none() => {
                held = Some(frame);
                continue;
            }
            Some(Fault::Reorder) => send(to, &frame),
        };
        // A held frame goes out right behind the one that overtook it.
        let sent = match held.take() {
            Some(late) => sent.and_then(|()| send(to, &late)),
            None => sent,
        };
        if sent.is_err() {
            return PumpEnd::Closed;
        }
    }
}

fn send(to: &mut dyn Write, bytes: &[u8]) -> io::Result<()> {
    to.write_all(bytes)?;
    to.flush()
}
