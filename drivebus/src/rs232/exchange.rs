//! One request and its answer, as a pure function of the bytes received.
//!
//! The host sends a telegram and reads the next 10 bytes as the answer (point-to-point), or, in
//! multi-point loop mode, first its own telegram back and then the answer (manual lines
//! 2194–2222). Each received telegram is judged as soon as its 10th byte arrives: a checksum that
//! does not match, a telegram out of place (an echo where the answer is due, anything else where
//! the echo is due), another station, another object or a command that does not answer the
//! request ends the exchange with an [`Rs232Error`]. A drive discards telegrams with a wrong
//! checksum without answering (line 2207), so the exchange never resends on its own: the caller
//! decides whether a failed request may be repeated.

use super::data::{command, Answer, Object, Request, Value, Width};
use super::telegram::{self, Telegram, TELEGRAM_LEN};
use super::{LoopMode, Rs232Error, StationId};

/// What the exchange waits for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Awaiting {
    /// The host's own telegram, back from the loop.
    Echo,
    /// The drive's answer.
    Answer,
}

/// A complete telegram that does not end the exchange with an error.
enum Verdict {
    /// The host's own telegram, back from the loop where it was due.
    Echo,
    /// The answer.
    Answer(Answer),
}

/// One request to one station and the state of its answer.
///
/// The exchange keeps the request as its telegram: an answer must repeat its station byte and its
/// object bytes where they lie, and its command byte says whether a value or a confirmation is
/// due. Beside it, the key of the fast path that takes an upload's expected answer.
#[derive(Debug, Clone)]
pub struct Exchange {
    telegram: Telegram,
    /// The key of the fast path: while an upload's answer is due and no part of a telegram is
    /// held, the bytes that answer repeats (station, index and subindex) in their places of its
    /// first eight bytes; [`NO_UPLOAD`] otherwise (a download, the echo still due, a telegram
    /// arriving in pieces), so that the fast path checks the exchange's state in the same compare.
    upload_key: u64,
    mode: LoopMode,
    awaiting: Awaiting,
    /// A telegram received in pieces, its first `len` bytes so far.
    received: Telegram,
    len: usize,
}

impl Exchange {
    /// An exchange of `request` with `station`, wired as `mode` says.
    #[inline]
    pub fn new(station: StationId, request: Request, mode: LoopMode) -> Self {
        Self {
            telegram: telegram::encode(station, &request.encode()),
            upload_key: match (request, mode) {
                (Request::Upload(object), LoopMode::PointToPoint) => upload_key(station, object),
                _ => NO_UPLOAD,
            },
            mode,
            awaiting: match mode {
                LoopMode::PointToPoint => Awaiting::Answer,
                LoopMode::MultiPoint => Awaiting::Echo,
            },
            received: [0; TELEGRAM_LEN],
            len: 0,
        }
    }

    /// The telegram to send.
    #[inline]
    pub fn telegram(&self) -> &Telegram {
        &self.telegram
    }

    /// Takes received bytes; returns the answer once it is complete (a download's or an
    /// upload's; an error answer is [`Rs232Error::Refused`]). Bytes after the answer are left
    /// unread: the caller drops stale input before its next request.
    #[inline]
    pub fn receive(&mut self, bytes: &[u8]) -> Result<Option<Answer>, Rs232Error> {
        match self.expected_upload(bytes) {
            Some(answer) => Ok(Some(answer)),
            None => self.receive_any(bytes),
        }
    }

    /// [`Exchange::receive`] of anything but an upload's expected answer: telegrams in pieces,
    /// echoes, downloads' answers, and every telegram that ends the exchange with an error. Out
    /// of line, so that the fast path stays small where it is inlined.
    #[inline(never)]
    fn receive_any(&mut self, bytes: &[u8]) -> Result<Option<Answer>, Rs232Error> {
        let answer = self.gather(bytes);
        self.arm();
        answer
    }

