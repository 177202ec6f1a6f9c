//! can-utils candump text: compact lines (`123#DEADBEEF`, `123#R`) and log lines
//! (`(1700000000.123456) can0 123#DEADBEEF`), over pipes and files.
//!
//! [`CandumpBus`] is a [`CanBus`] over any reader/writer pair — a child process's stdio (a relay
//! to another CAN stack), or a file for replay. [`CandumpReader`] and [`parse_line`] decode logs
//! offline.

use core::time::Duration;
use std::io::{self, BufRead, BufReader, Read, Write};
use std::process::{Child, ChildStdin};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc::{sync_channel, Receiver, RecvTimeoutError};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::vec::Vec;

use super::candump_fast::{parse_line_at, parse_well_formed};
use super::CanBus;
use crate::canopen::frame::CanFrame;
use crate::error::BusError;

/// One parsed line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Record {
    /// Log timestamp in microseconds since the epoch, for log lines.
    pub timestamp_us: Option<u64>,
    /// The frame.
    pub frame: CanFrame,
}

/// Not a hex digit, in [`HEX`].
pub(super) const INVALID: u8 = 0xFF;
/// Hex digit values; `INVALID` for other bytes.
pub(super) static HEX: [u8; 256] = {
    let mut table = [INVALID; 256];
    let mut i = 0;
    while i < 10 {
        table[b'0' as usize + i] = i as u8;
        i += 1;
    }
    let mut i = 0;
    while i < 6 {
        table[b'a' as usize + i] = 10 + i as u8;
        table[b'A' as usize + i] = 10 + i as u8;
        i += 1;
    }
    table
};

fn hex(byte: u8) -> Result<u8, BusError> {
    match HEX[byte as usize] {
        INVALID => Err(BusError::Frame("candump: not a hex digit")),
        value => Ok(value),
    }
}

/// Parses `(seconds.micros)`.
fn parse_timestamp(text: &[u8]) -> Result<u64, BusError> {
    let bad = BusError::Frame("candump: malformed timestamp");
    let dot = text.iter().position(|&b| b == b'.').ok_or(bad.clone())?;
    let (secs, micros) = (&text[..dot], &text[dot + 1..]);
    if secs.is_empty() || micros.is_empty() || micros.len() > 6 {
        return Err(bad);
    }
    let mut value = 0u64;
    for &b in secs.iter().chain(micros) {
        if !b.is_ascii_digit() {
            return Err(bad);
        }
        value = value
            .checked_mul(10)
            .and_then(|v| v.checked_add(u64::from(b - b'0')))
            .ok_or(bad.clone())?;
    }
    // A timestamp past u64 microseconds (year 586,524) is malformed, not an overflow.
    value
        .checked_mul(10u64.pow(6 - micros.len() as u32))
        .ok_or(bad)
}

/// Parses one line; `Ok(None)` for blank lines and `#` comments.
pub fn parse_line(line: &[u8]) -> Result<Option<Record>, BusError> {
    let line = line.trim_ascii();
    if line.is_empty() || line[0] == b'#' {
        return Ok(None);
    }
    // A log's lines take one pass (`drivegen trace`, issue 33); a line that pass does not
    // take (malformed, or a rare form) is parsed again field by field, which names the error.
    match parse_well_formed(line) {
        Some(record) => Ok(Some(record)),
        None => parse_fields(line).map(Some),
    }
}

/// Parses a trimmed line that is not a comment field by field: the timestamp, the last field
/// as the frame. Gives the error of a malformed line.
fn parse_fields(line: &[u8]) -> Result<Record, BusError> {
    let (timestamp_us, frame_text) = if line[0] == b'(' {
        let close = line
            .iter()
            .position(|&b| b == b')')
            .ok_or(BusError::Frame("candump: unterminated timestamp"))?;
        let timestamp = parse_timestamp(&line[1..close])?;
        // "(ts) iface frame": the frame is the last field.
        let rest = line[close + 1..].trim_ascii();
        let frame = rest
            .rsplit(|&b| b == b' ' || b == b'\t')
            .next()
            .ok_or(BusError::Frame("candump: missing frame"))?;
        (Some(timestamp), frame)
    } else {
        (None, line)
    };
    Ok(Record {
        timestamp_us,
        frame: parse_frame(frame_text)?,
    })
}

