//! A simulated drive on the Kinco RS-232 protocol (manual `003_8cc8f7f4f05b8633.txt`, chapter 9).
//!
//! Each received telegram is handled as the manual describes: a telegram for another station,
//! or for this one with a wrong checksum, gets no answer (lines 2207, 2220); an upload or
//! download is carried out on the same store the other protocols serve, with the access, length
//! and range checks of the description, and refused with an error answer (`80h`) whose cause is
//! the CiA 301 abort code of the refusal. In multi-point loop mode every telegram passes the
//! drive, so it is repeated before the drive's own answer (lines 2210–2217).

use std::time::{Duration, Instant};

use drivebus::canopen::sdo::server::ObjectDictionary;
use drivebus::canopen::sdo::AbortCode;
use drivebus::rs232::data::{Answer, Object, Request, Value};
use drivebus::rs232::telegram::{self, Telegram, TELEGRAM_LEN};
use drivebus::rs232::{LoopMode, StationId};
use drivebus::stream::ByteStream;
use drivebus::BusError;

use crate::canopen::Dictionary;
use crate::Simulator;

/// Silence after which the bytes of an unfinished telegram are dropped, so the drive finds the
/// start of the next one after noise (a pty has no timing; the manual gives no figure).
const SILENCE: Duration = Duration::from_millis(50);

/// A simulated drive answering RS-232 telegrams.
#[derive(Debug)]
pub struct Rs232Server {
    station: StationId,
    mode: LoopMode,
    dictionary: Dictionary,
}

impl Rs232Server {
    /// `sim`'s drive at `station`, wired as `mode` says.
    pub fn new(sim: &Simulator, station: StationId, mode: LoopMode) -> Self {
        let dictionary = sim.with(|drive| {
            Dictionary::of(sim.clone(), drive.store().device(), sim.variant(), |p| {
                &p.rs232
            })
        });
        Self {
            station,
            mode,
            dictionary,
        }
    }

    /// How the drive is wired: point to point, or in a loop that repeats every telegram.
    pub fn mode(&self) -> LoopMode {
        self.mode
    }

    /// The bytes the drive sends after receiving `received`: the telegram itself in loop mode,
    /// then the answer if the telegram is this station's and its checksum is right.
    pub fn handle(&mut self, received: &Telegram) -> Vec<u8> {
        let mut out = Vec::with_capacity(2 * TELEGRAM_LEN);
        if self.mode == LoopMode::MultiPoint {
            out.extend_from_slice(received);
        }
        match telegram::decode(received) {
            Ok((station, data)) if station == self.station => {
                let answer = self.answer(data);
                out.extend_from_slice(&telegram::encode(self.station, &answer.encode()));
            }
            _ => {}
        }
        out
    }

    fn answer(&mut self, data: &telegram::Data) -> Answer {
        let request = match Request::decode(data) {
            Ok(request) => request,
            Err(_) => {
                let object = Object {
                    index: u16::from_le_bytes([data[1], data[2]]),
                    subindex: data[3],
                };
                return refused(object, AbortCode::InvalidCommandSpecifier);
            }
        };
        let object = request.object();
        let result = match request {
            Request::Upload(_) => self
                .dictionary
                .read(object.index, object.subindex)
                .and_then(|bytes| Value::new(&bytes).map_err(|_| AbortCode::LengthMismatch))
                .map(|value| Answer::Uploaded(object, value)),
            Request::Download(_, value) => self
                .dictionary
                .write(object.index, object.subindex, value.as_bytes())
                .map(|()| Answer::Downloaded(object)),
        };
        result.unwrap_or_else(|code| refused(object, code))
    }
}

fn refused(object: Object, code: AbortCode) -> Answer {
    Answer::Refused(object, code.code())
}