    /// Arms the fast path where it may take the next telegram: an upload's answer is due and no
    /// part of a telegram is held.
    fn arm(&mut self) {
        let [head @ .., _, _] = &self.telegram;
        let due = self.len == 0 && self.awaiting == Awaiting::Answer;
        self.upload_key = match due && head[1] == command::UPLOAD {
            true => u64::from_le_bytes(*head) & UPLOAD_KEY_BYTES,
            false => NO_UPLOAD,
        };
    }

    /// Gathers `bytes` into whole telegrams and judges each in turn.
    fn gather(&mut self, mut bytes: &[u8]) -> Result<Option<Answer>, Rs232Error> {
        while !bytes.is_empty() {
            let take = (TELEGRAM_LEN - self.len).min(bytes.len());
            let (front, rest) = bytes.split_at(take);
            self.received[self.len..self.len + take].copy_from_slice(front);
            self.len += take;
            bytes = rest;
            if self.len < TELEGRAM_LEN {
                return Ok(None);
            }
            self.len = 0;
            match self.judge(&self.received)? {
                Verdict::Echo => self.awaiting = Awaiting::Answer,
                Verdict::Answer(answer) => return Ok(Some(answer)),
            }
        }
        Ok(None)
    }

    /// The value of an upload if `bytes` are exactly its expected answer, whole and where it
    /// is due (the upload key is armed): the right station and object, an upload answer's
    /// command, a good checksum. `None` for anything else, which the general path then judges.
    #[inline(always)]
    fn expected_upload(&self, bytes: &[u8]) -> Option<Answer> {
        let received: &Telegram = bytes.try_into().ok()?;
        let [head @ .., _, _] = received;
        let key = u64::from_le_bytes(*head) & UPLOAD_KEY_BYTES;
        if key != self.upload_key || !telegram::sums_to_zero(received) {
            return None;
        }
        let [_, data @ .., _] = received;
        let width = Width::from_uploaded_command(data[0])?;
        Some(Answer::Uploaded(
            Object::read_from(data),
            Value::from_data(width, data),
        ))
    }

    /// The error that ends the exchange when the timeout passes before the answer is complete.
    #[inline]
    pub fn timed_out(&self) -> Rs232Error {
        match (self.awaiting, self.len) {
            (_, received @ 1..) => Rs232Error::Short { received },
            (Awaiting::Echo, 0) => Rs232Error::Silence,
            (Awaiting::Answer, 0) if self.mode == LoopMode::MultiPoint => Rs232Error::NoAnswer,
            (Awaiting::Answer, 0) => Rs232Error::Silence,
        }
    }

    /// Judges a complete telegram.
    fn judge(&self, received: &Telegram) -> Result<Verdict, Rs232Error> {
        let is_echo = *received == self.telegram;
        match (self.awaiting, is_echo) {
            (Awaiting::Echo, true) => Ok(Verdict::Echo),
            (Awaiting::Echo, false) => Err(Rs232Error::MissingEcho),
            (Awaiting::Answer, true) => Err(Rs232Error::EchoOutOfPlace),
            (Awaiting::Answer, false) => self.answer(received).map(Verdict::Answer),
        }
    }

    /// The answer `received` gives to the request: its checksum, station and object checked
    /// against the request telegram's own bytes, then its command against the request's.
    fn answer(&self, received: &Telegram) -> Result<Answer, Rs232Error> {
        let (station, data) = telegram::decode(received).map_err(|bad| Rs232Error::Checksum {
            received: bad.received,
            expected: bad.expected,
        })?;
        let [request_station, request @ .., _] = &self.telegram;
        if station.0 != *request_station {
            return Err(Rs232Error::OtherStation { station: station.0 });
        }
        Answer::reply_to(request, data)
    }
}

/// The bytes of a telegram's first eight that an upload's answer repeats: station (byte 0),
/// index and subindex (bytes 2–4).
const UPLOAD_KEY_BYTES: u64 = 0x0000_00FF_FFFF_00FF;

/// The disarmed upload key: bits outside [`UPLOAD_KEY_BYTES`], so no answer matches it.
const NO_UPLOAD: u64 = !UPLOAD_KEY_BYTES;