/// Parses a compact frame: `123#DEADBEEF`, `123#DE.AD.BE.EF`, `123#R`, `123#R8`.
pub fn parse_frame(text: &[u8]) -> Result<CanFrame, BusError> {
    let hash = text
        .iter()
        .position(|&b| b == b'#')
        .ok_or(BusError::Frame("candump: missing '#'"))?;
    let (id_text, payload) = (&text[..hash], &text[hash + 1..]);
    if id_text.len() == 8 {
        return Err(BusError::Unsupported("29-bit CAN identifiers"));
    }
    if id_text.len() != 3 {
        return Err(BusError::Frame(
            "candump: identifier must have 3 hex digits",
        ));
    }
    let id = id_text.iter().try_fold(0u16, |id, &b| {
        Ok::<_, BusError>((id << 4) | u16::from(hex(b)?))
    })?;
    match payload.first() {
        Some(b'#') => return Err(BusError::Unsupported("CAN FD frames")),
        Some(b'R' | b'r') => {
            let len = match payload.get(1) {
                None => 0,
                Some(&digit) => hex(digit)?,
            };
            if payload.len() > 2 {
                return Err(BusError::Frame("candump: trailing text after remote frame"));
            }
            return CanFrame::remote(id, len);
        }
        _ => {}
    }
    let mut data = [0u8; 8];
    let mut len = 0;
    let mut digits = payload.iter().filter(|&&b| b != b'.');
    while let Some(&high) = digits.next() {
        let low = *digits
            .next()
            .ok_or(BusError::Frame("candump: odd number of hex digits"))?;
        let slot = data
            .get_mut(len)
            .ok_or(BusError::Frame("candump: more than 8 data bytes"))?;
        *slot = (hex(high)? << 4) | hex(low)?;
        len += 1;
    }
    CanFrame::new(id, &data[..len])
}

/// Appends the compact form of `frame` (`123#DEADBEEF`, `123#R`), without a newline.
pub fn format_frame(frame: &CanFrame, out: &mut Vec<u8>) {
    const DIGITS: &[u8; 16] = b"0123456789ABCDEF";
    let id = frame.id();
    out.extend([
        DIGITS[(id >> 8) as usize & 0xF],
        DIGITS[(id >> 4) as usize & 0xF],
        DIGITS[id as usize & 0xF],
        b'#',
    ]);
    if frame.is_remote() {
        out.push(b'R');
        if frame.dlc() > 0 {
            out.push(DIGITS[frame.dlc() as usize]);
        }
        return;
    }
    for byte in frame.data() {
        out.extend([DIGITS[(byte >> 4) as usize], DIGITS[(byte & 0xF) as usize]]);
    }
}

/// Longest line [`CandumpReader`] reads (a log line with a long interface name is under 64
/// bytes). A longer one is reported as malformed and skipped up to its newline, so a peer that
/// never sends a newline cannot make the reader's buffer grow.
pub const MAX_LINE: usize = 256;

/// How a bounded line read ended.
enum LineRead {
    /// The stream ended.
    End,
    /// A line (with its newline, unless the stream ended first).
    Line,
    /// A line longer than [`MAX_LINE`], now skipped.
    TooLong,
}

/// Reads one line of at most [`MAX_LINE`] bytes into `line`.
fn read_line<R: BufRead>(reader: &mut R, line: &mut Vec<u8>) -> io::Result<LineRead> {
    let read = reader
        .by_ref()
        .take(MAX_LINE as u64 + 1)
        .read_until(b'\n', line)?;
    if read == 0 {
        return Ok(LineRead::End);
    }
    if read > MAX_LINE && line.last() != Some(&b'\n') {
        skip_line(reader)?;
        return Ok(LineRead::TooLong);
    }
    Ok(LineRead::Line)
}

