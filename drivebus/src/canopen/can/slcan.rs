//! SLCAN (Lawicel ASCII) adapters over any byte stream: a serial port or TCP.
//!
//! Frames are `tIIILDD..\r` (data) and `rIIIL\r` (remote); commands are `Sn\r` (bit rate),
//! `O\r` (open), `C\r` (close). The adapter answers commands with `\r` (ok) or BEL (error), and
//! may confirm transmissions with `z\r`; those answers are consumed while receiving.
//!
//! The stream's own read timeout bounds how late [`CanBus::recv`] returns after its deadline:
//! [`SlcanBus::tcp`] sets a short one; for a serial port (e.g. a `serialport::SerialPort`, which
//! is `Read + Write`) configure it when opening the port.

use core::time::Duration;
use std::io::{self, Read, Write};
use std::net::{TcpStream, ToSocketAddrs};
use std::time::Instant;
use std::vec::Vec;

use super::candump::{format_frame, parse_frame};
use super::slcan_decoder::{Answer, SlcanDecoder};
use super::{CanBus, CanEvent, OpenError};
use crate::canopen::frame::CanFrame;
use crate::error::BusError;

/// The standard SLCAN bit rates (`S0`..`S8`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Bitrate {
    /// 10 kbit/s.
    K10,
    /// 20 kbit/s.
    K20,
    /// 50 kbit/s.
    K50,
    /// 100 kbit/s.
    K100,
    /// 125 kbit/s.
    K125,
    /// 250 kbit/s.
    K250,
    /// 500 kbit/s.
    K500,
    /// 800 kbit/s.
    K800,
    /// 1 Mbit/s.
    M1,
}

impl Bitrate {
    /// Every bit rate, in the order of their `Sn` codes.
    pub const ALL: [Bitrate; 9] = [
        Self::K10,
        Self::K20,
        Self::K50,
        Self::K100,
        Self::K125,
        Self::K250,
        Self::K500,
        Self::K800,
        Self::M1,
    ];

    /// The `Sn` command digit.
    pub const fn code(self) -> u8 {
        self as u8
    }

    /// The bit rate of an `Sn` command digit (0 to 8).
    pub fn from_code(code: u8) -> Option<Self> {
        Self::ALL.get(usize::from(code)).copied()
    }

    /// Bits per second.
    pub const fn bits_per_second(self) -> u32 {
        match self {
            Self::K10 => 10_000,
            Self::K20 => 20_000,
            Self::K50 => 50_000,
            Self::K100 => 100_000,
            Self::K125 => 125_000,
            Self::K250 => 250_000,
            Self::K500 => 500_000,
            Self::K800 => 800_000,
            Self::M1 => 1_000_000,
        }
    }

    /// The standard bit rate of exactly `bits` per second.
    pub fn from_bits_per_second(bits: u32) -> Option<Self> {
        Self::ALL
            .into_iter()
            .find(|rate| rate.bits_per_second() == bits)
    }
}

/// How long one blocking read of a TCP stream may take; bounds the lateness of `recv`.
const POLL: Duration = Duration::from_millis(5);
/// How long [`SlcanBus::start`] waits for each answer of the opening sequence by default.
pub const ANSWER_TIMEOUT: Duration = Duration::from_millis(500);

/// A [`CanBus`] over an SLCAN adapter.
#[derive(Debug)]
pub struct SlcanBus<S> {
    stream: S,
    decoder: SlcanDecoder,
    out: Vec<u8>,
}

impl SlcanBus<TcpStream> {
    /// Connects to an SLCAN-over-TCP adapter or gateway.
    pub fn connect<A: ToSocketAddrs>(address: A) -> Result<Self, BusError> {
        let stream = TcpStream::connect(address).map_err(|e| BusError::Io(e.kind()))?;
        Self::tcp(stream)
    }

    /// Uses a connected TCP stream.
    pub fn tcp(stream: TcpStream) -> Result<Self, BusError> {
        stream
            .set_read_timeout(Some(POLL))
            .map_err(|e| BusError::Io(e.kind()))?;
        stream
            .set_nodelay(true)
            .map_err(|e| BusError::Io(e.kind()))?;
        Ok(Self::new(stream))
    }
}

/// A serial port as the byte stream of an SLCAN adapter.
#[cfg(feature = "serial")]
pub type SerialPort = std::boxed::Box<dyn serialport::SerialPort>;