/// The upload key of `object` at `station`: its bytes where [`UPLOAD_KEY_BYTES`] are. Built from
/// the values, not read back from the request telegram: that would load as one word what was
/// stored byte by byte, a store-forwarding stall that tripled the time of a read.
#[inline]
fn upload_key(station: StationId, object: Object) -> u64 {
    let [lo, hi] = object.index.to_le_bytes();
    u64::from_le_bytes([station.0, 0, lo, hi, object.subindex, 0, 0, 0])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rs232::data::{Object, Value};
    use proptest::prelude::*;

    const STATUSWORD: Object = Object {
        index: 0x6041,
        subindex: 0,
    };

    fn read_statusword(mode: LoopMode) -> Exchange {
        Exchange::new(StationId(1), Request::Upload(STATUSWORD), mode)
    }

    fn statusword_answer() -> Telegram {
        let value = Value::new(&[0x37, 0x04]).unwrap();
        telegram::encode(StationId(1), &Answer::Uploaded(STATUSWORD, value).encode())
    }

    #[test]
    fn point_to_point_takes_the_next_telegram_as_the_answer() {
        let mut exchange = read_statusword(LoopMode::PointToPoint);
        let answer = statusword_answer();
        // Split across reads as a serial port delivers it.
        assert_eq!(exchange.receive(&answer[..3]), Ok(None));
        let done = exchange.receive(&answer[3..]).unwrap().unwrap();
        assert_eq!(done.value(), Some(&[0x37, 0x04][..]));
    }

    #[test]
    fn multi_point_wants_the_echo_first() {
        let mut exchange = read_statusword(LoopMode::MultiPoint);
        let mut wire = exchange.telegram().to_vec();
        wire.extend(statusword_answer());
        let done = exchange.receive(&wire).unwrap().unwrap();
        assert_eq!(done.object(), STATUSWORD);
    }

    #[test]
    fn an_answer_before_the_echo_is_out_of_place() {
        let mut exchange = read_statusword(LoopMode::MultiPoint);
        assert_eq!(
            exchange.receive(&statusword_answer()),
            Err(Rs232Error::MissingEcho)
        );
    }

    #[test]
    fn an_echo_where_the_answer_is_due_is_out_of_place() {
        let mut point_to_point = read_statusword(LoopMode::PointToPoint);
        let echo = *point_to_point.telegram();
        assert_eq!(
            point_to_point.receive(&echo),
            Err(Rs232Error::EchoOutOfPlace)
        );
        let mut multi_point = read_statusword(LoopMode::MultiPoint);
        assert_eq!(multi_point.receive(&echo), Ok(None));
        assert_eq!(multi_point.receive(&echo), Err(Rs232Error::EchoOutOfPlace));
    }

    #[test]
    fn silence_and_short_telegrams_are_told_apart() {
        let exchange = read_statusword(LoopMode::PointToPoint);
        assert_eq!(exchange.timed_out(), Rs232Error::Silence);
        let mut short = read_statusword(LoopMode::PointToPoint);
        short.receive(&statusword_answer()[..9]).unwrap();
        assert_eq!(short.timed_out(), Rs232Error::Short { received: 9 });
        let mut unanswered = read_statusword(LoopMode::MultiPoint);
        let echo = *unanswered.telegram();
        unanswered.receive(&echo).unwrap();
        assert_eq!(unanswered.timed_out(), Rs232Error::NoAnswer);
        assert_eq!(
            read_statusword(LoopMode::MultiPoint).timed_out(),
            Rs232Error::Silence
        );
    }

    #[test]
    fn a_wrong_checksum_is_refused() {
        let mut exchange = read_statusword(LoopMode::PointToPoint);
        let mut answer = statusword_answer();
        answer[9] = answer[9].wrapping_add(1);
        assert!(matches!(
            exchange.receive(&answer),
            Err(Rs232Error::Checksum { .. })
        ));
    }

    #[test]
    fn answers_about_other_stations_objects_or_requests_are_refused() {
        let other_station = telegram::encode(
            StationId(2),
            &Answer::Uploaded(STATUSWORD, Value::new(&[0, 0]).unwrap()).encode(),
        );
        assert_eq!(
            read_statusword(LoopMode::PointToPoint).receive(&other_station),
            Err(Rs232Error::OtherStation { station: 2 })
        );
        let control = Object {
            index: 0x6040,
            subindex: 0,
        };
        let other_object = telegram::encode(StationId(1), &Answer::Downloaded(control).encode());
        assert_eq!(
            read_statusword(LoopMode::PointToPoint).receive(&other_object),
            Err(Rs232Error::OtherObject {
                index: 0x6040,
                subindex: 0
            })
        );
        let written = telegram::encode(StationId(1), &Answer::Downloaded(STATUSWORD).encode());
        assert_eq!(
            read_statusword(LoopMode::PointToPoint).receive(&written),
            Err(Rs232Error::UnexpectedCommand { command: 0x60 })
        );
    }

    #[test]
    fn the_key_built_with_the_exchange_is_the_one_armed_from_its_telegram() {
        let built = read_statusword(LoopMode::PointToPoint);
        let mut armed = built.clone();
        armed.arm();
        assert_ne!(built.upload_key, NO_UPLOAD);
        assert_eq!(built.upload_key, armed.upload_key);
    }

    #[test]
    fn an_error_answer_carries_its_cause() {
        let refused = telegram::encode(
            StationId(1),
            &Answer::Refused(STATUSWORD, 0x0601_0002).encode(),
        );
        assert_eq!(
            read_statusword(LoopMode::PointToPoint).receive(&refused),
            Err(Rs232Error::Refused { cause: 0x0601_0002 })
        );
    }

    proptest! {
        #[test]
        fn any_bytes_in_any_chunks_never_panic(
            bytes in proptest::collection::vec(any::<u8>(), 0..40),
            cut in 0usize..40,
            multi_point: bool,
        ) {
            let mode = if multi_point { LoopMode::MultiPoint } else { LoopMode::PointToPoint };
            let mut exchange = read_statusword(mode);
            let cut = cut.min(bytes.len());
            if exchange.receive(&bytes[..cut]) == Ok(None) {
                let _ = exchange.receive(&bytes[cut..]);
            }
            let _ = exchange.timed_out();
        }

        #[test]
        fn the_fast_path_agrees_with_the_general_one(
            value in proptest::collection::vec(any::<u8>(), 4),
            width in prop_oneof![Just(1usize), Just(2), Just(4)],
            (at, byte) in (0..TELEGRAM_LEN, any::<u8>()),
            corrupt: bool,
            download: bool,
            multi_point: bool,
        ) {
            let request = match download {
                true => Request::download(0x6041, 0, &value[..width]).unwrap(),
                false => Request::Upload(STATUSWORD),
            };
            let mode = if multi_point { LoopMode::MultiPoint } else { LoopMode::PointToPoint };
            let mut exchange = Exchange::new(StationId(1), request, mode);
            if multi_point {
                let echo = *exchange.telegram();
                prop_assert_eq!(exchange.receive(&echo), Ok(None));
            }
            let answer = Answer::Uploaded(STATUSWORD, Value::new(&value[..width]).unwrap());
            let mut wire = telegram::encode(StationId(1), &answer.encode());
            if corrupt {
                wire[at] = byte;
            }
            let fast = exchange.clone().receive(&wire);
            prop_assert_eq!(fast, exchange.clone().receive_any(&wire));
            prop_assert_eq!(
                exchange.expected_upload(&wire).is_some(),
                !download && (!corrupt || wire == telegram::encode(StationId(1), &answer.encode()))
            );
        }

        #[test]
        fn every_answer_is_found_behind_its_echo(value in proptest::collection::vec(any::<u8>(), 4)) {
            let mut exchange = read_statusword(LoopMode::MultiPoint);
            let answer = Answer::Uploaded(STATUSWORD, Value::new(&value).unwrap());
            let mut wire = exchange.telegram().to_vec();
            wire.extend(telegram::encode(StationId(1), &answer.encode()));
            prop_assert_eq!(exchange.receive(&wire), Ok(Some(answer)));
        }
    }
}