/// Drops input up to and including the next newline (or the end of the stream).
fn skip_line<R: BufRead>(reader: &mut R) -> io::Result<()> {
    loop {
        let buf = reader.fill_buf()?;
        if buf.is_empty() {
            return Ok(());
        }
        match buf.iter().position(|&b| b == b'\n') {
            Some(newline) => {
                reader.consume(newline + 1);
                return Ok(());
            }
            None => {
                let len = buf.len();
                reader.consume(len);
            }
        }
    }
}

/// Iterates the frames of a candump text stream (compact or log lines), skipping blank lines
/// and comments; malformed lines (and lines over [`MAX_LINE`] bytes) are reported as errors and
/// iteration continues.
#[derive(Debug)]
pub struct CandumpReader<R> {
    reader: R,
    line: Vec<u8>,
}

impl<R: BufRead> CandumpReader<R> {
    /// Reads from `reader`.
    pub fn new(reader: R) -> Self {
        Self {
            reader,
            line: Vec::with_capacity(64),
        }
    }
}

impl<R: BufRead> Iterator for CandumpReader<R> {
    type Item = Result<Record, BusError>;

    fn next(&mut self) -> Option<Self::Item> {
        loop {
            // A whole line in the reader's buffer is parsed where it lies: a log of millions of
            // lines costs no copy each (`drivegen trace`, issue 33). A line across the buffer's
            // end, a long one or the last one is read below as before.
            match self.reader.fill_buf() {
                Ok(buf) => {
                    let window = &buf[..buf.len().min(MAX_LINE + 1)];
                    // A well-formed line is parsed as it is found: its end is where its frame
                    // ends, no search for the newline first.
                    if let Some((record, taken)) = parse_line_at(window) {
                        self.reader.consume(taken);
                        return Some(Ok(record));
                    }
                    // memchr: searched byte by byte, the newline took 12 % of `drivegen trace`'s time.
                    if let Some(newline) = memchr::memchr(b'\n', window) {
                        let parsed = parse_line(&buf[..newline]);
                        self.reader.consume(newline + 1);
                        match parsed {
                            Ok(None) => continue,
                            Ok(Some(record)) => return Some(Ok(record)),
                            Err(e) => return Some(Err(e)),
                        }
                    }
                }
                Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
                Err(e) => return Some(Err(BusError::Io(e.kind()))),
            }
            self.line.clear();
            match read_line(&mut self.reader, &mut self.line) {
                Ok(LineRead::End) => return None,
                Ok(LineRead::TooLong) => {
                    return Some(Err(BusError::Frame("candump: line too long")))
                }
                Ok(LineRead::Line) => match parse_line(&self.line) {
                    Ok(None) => continue,
                    Ok(Some(record)) => return Some(Ok(record)),
                    Err(e) => return Some(Err(e)),
                },
                Err(e) => return Some(Err(BusError::Io(e.kind()))),
            }
        }
    }
}

/// Frames buffered between the reader thread and [`CanBus::recv`]; a full buffer makes the
/// thread wait rather than drop frames.
const QUEUE: usize = 4096;

/// A [`CanBus`] over candump text: frames are written as compact lines to `W`, and read from any
/// `Read` stream by a background thread (pipes have no read timeout of their own).
#[derive(Debug)]
pub struct CandumpBus<W: Write> {
    writer: W,
    rx: Receiver<Record>,
    malformed: Arc<AtomicUsize>,
    reader: Option<JoinHandle<io::Result<()>>>,
    line: Vec<u8>,
}