#[cfg(feature = "serial")]
impl SlcanBus<SerialPort> {
    /// Opens a serial SLCAN adapter (`/dev/ttyACM0`) at `baud` (8N1, no flow control; a USB CDC
    /// adapter such as a CANable ignores the speed, an adapter behind a UART needs the right
    /// one). Call [`SlcanBus::start`] next.
    pub fn serial(path: &str, baud: u32) -> Result<Self, OpenError> {
        let port = serialport::new(path, baud)
            .data_bits(serialport::DataBits::Eight)
            .parity(serialport::Parity::None)
            .stop_bits(serialport::StopBits::One)
            .flow_control(serialport::FlowControl::None)
            .timeout(POLL)
            .open()
            .map_err(|e| {
                let kind = match e.kind {
                    serialport::ErrorKind::Io(kind) => kind,
                    serialport::ErrorKind::NoDevice => io::ErrorKind::NotFound,
                    _ => io::ErrorKind::Other,
                };
                match kind {
                    io::ErrorKind::NotFound => OpenError::NoDevice { path: path.into() },
                    io::ErrorKind::PermissionDenied => {
                        OpenError::PermissionDenied { what: path.into() }
                    }
                    kind => OpenError::Io(kind),
                }
            })?;
        Ok(Self::new(port))
    }
}

impl<S: Read + Write> SlcanBus<S> {
    /// Wraps a stream (configure its read timeout first; see the module documentation).
    pub fn new(stream: S) -> Self {
        Self {
            stream,
            decoder: SlcanDecoder::default(),
            out: Vec::with_capacity(32),
        }
    }

    fn command(&mut self, command: &[u8]) -> Result<(), BusError> {
        self.stream
            .write_all(command)
            .and_then(|()| self.stream.flush())
            .map_err(|e| BusError::Io(e.kind()))
    }

    /// Closes the channel, sets the bit rate and opens it (`C`, `Sn`, `O`) without waiting for
    /// answers: for gateways that do not answer commands. The acknowledgements of an adapter
    /// that does are consumed by later reads. [`SlcanBus::start`] checks them.
    pub fn open(&mut self, bitrate: Bitrate) -> Result<(), BusError> {
        self.command(b"C\r")?;
        self.command(&[b'S', b'0' + bitrate.code(), b'\r'])?;
        self.command(b"O\r")
    }

    /// Closes the channel, sets the bit rate and opens it, checking that the adapter answers
    /// `Sn` and `O` with CR within `answer_timeout` each (the answer to `C` is not checked: an
    /// adapter whose channel is already closed may refuse it). Frames that arrive meanwhile
    /// are kept for [`CanBus::recv`].
    pub fn start(&mut self, bitrate: Bitrate, answer_timeout: Duration) -> Result<(), OpenError> {
        const RATES: [&str; 9] = ["S0", "S1", "S2", "S3", "S4", "S5", "S6", "S7", "S8"];
        let io = |e: BusError| match e {
            BusError::Io(io::ErrorKind::PermissionDenied) => OpenError::PermissionDenied {
                what: "the SLCAN adapter".into(),
            },
            BusError::Io(kind) => OpenError::Io(kind),
            _ => OpenError::Io(io::ErrorKind::Other),
        };
        self.command(b"C\r").map_err(io)?;
        // An adapter in an unknown state: its answer to C (CR or BEL) is awaited but not judged.
        let _ = self.answer(answer_timeout, "C");
        let rate = RATES[usize::from(bitrate.code())];
        self.command(&[b'S', b'0' + bitrate.code(), b'\r'])
            .map_err(io)?;
        self.answer(answer_timeout, rate)?;
        self.command(b"O\r").map_err(io)?;
        self.answer(answer_timeout, "O")
    }

    /// Waits for the answer to `command`: CR (ok) or BEL (refused). Frame lines before it stay
    /// in the buffer.
    fn answer(&mut self, timeout: Duration, command: &'static str) -> Result<(), OpenError> {
        let deadline = Instant::now() + timeout;
        let mut chunk = [0u8; 64];
        loop {
            match self.decoder.take_answer() {
                Some(Answer::Accepted) => return Ok(()),
                Some(Answer::Refused) => return Err(OpenError::Refused { command }),
                None => {}
            }
            if Instant::now() >= deadline {
                return Err(OpenError::NoAnswer { command });
            }
            match self.stream.read(&mut chunk) {
                Ok(0) => return Err(OpenError::Io(io::ErrorKind::UnexpectedEof)),
                Ok(n) => self.decoder.push(&chunk[..n]),
                Err(e) if is_poll_timeout(e.kind()) => {}
                Err(e) => return Err(OpenError::Io(e.kind())),
            }
        }
    }

    /// Closes the channel (`C`).
    pub fn close(&mut self) -> Result<(), BusError> {
        self.command(b"C\r")
    }

