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

use super::data::{Answer, Object, Request};
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
#[derive(Debug, Clone)]
pub struct Exchange {
    station: StationId,
    mode: LoopMode,
    /// The object asked about, and whether the request is an upload (else a download): what
    /// the answer must match.
    object: Object,
    upload: bool,
    telegram: Telegram,
    awaiting: Awaiting,
    received: Telegram,
    len: usize,
}

impl Exchange {
    /// An exchange of `request` with `station`, wired as `mode` says.
    #[inline]
    pub fn new(station: StationId, request: Request, mode: LoopMode) -> Self {
        Self {
            station,
            mode,
            object: request.object(),
            upload: matches!(request, Request::Upload(_)),
            telegram: telegram::encode(station, &request.encode()),
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
    pub fn receive(&mut self, mut bytes: &[u8]) -> Result<Option<Answer>, Rs232Error> {
        while !bytes.is_empty() {
            let verdict = match (self.len, bytes.split_first_chunk::<TELEGRAM_LEN>()) {
                // A whole telegram at a boundary (the usual case) is judged where it lies.
                (0, Some((telegram, rest))) => {
                    bytes = rest;
                    self.judge(telegram)?
                }
                _ => {
                    let take = (TELEGRAM_LEN - self.len).min(bytes.len());
                    self.received[self.len..self.len + take].copy_from_slice(&bytes[..take]);
                    self.len += take;
                    bytes = &bytes[take..];
                    if self.len < TELEGRAM_LEN {
                        return Ok(None);
                    }
                    self.len = 0;
                    self.judge(&self.received)?
                }
            };
            match verdict {
                Verdict::Echo => self.awaiting = Awaiting::Answer,
                Verdict::Answer(answer) => return Ok(Some(answer)),
            }
        }
        Ok(None)
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

    /// Judges a complete telegram. Always inlined: called by reference to the telegram where it
    /// lies, a call would reload the request's bytes through memory.
    #[inline(always)]
    fn judge(&self, received: &Telegram) -> Result<Verdict, Rs232Error> {
        // The command byte first: an answer's never equals the request's, so the whole
        // telegram is compared only for a likely echo (and the telegram just built, still in
        // the store buffer as pieces, is not reloaded whole).
        let is_echo = received[1] == self.telegram[1] && *received == self.telegram;
        match (self.awaiting, is_echo) {
            (Awaiting::Echo, true) => Ok(Verdict::Echo),
            (Awaiting::Echo, false) => Err(Rs232Error::MissingEcho),
            (Awaiting::Answer, true) => Err(Rs232Error::EchoOutOfPlace),
            (Awaiting::Answer, false) => self.answer(received).map(Verdict::Answer),
        }
    }

    #[inline]
    fn answer(&self, received: &Telegram) -> Result<Answer, Rs232Error> {
        let (station, data) = telegram::decode(received).map_err(|bad| Rs232Error::Checksum {
            received: bad.received,
            expected: bad.expected,
        })?;
        if station != self.station {
            return Err(Rs232Error::OtherStation { station: station.0 });
        }
        let answer = Answer::decode(data)?;
        let object = answer.object();
        if object != self.object {
            return Err(Rs232Error::OtherObject {
                index: object.index,
                subindex: object.subindex,
            });
        }
        match (self.upload, answer) {
            (_, Answer::Refused(_, cause)) => Err(Rs232Error::Refused { cause }),
            (true, Answer::Uploaded(..)) | (false, Answer::Downloaded(_)) => Ok(answer),
            _ => Err(Rs232Error::UnexpectedCommand { command: data[0] }),
        }
    }
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
        fn every_answer_is_found_behind_its_echo(value in proptest::collection::vec(any::<u8>(), 4)) {
            let mut exchange = read_statusword(LoopMode::MultiPoint);
            let answer = Answer::Uploaded(STATUSWORD, Value::new(&value).unwrap());
            let mut wire = exchange.telegram().to_vec();
            wire.extend(telegram::encode(StationId(1), &answer.encode()));
            prop_assert_eq!(exchange.receive(&wire), Ok(Some(answer)));
        }
    }
}
