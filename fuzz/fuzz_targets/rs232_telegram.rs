//! The Kinco RS-232 telegram decoder, its data protocol, the host's exchange and the
//! simulator's drive fed arbitrary bytes.
//!
//! Input: `[mode, chunk, telegram (10 bytes), received bytes...]`; `mode` bit 0 picks the
//! multi-point loop; `chunk` (1..=256) is the size of the pieces the received bytes arrive in.
//! Asserts that
//! * a telegram whose checksum holds re-encodes to the same 10 bytes;
//! * a decoded request or answer re-encodes to data that decodes to it again, and keeps the
//!   command, object and value bytes it was read from;
//! * the exchange's outcome does not depend on how the received bytes are chunked;
//! * the simulated Kinco drive's reply to the telegram is accepted by an exchange of the
//!   request it carries (the answer, or the drive's refusal).
#![no_main]

use drivebus::rs232::data::{Answer, Request};
use drivebus::rs232::exchange::Exchange;
use drivebus::rs232::telegram::{self, Data, Telegram};
use drivebus::rs232::{LoopMode, Rs232Error, StationId};
use fuzz::{shipped, Cursor};
use drivesim::Simulator;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let mut input = Cursor::new(data);
    let mode = if input.u8() & 1 == 0 {
        LoopMode::PointToPoint
    } else {
        LoopMode::MultiPoint
    };
    let chunk = usize::from(input.u8()) + 1;
    let sent: Telegram = input.array();
    let received = input.rest();
    let Ok((station, data)) = telegram::decode(&sent) else {
        return;
    };
    assert_eq!(telegram::encode(station, data), sent, "telegram re-encodes");
    check_request(data);
    check_answer(data);
    let Ok(request) = Request::decode(data) else {
        return;
    };
    let whole = Exchange::new(station, request, mode).receive(received);
    assert_eq!(chunked(station, request, mode, received, chunk), whole);
    check_drive(station, request, mode);
});

/// A decoded request keeps its bytes through a re-encoding.
fn check_request(data: &Data) {
    let Ok(request) = Request::decode(data) else {
        return;
    };
    let encoded = request.encode();
    assert_eq!(Request::decode(&encoded), Ok(request));
    let kept = match request {
        Request::Upload(_) => 4,
        Request::Download(_, value) => 4 + value.as_bytes().len(),
    };
    assert_eq!(encoded[..kept], data[..kept], "{request:?}");
}

/// A decoded answer keeps its bytes through a re-encoding.
fn check_answer(data: &Data) {
    let Ok(answer) = Answer::decode(data) else {
        return;
    };
    let encoded = answer.encode();
    assert_eq!(Answer::decode(&encoded), Ok(answer));
    let kept = match answer {
        Answer::Downloaded(_) => 4,
        Answer::Refused(..) => 8,
        Answer::Uploaded(_, value) => 4 + value.as_bytes().len(),
    };
    assert_eq!(encoded[..kept], data[..kept], "{answer:?}");
}

/// The exchange's outcome with `received` arriving `chunk` bytes at a time.
fn chunked(
    station: StationId,
    request: Request,
    mode: LoopMode,
    received: &[u8],
    chunk: usize,
) -> Result<Option<Answer>, Rs232Error> {
    let mut exchange = Exchange::new(station, request, mode);
    for piece in received.chunks(chunk) {
        if let Some(answer) = exchange.receive(piece)? {
            return Ok(Some(answer));
        }
    }
    Ok(None)
}

/// The simulated drive answers the request, as the host sends it, in a way the host accepts.
fn check_drive(station: StationId, request: Request, mode: LoopMode) {
    let sim = Simulator::new(shipped::device("kinco-fd").clone());
    let mut drive = sim.rs232_server(station, mode);
    let mut exchange = Exchange::new(station, request, mode);
    let reply = drive.handle(exchange.telegram());
    let outcome = exchange.receive(&reply);
    match outcome {
        Ok(Some(answer)) => assert_eq!(answer.object(), request.object()),
        Err(Rs232Error::Refused { .. }) => {}
        other => panic!("the host cannot read the drive's reply {reply:02X?}: {other:?}"),
    }
}