    /// Commands the adapter refused (BEL answers) so far.
    pub fn refused_commands(&self) -> usize {
        self.decoder.refused()
    }

    /// The stream.
    pub fn stream_mut(&mut self) -> &mut S {
        &mut self.stream
    }

    /// Reads more bytes into the buffer; `false` when the read timed out.
    fn fill(&mut self) -> Result<bool, BusError> {
        let mut chunk = [0u8; 256];
        match self.stream.read(&mut chunk) {
            Ok(0) => Err(BusError::Io(io::ErrorKind::UnexpectedEof)),
            Ok(n) => {
                self.decoder.push(&chunk[..n]);
                Ok(true)
            }
            Err(e) if is_poll_timeout(e.kind()) => Ok(false),
            Err(e) => Err(BusError::Io(e.kind())),
        }
    }
}

fn is_poll_timeout(kind: io::ErrorKind) -> bool {
    matches!(
        kind,
        io::ErrorKind::WouldBlock | io::ErrorKind::TimedOut | io::ErrorKind::Interrupted
    )
}

/// One SLCAN line, decoded.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum SlcanLine {
    /// A standard-identifier frame, with the adapter's millisecond timestamp if it sends them
    /// (`Z1` mode: four hex digits after the data).
    Frame {
        /// The frame.
        frame: CanFrame,
        /// Milliseconds, 0 to 59 999, wrapping.
        timestamp: Option<u16>,
    },
    /// The answer to `F`: the status flags (`Fxx`).
    Status(u8),
    /// An acknowledgement (`z`, `Z`, an empty line), a version answer or an extended frame,
    /// which a CANopen bus does not use.
    Ignored,
}

/// Decodes an SLCAN line (without its `\r`): a frame, a status answer, or something to ignore;
/// a line that is none of those is a [`BusError::Frame`] saying why.
pub fn parse_line(line: &[u8]) -> Result<SlcanLine, BusError> {
    let Some((&kind, rest)) = line.split_first() else {
        return Ok(SlcanLine::Ignored);
    };
    match kind {
        b't' | b'r' => {}
        b'T' | b'R' => {
            // Extended frames: checked for shape, then ignored.
            let digits = rest
                .get(..9)
                .ok_or(BusError::Frame("SLCAN: truncated frame"))?;
            if !digits.iter().all(u8::is_ascii_hexdigit) {
                return Err(BusError::Frame("SLCAN: identifier is not hex digits"));
            }
            return Ok(SlcanLine::Ignored);
        }
        b'F' => {
            return match rest {
                [hi, lo] => hex_byte(*hi, *lo)
                    .map(SlcanLine::Status)
                    .ok_or(BusError::Frame("SLCAN: status is not hex digits")),
                _ => Err(BusError::Frame("SLCAN: status is not two hex digits")),
            }
        }
        // Transmission acknowledgements, version and serial-number answers.
        b'z' | b'Z' | b'V' | b'v' | b'N' if rest.len() <= 8 => return Ok(SlcanLine::Ignored),
        _ => return Err(BusError::Frame("SLCAN: not a frame or answer")),
    }
    if rest.len() < 4 {
        return Err(BusError::Frame("SLCAN: truncated frame"));
    }
    if !rest[..3].iter().all(u8::is_ascii_hexdigit) {
        return Err(BusError::Frame("SLCAN: identifier is not hex digits"));
    }
    let len = rest[3].wrapping_sub(b'0');
    if len > 8 {
        return Err(BusError::Frame("SLCAN: bad length digit"));
    }
    // Rebuild the candump form ("III#DD.." / "III#RL") and reuse its parser.
    let mut text = Vec::with_capacity(24);
    text.extend_from_slice(&rest[..3]);
    text.push(b'#');
    let tail = if kind == b'r' {
        text.extend_from_slice(&[b'R', rest[3]]);
        &rest[4..]
    } else {
        let digits = 2 * len as usize;
        match rest.get(4..4 + digits) {
            // Only hex digits: the candump parser also skips `.` separators, which would let a
            // line carry fewer bytes than its length digit says.
            Some(data) if !data.iter().all(u8::is_ascii_hexdigit) => {
                return Err(BusError::Frame("SLCAN: data is not hex digits"))
            }
            Some(data) => text.extend_from_slice(data),
            None => return Err(BusError::Frame("SLCAN: truncated data")),
        }
        &rest[4 + digits..]
    };
    let timestamp = match tail {
        [] => None,
        [a, b, c, d] => match (hex_byte(*a, *b), hex_byte(*c, *d)) {
            (Some(hi), Some(lo)) => Some(u16::from_be_bytes([hi, lo])),
            _ => return Err(BusError::Frame("SLCAN: timestamp is not hex digits")),
        },
        _ => return Err(BusError::Frame("SLCAN: trailing characters after the data")),
    };
    Ok(SlcanLine::Frame {
        frame: parse_frame(&text)?,
        timestamp,
    })
}

