//! SDO client transfers as sans-I/O state machines.
//!
//! [`SdoClient`] starts a transfer; the caller then loops: send what
//! [`Transfer::poll_transmit`] yields, feed every received frame to [`Transfer::handle`] (frames
//! of other COB-IDs or of other objects are ignored), and call [`Transfer::handle_timeout`] once
//! [`Transfer::deadline`] has passed. When the client gives up (timeout, toggle or sequence
//! error, unexpected command) it queues an abort frame for the server before reporting failure,
//! so the caller must drain [`Transfer::poll_transmit`] after a failure too.

pub use drivebus_model::canopen::abort;
#[cfg(feature = "sdo-block")]
pub mod block;
pub mod client;
#[cfg(all(feature = "canopen", feature = "server"))]
pub mod server;
#[cfg(all(test, feature = "canopen"))]
mod tests;

use core::time::Duration;

pub use abort::AbortCode;
pub use client::{Download, SdoClient, Upload};

use super::frame::CanFrame;
use crate::error::BusError;

/// Client command specifiers (bits 5..7 of byte 0 of a request).
pub(crate) mod ccs {
    pub const DOWNLOAD_SEGMENT: u8 = 0;
    pub const INITIATE_DOWNLOAD: u8 = 1;
    pub const INITIATE_UPLOAD: u8 = 2;
    pub const UPLOAD_SEGMENT: u8 = 3;
    pub const ABORT: u8 = 4;
    #[cfg(feature = "sdo-block")]
    pub const BLOCK_UPLOAD: u8 = 5;
    #[cfg(feature = "sdo-block")]
    pub const BLOCK_DOWNLOAD: u8 = 6;
}

/// Server command specifiers (bits 5..7 of byte 0 of a response).
pub(crate) mod scs {
    pub const UPLOAD_SEGMENT: u8 = 0;
    pub const DOWNLOAD_SEGMENT: u8 = 1;
    pub const INITIATE_UPLOAD: u8 = 2;
    pub const INITIATE_DOWNLOAD: u8 = 3;
    pub const ABORT: u8 = 4;
    #[cfg(feature = "sdo-block")]
    pub const BLOCK_DOWNLOAD: u8 = 5;
    #[cfg(feature = "sdo-block")]
    pub const BLOCK_UPLOAD: u8 = 6;
}

/// Data length of every SDO frame, request or response (Lafert Smartris user guide, lines
/// 4223-4233: "SDO (Write command) ... DLC 8"; Kinco FD manual, lines 2628-2640: both directions
/// DLC 8).
pub const FRAME_LEN: u8 = 8;

/// Whether `frame` is long enough to be an SDO frame. A shorter one is a frame cut short, and
/// its missing bytes, read as the zeros [`CanFrame::padded`] supplies, would be taken for data:
/// client and server ignore it, as any other frame that is not theirs.
pub(crate) const fn is_full_length(frame: &CanFrame) -> bool {
    frame.dlc() == FRAME_LEN
}

/// The command specifier of an SDO frame.
pub(crate) const fn specifier(data: &[u8; 8]) -> u8 {
    data[0] >> 5
}

/// A frame that carries only its command byte.
pub(crate) const fn command_only(command: u8) -> [u8; 8] {
    [command, 0, 0, 0, 0, 0, 0, 0]
}

/// Toggle bit of a segment command byte.
pub(crate) const TOGGLE: u8 = 0x10;

/// How an SDO transfer failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SdoError {
    /// The server aborted the transfer with this code.
    Server(AbortCode),
    /// The client aborted the transfer with this code (and sent the abort to the server):
    /// timeout, toggle or sequence error, unexpected command, CRC error, buffer too small.
    Client(AbortCode),
}

impl SdoError {
    /// The abort code, whoever sent it.
    pub const fn code(self) -> AbortCode {
        match self {
            Self::Server(code) | Self::Client(code) => code,
        }
    }

    /// The runtime error for a transfer of `index:subindex`: a timeout stays a timeout, every
    /// other abort keeps its code and who sent it.
    pub fn into_bus_error(self, index: u16, subindex: u8) -> BusError {
        match self {
            Self::Client(AbortCode::ProtocolTimedOut) => BusError::Timeout,
            Self::Server(code) => BusError::SdoAbort {
                index,
                subindex,
                code,
            },
            Self::Client(code) => BusError::SdoClientAbort {
                index,
                subindex,
                code,
            },
        }
    }
}

/// The outcome of feeding a transfer a frame or the time.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Progress {
    /// Not finished; keep sending and receiving.
    Pending,
    /// Finished: the number of bytes uploaded into the buffer, or downloaded.
    Done(usize),
    /// Failed; any abort frame is queued in [`Transfer::poll_transmit`].
    Failed(SdoError),
}

/// The interface every SDO client transfer offers its driver.
pub trait Transfer {
    /// The next frame to send, if any.
    fn poll_transmit(&mut self) -> Option<CanFrame>;
    /// Feeds a received frame (of any COB-ID; foreign frames are ignored).
    fn handle(&mut self, frame: &CanFrame, now: Duration) -> Progress;
    /// Aborts the transfer if its deadline has passed at `now`.
    fn handle_timeout(&mut self, now: Duration) -> Progress;
    /// When the server must have answered by; `None` once the transfer has finished.
    fn deadline(&self) -> Option<Duration>;
    /// The object this transfer moves.
    fn object(&self) -> (u16, u8);
    /// The COB-ID the server answers on; frames with other ids are not this transfer's.
    fn response_cob(&self) -> u16;
    /// The frame that aborts this transfer with `code`, for a driver that gives the transfer up
    /// on its own (an async driver whose future was dropped); `None` once it has finished, or
    /// when the transfer cannot say (the default).
    fn abort_frame(&self, code: AbortCode) -> Option<CanFrame> {
        let _ = code;
        None
    }
}

