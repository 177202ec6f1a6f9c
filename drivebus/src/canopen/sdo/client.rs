//! Expedited and segmented SDO transfers (CiA 301 §7.2.4.3), and the client that starts them.

use core::time::Duration;

use super::{ccs, command_only, scs, specifier, AbortCode, Channel, Progress, Transfer, TOGGLE};
use crate::canopen::address::NodeId;
use crate::canopen::frame::{cob, CanFrame};

/// Bytes an expedited transfer carries.
const EXPEDITED_MAX: usize = 4;
/// Data bytes of one segment.
pub(crate) const SEGMENT_BYTES: usize = 7;

/// The client side of one SDO channel: whom to talk to and how long to wait for each answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SdoClient {
    pub(crate) request_cob: u16,
    pub(crate) response_cob: u16,
    pub(crate) timeout: Duration,
}

impl SdoClient {
    /// The default SDO channel of `node` (requests on 0x600 + id, responses on 0x580 + id).
    pub const fn new(node: NodeId, timeout: Duration) -> Self {
        Self {
            request_cob: cob::SDO_RX + node.0 as u16,
            response_cob: cob::SDO_TX + node.0 as u16,
            timeout,
        }
    }

    /// A channel with explicit COB-IDs (additional SDO servers, 0x1200.. objects).
    pub const fn with_cob_ids(request: u16, response: u16, timeout: Duration) -> Self {
        Self {
            request_cob: request,
            response_cob: response,
            timeout,
        }
    }

    /// Starts reading `index:subindex` into `buf` (expedited or segmented, as the server chooses).
    pub fn upload<'a>(
        &self,
        index: u16,
        subindex: u8,
        buf: &'a mut [u8],
        now: Duration,
    ) -> Upload<'a> {
        let mut ch = Channel::new(self, index, subindex, now);
        ch.send(ch.initiate(ccs::INITIATE_UPLOAD << 5, [0; 4]), now);
        Upload {
            ch,
            buf,
            state: UploadState::Initiate,
        }
    }

    /// Starts writing `data` to `index:subindex`: expedited for 1..=4 bytes, segmented otherwise.
    pub fn download<'a>(
        &self,
        index: u16,
        subindex: u8,
        data: &'a [u8],
        now: Duration,
    ) -> Download<'a> {
        let mut ch = Channel::new(self, index, subindex, now);
        let request = if (1..=EXPEDITED_MAX).contains(&data.len()) {
            // e=1, s=1, n = bytes that hold no data.
            let n = (EXPEDITED_MAX - data.len()) as u8;
            let mut tail = [0; 4];
            tail[..data.len()].copy_from_slice(data);
            ch.initiate((ccs::INITIATE_DOWNLOAD << 5) | (n << 2) | 0b11, tail)
        } else {
            ch.initiate((ccs::INITIATE_DOWNLOAD << 5) | 0b01, size_bytes(data.len()))
        };
        ch.send(request, now);
        Download {
            ch,
            data,
            state: DownloadState::Initiate,
        }
    }
}

/// A transfer size as the 4 little-endian bytes of an initiate frame.
pub(crate) fn size_bytes(len: usize) -> [u8; 4] {
    (len as u32).to_le_bytes()
}

/// The 32-bit size in bytes 4..8 of an initiate frame.
pub(crate) fn read_size(data: &[u8; 8]) -> usize {
    u32::from_le_bytes([data[4], data[5], data[6], data[7]]) as usize
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum UploadState {
    Initiate,
    Segment {
        toggle: u8,
        received: usize,
        size: Option<usize>,
    },
    #[cfg(feature = "sdo-block")]
    Block(super::block::UploadBlock),
}

/// An SDO upload (read) in progress; the value lands in the caller's buffer.
#[derive(Debug)]
pub struct Upload<'a> {
    pub(crate) ch: Channel,
    pub(crate) buf: &'a mut [u8],
    pub(crate) state: UploadState,
}

impl Upload<'_> {
    /// Handles the answer to an initiate (or block initiate falling back to normal) request.
    pub(crate) fn on_initiate(&mut self, data: &[u8; 8], now: Duration) -> Progress {
        if specifier(data) != scs::INITIATE_UPLOAD {
            return self.ch.abort(AbortCode::InvalidCommandSpecifier);
        }
        let (expedited, sized) = (data[0] & 0b10 != 0, data[0] & 0b01 != 0);
        if expedited {
            let len = if sized {
                EXPEDITED_MAX - ((data[0] >> 2) & 0b11) as usize
            } else {
                EXPEDITED_MAX
            };
            return match self.buf.get_mut(..len) {
                Some(out) => {
                    out.copy_from_slice(&data[4..4 + len]);
                    self.ch.done(len)
                }
                None => self.ch.abort(AbortCode::OutOfMemory),
            };
        }
        let size = sized.then(|| read_size(data));
        if size.is_some_and(|size| size > self.buf.len()) {
            return self.ch.abort(AbortCode::OutOfMemory);
        }
        self.state = UploadState::Segment {
            toggle: 0,
            received: 0,
            size,
        };
        self.ch.send(command_only(ccs::UPLOAD_SEGMENT << 5), now);
        Progress::Pending
    }

    fn on_segment(&mut self, data: &[u8; 8], now: Duration) -> Progress {
        let UploadState::Segment {
            toggle,
            received,
            size,
        } = self.state
        else {
            return Progress::Pending;
        };
        if specifier(data) != scs::UPLOAD_SEGMENT {
            return self.ch.abort(AbortCode::InvalidCommandSpecifier);
        }
        if data[0] & TOGGLE != toggle {
            return self.ch.abort(AbortCode::ToggleBitNotAlternated);
        }
        let count = SEGMENT_BYTES - ((data[0] >> 1) & 0b111) as usize;
        let Some(out) = self.buf.get_mut(received..received + count) else {
            return self.ch.abort(AbortCode::OutOfMemory);
        };
        out.copy_from_slice(&data[1..1 + count]);
        let received = received + count;
        if data[0] & 1 != 0 {
            return match size {
                Some(size) if size != received => self.ch.abort(AbortCode::LengthMismatch),
                _ => self.ch.done(received),
            };
        }
        let toggle = toggle ^ TOGGLE;
        self.state = UploadState::Segment {
            toggle,
            received,
            size,
        };
        self.ch
            .send(command_only((ccs::UPLOAD_SEGMENT << 5) | toggle), now);
        Progress::Pending
    }
}