fn hex_byte(hi: u8, lo: u8) -> Option<u8> {
    let digit = |c: u8| (c as char).to_digit(16).map(|d| d as u8);
    Some(digit(hi)? << 4 | digit(lo)?)
}

/// Decodes an SLCAN line: `Some` for standard frames (or errors), `None` for acknowledgements,
/// answers and extended frames, which a CANopen bus does not use. The timestamp, if any, is
/// dropped; [`parse_line`] keeps it.
pub fn decode_line(line: &[u8]) -> Option<Result<CanFrame, BusError>> {
    match parse_line(line) {
        Ok(SlcanLine::Frame { frame, .. }) => Some(Ok(frame)),
        Ok(_) => None,
        Err(e) => Some(Err(e)),
    }
}

/// Encodes a frame as an SLCAN line including the trailing `\r`.
pub fn encode_frame(frame: &CanFrame, out: &mut Vec<u8>) {
    // The candump form differs only in the prefix letter, the '#' and the length digit.
    let mut compact = Vec::with_capacity(24);
    format_frame(frame, &mut compact);
    out.push(if frame.is_remote() { b'r' } else { b't' });
    out.extend_from_slice(&compact[..3]);
    out.push(b'0' + frame.dlc());
    if !frame.is_remote() {
        out.extend_from_slice(&compact[4..]);
    }
    out.push(b'\r');
}

impl<S: Read + Write> CanBus for SlcanBus<S> {
    fn send(&mut self, frame: &CanFrame) -> Result<(), BusError> {
        self.out.clear();
        encode_frame(frame, &mut self.out);
        let line = core::mem::take(&mut self.out);
        let result = self.command(&line);
        self.out = line;
        result
    }