/// The connection state every transfer shares: COB-IDs, multiplexer, deadline, outgoing frame.
#[derive(Debug, Clone)]
pub(crate) struct Channel {
    request_cob: u16,
    response_cob: u16,
    pub(crate) index: u16,
    pub(crate) subindex: u8,
    timeout: Duration,
    deadline: Duration,
    outbox: Option<CanFrame>,
    finished: bool,
}

impl Channel {
    pub(crate) fn new(client: &SdoClient, index: u16, subindex: u8, now: Duration) -> Self {
        Self {
            request_cob: client.request_cob,
            response_cob: client.response_cob,
            index,
            subindex,
            timeout: client.timeout,
            deadline: now + client.timeout,
            outbox: None,
            finished: false,
        }
    }

    /// Bytes 1..4 of an initiate or abort frame: index (LE) and subindex.
    pub(crate) fn mux(&self) -> [u8; 3] {
        let [lo, hi] = self.index.to_le_bytes();
        [lo, hi, self.subindex]
    }

    pub(crate) fn mux_matches(&self, data: &[u8; 8]) -> bool {
        data[1..4] == self.mux()
    }

    /// Whether a response to a transfer waiting for its initiate answer is stale, the late answer
    /// to an earlier transfer that timed out, or another client's: an initiate answer, upload or
    /// download, for another object. It is passed over rather than taken for a protocol error, so
    /// a stop written after a timed-out read still goes through. (The wrong kind of answer for
    /// this very object stays an error: nothing tells it from a confused server.)
    pub(crate) fn is_stale_initiate(&self, data: &[u8; 8]) -> bool {
        let initiate = matches!(
            specifier(data),
            scs::INITIATE_UPLOAD | scs::INITIATE_DOWNLOAD
        );
        initiate && !self.mux_matches(data)
    }

    /// A request carrying the multiplexer: `command`, index, subindex, then `tail`.
    pub(crate) fn initiate(&self, command: u8, tail: [u8; 4]) -> [u8; 8] {
        let [a, b, c] = self.mux();
        [command, a, b, c, tail[0], tail[1], tail[2], tail[3]]
    }

    /// Queues a request and restarts the response timer.
    pub(crate) fn send(&mut self, data: [u8; 8], now: Duration) {
        self.outbox = Some(CanFrame::full(self.request_cob, data));
        self.touch(now);
    }

    #[cfg(feature = "sdo-block")]
    /// A request frame, without touching the timer (block segments go out in a burst).
    pub(crate) fn frame(&self, data: [u8; 8]) -> CanFrame {
        CanFrame::full(self.request_cob, data)
    }

    /// Restarts the response timer (a valid frame arrived).
    pub(crate) fn touch(&mut self, now: Duration) {
        self.deadline = now + self.timeout;
    }

    pub(crate) fn take_outbox(&mut self) -> Option<CanFrame> {
        self.outbox.take()
    }

    /// The payload of `frame` if it is an SDO response of this channel and the transfer is live.
    /// A server abort for this object finishes the transfer and is returned as `Err`.
    pub(crate) fn accept(&mut self, frame: &CanFrame) -> Result<Option<[u8; 8]>, Progress> {
        if self.finished
            || frame.id() != self.response_cob
            || frame.is_remote()
            || !is_full_length(frame)
        {
            return Ok(None);
        }
        let data = frame.padded();
        // Exactly 0x80: block segments 0x81..=0x9F share the abort's command specifier.
        if data[0] == scs::ABORT << 5 {
            if !self.mux_matches(&data) {
                return Ok(None);
            }
            self.finished = true;
            let code = u32::from_le_bytes([data[4], data[5], data[6], data[7]]);
            return Err(Progress::Failed(SdoError::Server(AbortCode::from_u32(
                code,
            ))));
        }
        Ok(Some(data))
    }

    /// The frame that aborts this channel's transfer with `code`; `None` once it has finished.
    pub(crate) fn abort_frame(&self, code: AbortCode) -> Option<CanFrame> {
        (!self.finished).then(|| self.abort_request(code))
    }

    fn abort_request(&self, code: AbortCode) -> CanFrame {
        let abort = self.initiate(ccs::ABORT << 5, code.code().to_le_bytes());
        CanFrame::full(self.request_cob, abort)
    }

    /// Gives up: queues an abort frame for the server and reports the failure.
    pub(crate) fn abort(&mut self, code: AbortCode) -> Progress {
        self.outbox = Some(self.abort_request(code));
        self.finished = true;
        Progress::Failed(SdoError::Client(code))
    }

    pub(crate) fn done(&mut self, len: usize) -> Progress {
        self.finished = true;
        Progress::Done(len)
    }

    pub(crate) fn handle_timeout(&mut self, now: Duration) -> Progress {
        if !self.finished && now >= self.deadline {
            self.abort(AbortCode::ProtocolTimedOut)
        } else {
            Progress::Pending
        }
    }

    pub(crate) fn response_cob(&self) -> u16 {
        self.response_cob
    }

    pub(crate) fn deadline(&self) -> Option<Duration> {
        (!self.finished).then_some(self.deadline)
    }
}