/// The `Transfer` methods every transfer answers from its channel alone.
macro_rules! channel_methods {
    () => {
        fn handle_timeout(&mut self, now: Duration) -> Progress {
            self.ch.handle_timeout(now)
        }

        fn deadline(&self) -> Option<Duration> {
            self.ch.deadline()
        }

        fn object(&self) -> (u16, u8) {
            (self.ch.index, self.ch.subindex)
        }

        fn response_cob(&self) -> u16 {
            self.ch.response_cob()
        }

        fn abort_frame(&self, code: AbortCode) -> Option<CanFrame> {
            self.ch.abort_frame(code)
        }
    };
}

impl Transfer for Upload<'_> {
    fn poll_transmit(&mut self) -> Option<CanFrame> {
        self.ch.take_outbox()
    }

    fn handle(&mut self, frame: &CanFrame, now: Duration) -> Progress {
        let data = match self.ch.accept(frame) {
            Ok(Some(data)) => data,
            Ok(None) => return Progress::Pending,
            Err(aborted) => return aborted,
        };
        match self.state {
            UploadState::Initiate => {
                if self.ch.is_stale_initiate(&data) {
                    return Progress::Pending;
                }
                self.on_initiate(&data, now)
            }
            UploadState::Segment { .. } => self.on_segment(&data, now),
            #[cfg(feature = "sdo-block")]
            UploadState::Block(block) => self.on_block(block, &data, now),
        }
    }

    channel_methods!();
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum DownloadState {
    Initiate,
    Segment {
        toggle: u8,
        sent: usize,
    },
    #[cfg(feature = "sdo-block")]
    Block(super::block::DownloadBlock),
}

/// An SDO download (write) in progress.
#[derive(Debug)]
pub struct Download<'a> {
    pub(crate) ch: Channel,
    pub(crate) data: &'a [u8],
    pub(crate) state: DownloadState,
}

impl Download<'_> {
    /// Queues the segment starting at `sent`; returns the offset after it.
    fn send_segment(&mut self, toggle: u8, sent: usize, now: Duration) -> usize {
        let end = (sent + SEGMENT_BYTES).min(self.data.len());
        let chunk = &self.data[sent..end];
        let last = u8::from(end == self.data.len());
        let mut frame = [0u8; 8];
        frame[0] = (ccs::DOWNLOAD_SEGMENT << 5)
            | toggle
            | (((SEGMENT_BYTES - chunk.len()) as u8) << 1)
            | last;
        frame[1..1 + chunk.len()].copy_from_slice(chunk);
        self.ch.send(frame, now);
        end
    }

    fn on_initiate(&mut self, data: &[u8; 8], now: Duration) -> Progress {
        if specifier(data) != scs::INITIATE_DOWNLOAD {
            return self.ch.abort(AbortCode::InvalidCommandSpecifier);
        }
        if (1..=EXPEDITED_MAX).contains(&self.data.len()) {
            return self.ch.done(self.data.len());
        }
        let sent = self.send_segment(0, 0, now);
        self.state = DownloadState::Segment { toggle: 0, sent };
        Progress::Pending
    }

    fn on_segment(&mut self, data: &[u8; 8], now: Duration) -> Progress {
        let DownloadState::Segment { toggle, sent } = self.state else {
            return Progress::Pending;
        };
        if specifier(data) != scs::DOWNLOAD_SEGMENT {
            return self.ch.abort(AbortCode::InvalidCommandSpecifier);
        }
        if data[0] & TOGGLE != toggle {
            return self.ch.abort(AbortCode::ToggleBitNotAlternated);
        }
        if sent == self.data.len() {
            return self.ch.done(sent);
        }
        let toggle = toggle ^ TOGGLE;
        let sent = self.send_segment(toggle, sent, now);
        self.state = DownloadState::Segment { toggle, sent };
        Progress::Pending
    }
}

impl Transfer for Download<'_> {
    fn poll_transmit(&mut self) -> Option<CanFrame> {
        if let Some(frame) = self.ch.take_outbox() {
            return Some(frame);
        }
        #[cfg(feature = "sdo-block")]
        if let DownloadState::Block(block) = self.state {
            return self.next_block_segment(block);
        }
        None
    }

    fn handle(&mut self, frame: &CanFrame, now: Duration) -> Progress {
        let data = match self.ch.accept(frame) {
            Ok(Some(data)) => data,
            Ok(None) => return Progress::Pending,
            Err(aborted) => return aborted,
        };
        match self.state {
            DownloadState::Initiate => {
                if self.ch.is_stale_initiate(&data) {
                    return Progress::Pending;
                }
                self.on_initiate(&data, now)
            }
            DownloadState::Segment { .. } => self.on_segment(&data, now),
            #[cfg(feature = "sdo-block")]
            DownloadState::Block(block) => self.on_block(block, &data, now),
        }
    }

    channel_methods!();
}