    /// The next frame; noise, malformed lines, status reports and refusals are skipped
    /// ([`CanBus::recv_event`] reports them).
    fn recv(&mut self, timeout: Duration) -> Result<Option<CanFrame>, BusError> {
        let deadline = Instant::now() + timeout;
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            match self.recv_event(left)? {
                None => return Ok(None),
                Some(CanEvent::Frame { frame, .. }) => return Ok(Some(frame)),
                Some(_) => {}
            }
        }
    }

    fn recv_event(&mut self, timeout: Duration) -> Result<Option<CanEvent>, BusError> {
        let deadline = Instant::now() + timeout;
        loop {
            if let Some(event) = self.decoder.next_event() {
                return event.map(Some);
            }
            if Instant::now() >= deadline {
                return Ok(None);
            }
            self.fill()?;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::canopen::can::Timestamp;
    use std::io::Cursor;

    /// A stream whose reads come from a script and whose writes are recorded.
    struct Script {
        input: Cursor<Vec<u8>>,
        written: Vec<u8>,
    }

    impl Read for Script {
        fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
            match self.input.read(buf)? {
                0 => Err(io::ErrorKind::WouldBlock.into()),
                n => Ok(n),
            }
        }
    }

    impl Write for Script {
        fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
            self.written.extend_from_slice(buf);
            Ok(buf.len())
        }
        fn flush(&mut self) -> io::Result<()> {
            Ok(())
        }
    }

    fn bus(input: &[u8]) -> SlcanBus<Script> {
        SlcanBus::new(Script {
            input: Cursor::new(input.to_vec()),
            written: Vec::new(),
        })
    }

    #[test]
    fn encodes_frames_and_commands() {
        let mut bus = bus(b"");
        bus.open(Bitrate::K500).unwrap();
        bus.send(&CanFrame::new(0x123, &[0xDE, 0xAD, 0xBE, 0xEF]).unwrap())
            .unwrap();
        bus.send(&CanFrame::remote(0x701, 1).unwrap()).unwrap();
        bus.send(&CanFrame::new(0x080, &[]).unwrap()).unwrap();
        bus.close().unwrap();
        assert_eq!(
            bus.stream_mut().written,
            b"C\rS6\rO\rt1234DEADBEEF\rr7011\rt0800\rC\r"
        );
    }

    #[test]
    fn decodes_frames_skipping_acks_commands_and_extended_frames() {
        let input = b"\r\rz\rT123456782AABB\rt1232AABB\r\x07r7011\rt0801FF1234\rO\r";
        let mut bus = bus(input);
        let t = Duration::from_millis(50);
        assert_eq!(
            bus.recv(t).unwrap(),
            Some(CanFrame::new(0x123, &[0xAA, 0xBB]).unwrap())
        );
        assert_eq!(
            bus.recv(t).unwrap(),
            Some(CanFrame::remote(0x701, 1).unwrap())
        );
        assert_eq!(
            bus.recv(t).unwrap(),
            Some(CanFrame::new(0x080, &[0xFF]).unwrap()),
            "timestamp dropped"
        );
        assert_eq!(bus.recv(t).unwrap(), None);
        assert_eq!(bus.refused_commands(), 1);
    }

    #[test]
    fn start_checks_the_answers_to_the_opening_sequence() {
        let t = Duration::from_millis(20);
        // C refused (channel was closed), S6 and O accepted; a frame before the answers is kept.
        let mut ok = bus(b"t1230\r\x07\r\r");
        ok.start(Bitrate::K500, t).unwrap();
        assert_eq!(ok.stream_mut().written, b"C\rS6\rO\r");
        assert_eq!(
            ok.recv(t).unwrap(),
            Some(CanFrame::new(0x123, &[]).unwrap())
        );
        let mut refused = bus(b"\r\r\x07");
        assert_eq!(
            refused.start(Bitrate::M1, t),
            Err(OpenError::Refused { command: "O" })
        );
        let mut silent = bus(b"");
        assert_eq!(
            silent.start(Bitrate::K125, t),
            Err(OpenError::NoAnswer { command: "S4" })
        );
    }

    #[test]
    fn adapter_timestamps_status_noise_and_refusals_are_events() {
        let input = b"t1232AABB1A2B\rF24\r\x01\x02junk\r\x07r7011EA5F\rt1230XYZ\r";
        let mut bus = bus(input);
        let t = Duration::from_millis(50);
        assert_eq!(
            bus.recv_event(t).unwrap(),
            Some(CanEvent::Frame {
                frame: CanFrame::new(0x123, &[0xAA, 0xBB]).unwrap(),
                timestamp: Some(Timestamp::AdapterMillis(0x1A2B)),
            })
        );
        let Some(CanEvent::Error { report, .. }) = bus.recv_event(t).unwrap() else {
            panic!("status not reported");
        };
        assert_eq!(report.state, Some(super::super::BusState::ErrorPassive));
        assert!(matches!(
            bus.recv_event(t).unwrap(),
            Some(CanEvent::Garbage { .. })
        ));
        assert_eq!(bus.recv_event(t).unwrap(), Some(CanEvent::Refused));
        assert_eq!(
            bus.recv_event(t).unwrap(),
            Some(CanEvent::Frame {
                frame: CanFrame::remote(0x701, 1).unwrap(),
                timestamp: Some(Timestamp::AdapterMillis(59_999)),
            })
        );
        assert_eq!(
            bus.recv_event(t).unwrap(),
            Some(CanEvent::Garbage {
                why: "SLCAN: trailing characters after the data"
            })
        );
        assert_eq!(bus.recv_event(t).unwrap(), None);
    }

    #[test]
    fn bitrates_convert() {
        for (code, rate) in Bitrate::ALL.into_iter().enumerate() {
            assert_eq!(Bitrate::from_code(code as u8), Some(rate));
            assert_eq!(rate.code(), code as u8);
            assert_eq!(
                Bitrate::from_bits_per_second(rate.bits_per_second()),
                Some(rate)
            );
        }
        assert_eq!(Bitrate::from_code(9), None);
        assert_eq!(Bitrate::from_bits_per_second(333_000), None);
    }

    #[test]
    fn malformed_lines_are_typed_errors_and_noise_is_dropped() {
        for line in [&b"t12"[..], b"t1239", b"t1232AA", b"tXYZ0"] {
            assert!(
                matches!(decode_line(line), Some(Err(BusError::Frame(_)))),
                "{line:?}"
            );
        }
        // Found by the `slcan_line` fuzz target: `.` in the data was skipped, so this line
        // decoded as a 6-byte frame although its length digit says 7.
        assert_eq!(
            decode_line(b"t0117909541.41.3A876"),
            Some(Err(BusError::Frame("SLCAN: data is not hex digits")))
        );
        assert_eq!(
            decode_line(b"t12321.2."),
            Some(Err(BusError::Frame("SLCAN: data is not hex digits")))
        );
        let mut noisy = std::vec![b'x'; 200];
        noisy.extend_from_slice(b"\rt1230\r");
        let mut bus = bus(&noisy);
        assert_eq!(
            bus.recv(Duration::from_millis(50)).unwrap(),
            Some(CanFrame::new(0x123, &[]).unwrap())
        );
    }
}
