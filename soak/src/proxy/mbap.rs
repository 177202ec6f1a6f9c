//! Modbus TCP through the proxy: MBAP frames on TCP connections, one server connection per
//! client connection.

use std::io::{self, BufRead, BufReader};
use std::net::{Shutdown, SocketAddr, TcpListener, TcpStream};

use super::{pump, Direction, Protocol, PumpEnd};
use crate::fault::{FaultCounts, FaultPlan, Injector};
use crate::rng::Rng;

/// MBAP header bytes before the PDU's function code (transaction, protocol, length, unit).
const HEADER: usize = 7;
/// Largest MBAP length field: unit id plus a 253-byte PDU.
const MAX_LENGTH: usize = 254;

/// MBAP framing.
#[derive(Debug)]
pub struct Mbap;

impl Protocol for Mbap {
    const TRUNCATE_ENDS_STREAM: bool = true;

    fn read_frame(&self, from: &mut dyn BufRead, _: Direction) -> io::Result<Option<Vec<u8>>> {
        let mut frame = vec![0u8; 6];
        if let Err(e) = from.read_exact(&mut frame) {
            return if e.kind() == io::ErrorKind::UnexpectedEof {
                Ok(None)
            } else {
                Err(e)
            };
        }
        let length = usize::from(u16::from_be_bytes([frame[4], frame[5]]));
        if length == 0 || length > MAX_LENGTH {
            return Err(io::Error::new(io::ErrorKind::InvalidData, "MBAP length"));
        }
        frame.resize(6 + length, 0);
        from.read_exact(&mut frame[6..])?;
        Ok(Some(frame))
    }

    /// MBAP has no checksum (TCP has its own), so damage to a value could not be detected by any
    /// Modbus peer: only the header and the function code are corrupted.
    fn corrupt(&self, frame: &mut Vec<u8>, rng: &mut Rng) {
        let at = rng.below((HEADER + 1).min(frame.len()) as u64) as usize;
        frame[at] ^= 1 + rng.below(255) as u8;
    }
}

/// Accepts clients on a loopback port and relays each to `server` through the faults of `plan`.
pub fn start(
    server: SocketAddr,
    plan: FaultPlan,
    seed: u64,
    counts: &'static FaultCounts,
) -> io::Result<SocketAddr> {
    let listener = TcpListener::bind("127.0.0.1:0")?;
    let addr = listener.local_addr()?;
    std::thread::spawn(move || {
        // One fault stream per direction, carried from connection to connection.
        let mut streams = [Direction::Request, Direction::Response]
            .map(|direction| Rng::stream(seed, &format!("tcp {}", direction.name())));
        for (connection, client) in listener.incoming().enumerate() {
            let Ok(client) = client else { continue };
            let Ok(upstream) = TcpStream::connect(server) else {
                continue;
            };
            let _ = client.set_nodelay(true);
            let _ = upstream.set_nodelay(true);
            let rngs = streams
                .each_mut()
                .map(|rng| Rng::new(rng.next_u64() ^ connection as u64));
            relay(client, upstream, rngs, plan, counts);
        }
    });
    Ok(addr)
}

/// Runs both pumps of one connection pair on their own threads; when either ends, both
/// connections close.
fn relay(
    client: TcpStream,
    upstream: TcpStream,
    [request_rng, response_rng]: [Rng; 2],
    plan: FaultPlan,
    counts: &'static FaultCounts,
) {
    let directions = [
        (
            Direction::Request,
            client.try_clone(),
            upstream.try_clone(),
            request_rng,
        ),
        (
            Direction::Response,
            upstream.try_clone(),
            client.try_clone(),
            response_rng,
        ),
    ];
    for (direction, from, to, rng) in directions {
        let (Ok(from), Ok(mut to)) = (from, to) else {
            continue;
        };
        let ends = [client.try_clone(), upstream.try_clone()];
        std::thread::spawn(move || {
            let mut injector = Injector::new(rng, plan, direction, counts);
            let mut reader = BufReader::new(from);
            // Closed or cut, the pair is over: the client reconnects.
            let _: PumpEnd = pump(&Mbap, direction, &mut reader, &mut to, &mut injector);
            for end in ends.into_iter().flatten() {
                let _ = end.shutdown(Shutdown::Both);
            }
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn corruption_stays_in_the_header_and_function_code() {
        let answer = [0, 7, 0, 0, 0, 5, 1, 0x03, 2, 0x12, 0x34];
        let mut rng = Rng::new(3);
        for _ in 0..200 {
            let mut frame = answer.to_vec();
            Mbap.corrupt(&mut frame, &mut rng);
            assert_ne!(frame, answer);
            assert_eq!(frame[HEADER + 1..], answer[HEADER + 1..]);
        }
    }

    #[test]
    fn frames_are_split_by_their_length_field() {
        let stream = [0, 1, 0, 0, 0, 3, 1, 0x03, 0x00, 0, 2, 0, 0, 0, 2, 1, 0x83];
        let mut from = &stream[..];
        assert_eq!(
            Mbap.read_frame(&mut from, Direction::Response)
                .unwrap()
                .unwrap()
                .len(),
            9
        );
        assert_eq!(
            Mbap.read_frame(&mut from, Direction::Response)
                .unwrap()
                .unwrap()
                .len(),
            8
        );
        assert_eq!(
            Mbap.read_frame(&mut from, Direction::Response).unwrap(),
            None
        );
    }
}