/// Serves `server` on `stream` until the stream fails.
pub fn serve<S: ByteStream>(server: &mut Rs232Server, stream: &mut S) -> Result<(), BusError> {
    let mut pending: Vec<u8> = Vec::with_capacity(2 * TELEGRAM_LEN);
    let mut chunk = [0u8; 64];
    loop {
        let n = stream.receive(&mut chunk, Instant::now() + SILENCE)?;
        if n == 0 {
            pending.clear();
            continue;
        }
        pending.extend_from_slice(&chunk[..n]);
        while pending.len() >= TELEGRAM_LEN {
            let mut received = [0u8; TELEGRAM_LEN];
            received.copy_from_slice(&pending[..TELEGRAM_LEN]);
            pending.drain(..TELEGRAM_LEN);
            let reply = server.handle(&received);
            if !reply.is_empty() {
                stream.send(&reply)?;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fixture() -> Simulator {
        Simulator::load(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../tests/fixtures/kinco-rs232"
        ))
        .unwrap()
    }

    fn request(station: u8, request: Request) -> Telegram {
        telegram::encode(StationId(station), &request.encode())
    }

    fn answer(bytes: &[u8]) -> Answer {
        let telegram: Telegram = bytes.try_into().unwrap();
        let (_, data) = telegram::decode(&telegram).unwrap();
        Answer::decode(data).unwrap()
    }

    #[test]
    fn the_manuals_telegrams_are_carried_out() {
        let sim = fixture();
        let mut server = sim.rs232_server(StationId(1), LoopMode::PointToPoint);
        // Line 2332: "Set Target_position = 50000".
        let set = [0x01, 0x23, 0x7A, 0x60, 0x00, 0x50, 0xC3, 0x00, 0x00, 0xEF];
        let reply = server.handle(&set);
        assert_eq!(
            reply,
            [0x01, 0x60, 0x7A, 0x60, 0x00, 0x00, 0x00, 0x00, 0x00, 0xC5]
        );
        let read = server.handle(&request(1, Request::upload(0x607A, 0)));
        assert_eq!(answer(&read).value(), Some(&50_000i32.to_le_bytes()[..]));
    }

    #[test]
    fn other_stations_and_bad_checksums_get_no_answer() {
        let sim = fixture();
        let mut server = sim.rs232_server(StationId(1), LoopMode::PointToPoint);
        assert!(server
            .handle(&request(2, Request::upload(0x6041, 0)))
            .is_empty());
        let mut corrupt = request(1, Request::upload(0x6041, 0));
        corrupt[9] ^= 0xFF;
        assert!(server.handle(&corrupt).is_empty());
    }

    #[test]
    fn in_a_loop_every_telegram_passes_before_the_answer() {
        let sim = fixture();
        let mut server = sim.rs232_server(StationId(1), LoopMode::MultiPoint);
        let other = request(2, Request::upload(0x6041, 0));
        assert_eq!(server.handle(&other), other);
        let mine = request(1, Request::upload(0x6041, 0));
        let reply = server.handle(&mine);
        assert_eq!(&reply[..10], &mine);
        assert!(matches!(answer(&reply[10..]), Answer::Uploaded(..)));
    }

    #[test]
    fn refusals_carry_the_abort_code() {
        let sim = fixture();
        let mut server = sim.rs232_server(StationId(1), LoopMode::PointToPoint);
        let object = |index| Object { index, subindex: 0 };
        let write_statusword = Request::download(0x6041, 0, &[0, 0]).unwrap();
        assert_eq!(
            answer(&server.handle(&request(1, write_statusword))),
            Answer::Refused(object(0x6041), AbortCode::ReadOnly.code())
        );
        let mode_5 = Request::download(0x6060, 0, &[5]).unwrap();
        assert_eq!(
            answer(&server.handle(&request(1, mode_5))),
            Answer::Refused(object(0x6060), AbortCode::InvalidValue.code())
        );
        assert_eq!(
            answer(&server.handle(&request(1, Request::upload(0x2000, 0)))),
            Answer::Refused(object(0x2000), AbortCode::ObjectDoesNotExist.code())
        );
        // The Modbus-only parameter has no RS-232 object.
        assert_eq!(
            answer(&server.handle(&request(1, Request::upload(0x0CF0, 0)))),
            Answer::Refused(object(0x0CF0), AbortCode::ObjectDoesNotExist.code())
        );
    }
}