impl<W: Write> CandumpBus<W> {
    /// Reads frames from `reader` and writes frames to `writer`. Lines that do not parse are
    /// skipped and counted ([`malformed_lines`](Self::malformed_lines)): a relay may print other
    /// text.
    pub fn new<R: Read + Send + 'static>(reader: R, writer: W) -> Self {
        let (tx, rx) = sync_channel(QUEUE);
        let malformed = Arc::new(AtomicUsize::new(0));
        let counter = Arc::clone(&malformed);
        let reader = std::thread::spawn(move || {
            for record in CandumpReader::new(BufReader::new(reader)) {
                match record {
                    Ok(record) => {
                        if tx.send(record).is_err() {
                            return Ok(()); // The bus was dropped.
                        }
                    }
                    Err(BusError::Io(kind)) => return Err(io::Error::from(kind)),
                    Err(_) => {
                        counter.fetch_add(1, Ordering::Relaxed);
                    }
                }
            }
            Ok(())
        });
        Self {
            writer,
            rx,
            malformed,
            reader: Some(reader),
            line: Vec::with_capacity(32),
        }
    }

    /// Lines skipped because they were not frames.
    pub fn malformed_lines(&self) -> usize {
        self.malformed.load(Ordering::Relaxed)
    }

    /// The next frame with its log timestamp, if any.
    pub fn recv_record(&mut self, timeout: Duration) -> Result<Option<Record>, BusError> {
        match self.rx.recv_timeout(timeout) {
            Ok(record) => Ok(Some(record)),
            Err(RecvTimeoutError::Timeout) => Ok(None),
            Err(RecvTimeoutError::Disconnected) => {
                // The stream ended; report how.
                let outcome = self.reader.take().map(JoinHandle::join);
                Err(match outcome {
                    Some(Ok(Err(e))) => BusError::Io(e.kind()),
                    _ => BusError::Io(io::ErrorKind::UnexpectedEof),
                })
            }
        }
    }

    /// The writer.
    pub fn writer_mut(&mut self) -> &mut W {
        &mut self.writer
    }
}

impl CandumpBus<ChildStdin> {
    /// A bus over a child process's stdio (spawned with piped stdin and stdout), e.g. a relay
    /// to another CAN stack. The child stays owned by the caller, who must stop it.
    pub fn from_child(child: &mut Child) -> Result<Self, BusError> {
        let (stdin, stdout) = piped(child.stdin.take(), child.stdout.take())?;
        Ok(Self::new(stdout, stdin))
    }
}

/// A child's stdin and stdout, each an error if it was not piped (or was taken already).
pub(crate) fn piped<I, O>(stdin: Option<I>, stdout: Option<O>) -> Result<(I, O), BusError> {
    let stdin = stdin.ok_or(BusError::Unsupported("child stdin is not piped"))?;
    let stdout = stdout.ok_or(BusError::Unsupported("child stdout is not piped"))?;
    Ok((stdin, stdout))
}

impl<W: Write> CanBus for CandumpBus<W> {
    fn send(&mut self, frame: &CanFrame) -> Result<(), BusError> {
        self.line.clear();
        format_frame(frame, &mut self.line);
        self.line.push(b'\n');
        self.writer
            .write_all(&self.line)
            .and_then(|()| self.writer.flush())
            .map_err(|e| BusError::Io(e.kind()))
    }

    fn recv(&mut self, timeout: Duration) -> Result<Option<CanFrame>, BusError> {
        Ok(self.recv_record(timeout)?.map(|record| record.frame))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(id: u16, data: &[u8]) -> CanFrame {
        CanFrame::new(id, data).unwrap()
    }

    #[test]
    fn compact_and_log_lines() {
        assert_eq!(
            parse_line(b"123#DEADBEEF\n").unwrap().unwrap().frame,
            frame(0x123, &[0xDE, 0xAD, 0xBE, 0xEF])
        );
        assert_eq!(
            parse_line(b"605#4000100000000000").unwrap().unwrap().frame,
            frame(0x605, &[0x40, 0, 0x10, 0, 0, 0, 0, 0])
        );
        assert_eq!(
            parse_line(b"123#").unwrap().unwrap().frame,
            frame(0x123, &[])
        );
        assert_eq!(
            parse_line(b"123#de.ad").unwrap().unwrap().frame,
            frame(0x123, &[0xDE, 0xAD])
        );
        assert_eq!(
            parse_line(b"123#R").unwrap().unwrap().frame,
            CanFrame::remote(0x123, 0).unwrap()
        );
        assert_eq!(
            parse_line(b"123#R8").unwrap().unwrap().frame,
            CanFrame::remote(0x123, 8).unwrap()
        );
        let record = parse_line(b"(1700000000.123456) can0 123#DEADBEEF")
            .unwrap()
            .unwrap();
        assert_eq!(record.timestamp_us, Some(1_700_000_000_123_456));
        assert_eq!(record.frame, frame(0x123, &[0xDE, 0xAD, 0xBE, 0xEF]));
        assert_eq!(
            parse_line(b"(1.5) vcan1 080#")
                .unwrap()
                .unwrap()
                .timestamp_us,
            Some(1_500_000)
        );
        assert_eq!(parse_line(b"  \n").unwrap(), None);
        assert_eq!(parse_line(b"# comment").unwrap(), None);
    }

    #[test]
    fn malformed_lines_are_typed_errors() {
        for line in [
            &b"123DEADBEEF"[..],
            b"12#00",
            b"1234#00",
            b"123#0",
            b"123#0G",
            b"123#000000000000000000",
            b"(17 can0 123#00",
            b"(abc) can0 123#00",
            b"800#00",
            b"123#R9",
            b"123#R8x",
        ] {
            assert!(
                matches!(parse_line(line), Err(BusError::Frame(_))),
                "{}",
                std::string::String::from_utf8_lossy(line)
            );
        }
        assert_eq!(
            parse_line(b"12345678#00"),
            Err(BusError::Unsupported("29-bit CAN identifiers"))
        );
        assert_eq!(
            parse_line(b"123##100"),
            Err(BusError::Unsupported("CAN FD frames"))
        );
    }

    /// Found by the `candump_line` fuzz target: a timestamp whose microseconds overflow u64
    /// once scaled (here `.4` is 400,000 µs) panicked with an arithmetic overflow.
    #[test]
    fn timestamps_past_u64_microseconds_are_malformed() {
        for line in [
            &b"(170000000022130.4) can0 585#00"[..],
            b"(18446744073709.551616) can0 123#00",
            b"(99999999999999999999.1) can0 123#00",
        ] {
            assert_eq!(
                parse_line(line),
                Err(BusError::Frame("candump: malformed timestamp")),
                "{}",
                std::string::String::from_utf8_lossy(line)
            );
        }
        let largest = parse_line(b"(18446744073709.551615) can0 123#00")
            .unwrap()
            .unwrap();
        assert_eq!(largest.timestamp_us, Some(u64::MAX));
    }

    /// Lines built from the bytes that matter to either parser (digits, hex, `#`, `.`, `R`,
    /// brackets, separators, other whitespace) and valid lines with one byte changed.
    fn random_lines(count: usize) -> Vec<Vec<u8>> {
        const BYTES: &[u8] = b"0123456789aFfG#.#.Rr()  \t\x0c\r\ncn";
        const VALID: &[&[u8]] = &[
            b"(1700000000.123456) can0 605#4000100000000000",
            b"(1.5) vcan1 080#",
            b"(1000000000.000001)  can0 123#DE.AD",
            b"(9999999999999.999999)\tcan0\t123#R8",
            b"7FF#0102030405060708",
            b"123#r",
        ];
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        let mut random = move |below: usize| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state % below as u64) as usize
        };
        (0..count)
            .map(|round| {
                let mut line = Vec::new();
                if round % 2 == 0 {
                    line.extend_from_slice(VALID[random(VALID.len())]);
                    let at = random(line.len());
                    line[at] = BYTES[random(BYTES.len())];
                } else {
                    for _ in 0..random(48) {
                        line.push(BYTES[random(BYTES.len())]);
                    }
                }
                line
            })
            .collect()
    }

    /// What the one pass takes it reads as the field parser does. The lines the pass gives up
    /// on are parsed by the field parser, so `parse_line` is the field parser's on every line.
    #[test]
    fn the_one_pass_reads_lines_as_the_field_parser() {
        let (mut taken, mut lines) = (0, 0);
        for line in random_lines(200_000) {
            let trimmed = line.trim_ascii();
            if trimmed.is_empty() || trimmed[0] == b'#' {
                continue;
            }
            lines += 1;
            if let Some(record) = parse_well_formed(trimmed) {
                taken += 1;
                assert_eq!(
                    parse_fields(trimmed),
                    Ok(record),
                    "{}",
                    std::string::String::from_utf8_lossy(&line)
                );
            }
        }
        // The pass must take the valid lines, and the comparison must have had some to check.
        assert!(parse_well_formed(b"(1700000000.123456) can0 605#4000100000000000").is_some());
        assert!(taken > lines / 20, "{taken} of {lines}");
    }

    /// The reader, which parses a well-formed line where it finds it and ends it where its
    /// frame ends, gives for a stream what `parse_line` gives for each of its lines.
    #[test]
    fn the_reader_reads_a_stream_line_by_line() {
        let lines = random_lines(20_000);
        let stream = lines.join(&b'\n');
        let by_line: Vec<_> = stream
            .split(|&b| b == b'\n')
            .filter_map(|line| parse_line(line).transpose())
            .collect();
        let read: Vec<_> = CandumpReader::new(&stream[..]).collect();
        assert_eq!(read, by_line);
        assert!(by_line.iter().filter(|r| r.is_ok()).count() > 1000);
    }

    #[test]
    fn format_round_trips() {
        for f in [
            frame(0x605, &[0x40, 0, 0x10, 0, 0, 0, 0, 0]),
            frame(0x7FF, &[]),
            CanFrame::remote(0x181, 0).unwrap(),
            CanFrame::remote(0x181, 8).unwrap(),
        ] {
            let mut line = Vec::new();
            format_frame(&f, &mut line);
            assert_eq!(parse_frame(&line).unwrap(), f);
        }
        let mut line = Vec::new();
        format_frame(&frame(0x00A, &[0xAB]), &mut line);
        assert_eq!(line, b"00A#AB");
    }

    #[test]
    fn bus_over_a_replayed_log_skips_noise_and_reports_the_end() {
        let log = b"(0.000001) can0 705#00\nnot a frame\n185#0102\n";
        let mut bus = CandumpBus::new(&log[..], Vec::new());
        let timeout = Duration::from_secs(1);
        assert_eq!(bus.recv(timeout).unwrap(), Some(frame(0x705, &[0])));
        assert_eq!(bus.recv(timeout).unwrap(), Some(frame(0x185, &[1, 2])));
        assert_eq!(
            bus.recv(timeout),
            Err(BusError::Io(io::ErrorKind::UnexpectedEof))
        );
        assert_eq!(bus.malformed_lines(), 1);
        bus.send(&frame(0x605, &[0x40, 0, 0x10, 0, 0, 0, 0, 0]))
            .unwrap();
        assert_eq!(bus.writer_mut().as_slice(), b"605#4000100000000000\n");
    }

    #[test]
    fn a_line_without_end_is_skipped_within_a_bounded_buffer() {
        let mut stream = std::vec![b'A'; 1 << 20];
        stream.extend_from_slice(b"\n123#00\n");
        let mut reader = CandumpReader::new(&stream[..]);
        assert_eq!(
            reader.next(),
            Some(Err(BusError::Frame("candump: line too long")))
        );
        assert!(
            reader.line.capacity() <= 2 * MAX_LINE,
            "{}",
            reader.line.capacity()
        );
        assert_eq!(reader.next().unwrap().unwrap().frame, frame(0x123, &[0]));
        assert_eq!(reader.next(), None);
    }

    /// A line is parsed in the reader's buffer when it lies there whole, and read by copying
    /// when it crosses the buffer's end: the records are the same for every buffer size.
    #[test]
    fn lines_across_the_readers_buffer_read_as_whole_lines() {
        let log = "(1700000000.000001) can0 705#00\n185#0102\nbad\n\n# c\n(1.5) can0 123#DEADBEEF";
        let expected: Vec<_> = CandumpReader::new(log.as_bytes()).collect();
        assert_eq!(expected.len(), 4);
        for capacity in 1..48 {
            let reader = BufReader::with_capacity(capacity, log.as_bytes());
            let records: Vec<_> = CandumpReader::new(reader).collect();
            assert_eq!(records, expected, "a buffer of {capacity} bytes");
        }
    }

    #[test]
    fn reader_iterates_and_reports_bad_lines() {
        let log = "123#00\n\nbad\n(1.000000) can0 456#R\n";
        let records: Vec<_> = CandumpReader::new(log.as_bytes()).collect();
        assert_eq!(records.len(), 3);
        assert!(records[1].is_err());
        assert_eq!(
            records[2].as_ref().unwrap().frame,
            CanFrame::remote(0x456, 0).unwrap()
        );
    }
}
