//! A small SDO server over an object dictionary: expedited, segmented and block transfers
//! (feature `server`).
//!
//! The simulator's CANopen nodes answer SDOs through it (`drivesim::canopen::node`), and it is
//! the double the client is checked against (unit, property and fault-injection tests); it is
//! not a complete CiA 301 device.

use std::collections::BTreeMap;
use std::vec::Vec;

use super::block::{crc16_xmodem, MAX_BLOCK_SIZE};
use super::client::SEGMENT_BYTES;
use super::{ccs, command_only, scs, AbortCode, TOGGLE};
use crate::canopen::address::NodeId;
use crate::canopen::frame::{cob, CanFrame};

/// The objects an [`SdoServer`] serves.
pub trait ObjectDictionary {
    /// The value of `index:subindex`.
    fn read(&mut self, index: u16, subindex: u8) -> Result<Vec<u8>, AbortCode>;
    /// Stores `data` at `index:subindex`.
    fn write(&mut self, index: u16, subindex: u8, data: &[u8]) -> Result<(), AbortCode>;
    /// Whether `index:subindex` takes downloads at all (it exists and is writable): asked before
    /// the data of a block download is accepted, so that the client learns early. By default the
    /// object must be readable or write-only; [`ObjectDictionary::write`] still decides once the
    /// data is in.
    fn check_writable(&mut self, index: u16, subindex: u8) -> Result<(), AbortCode> {
        match self.read(index, subindex) {
            Ok(_) | Err(AbortCode::WriteOnly) => Ok(()),
            Err(refusal) => Err(refusal),
        }
    }
}

/// Objects in a map; unknown ones abort with "object does not exist".
impl ObjectDictionary for BTreeMap<(u16, u8), Vec<u8>> {
    fn read(&mut self, index: u16, subindex: u8) -> Result<Vec<u8>, AbortCode> {
        self.get(&(index, subindex))
            .cloned()
            .ok_or(AbortCode::ObjectDoesNotExist)
    }
    fn write(&mut self, index: u16, subindex: u8, data: &[u8]) -> Result<(), AbortCode> {
        let slot = self
            .get_mut(&(index, subindex))
            .ok_or(AbortCode::ObjectDoesNotExist)?;
        *slot = data.to_vec();
        Ok(())
    }
}

#[derive(Debug, Clone, PartialEq, Eq)]
enum State {
    Idle,
    Upload {
        data: Vec<u8>,
        pos: usize,
        toggle: u8,
    },
    Download {
        buf: Vec<u8>,
        toggle: u8,
    },
    BlockUploadReady {
        data: Vec<u8>,
        block_size: u8,
    },
    BlockUploadAck {
        data: Vec<u8>,
        base: usize,
        sent: u8,
        block_size: u8,
    },
    BlockUploadEnd,
    BlockDownload {
        buf: Vec<u8>,
        expected: u8,
    },
    BlockDownloadEnd {
        buf: Vec<u8>,
    },
}

/// Most bytes a download may carry unless [`SdoServer::with_max_download`] says otherwise: the
/// client decides how many segments it sends, so the server bounds what it buffers.
pub const DEFAULT_MAX_DOWNLOAD: usize = 64 * 1024;

/// A sans-I/O SDO server for one node.
#[derive(Debug)]
pub struct SdoServer<D> {
    request_cob: u16,
    response_cob: u16,
    dictionary: D,
    block_size: u8,
    max_download: usize,
    state: State,
    mux: (u16, u8),
}

impl<D: ObjectDictionary> SdoServer<D> {
    /// A server for `node` on the default SDO channel.
    pub fn new(node: NodeId, dictionary: D) -> Self {
        Self {
            request_cob: cob::SDO_RX + u16::from(node.0),
            response_cob: cob::SDO_TX + u16::from(node.0),
            dictionary,
            block_size: MAX_BLOCK_SIZE,
            max_download: DEFAULT_MAX_DOWNLOAD,
            state: State::Idle,
            mux: (0, 0),
        }
    }

    /// Sets the block size the server asks for in block downloads.
    pub fn with_block_size(mut self, size: u8) -> Self {
        self.block_size = size.clamp(1, MAX_BLOCK_SIZE);
        self
    }

    /// Sets the most bytes one download may carry; longer ones are aborted with
    /// [`AbortCode::OutOfMemory`].
    pub fn with_max_download(mut self, bytes: usize) -> Self {
        self.max_download = bytes;
        self
    }

    /// Refuses a download that has grown past the limit.
    fn check_download_size(&self, buf: &[u8]) -> Result<(), AbortCode> {
        if buf.len() > self.max_download {
            return Err(AbortCode::OutOfMemory);
        }
        Ok(())
    }

    /// The served objects.
    pub fn dictionary(&mut self) -> &mut D {
        &mut self.dictionary
    }

    /// Handles one frame; returns the frames to send (none for foreign frames).
    pub fn handle(&mut self, frame: &CanFrame) -> Vec<CanFrame> {
        if frame.id() != self.request_cob || frame.is_remote() || !super::is_full_length(frame) {
            return Vec::new();
        }
        let data = frame.padded();
        let state = core::mem::replace(&mut self.state, State::Idle);
        let mut out = Vec::new();
        if let Err(code) = self.step(state, &data, &mut out) {
            out.clear();
            self.state = State::Idle;
            out.push(self.response(self.with_mux(scs::ABORT << 5, code.code().to_le_bytes())));
        }
        out
    }

    fn response(&self, data: [u8; 8]) -> CanFrame {
        CanFrame::full(self.response_cob, data)
    }

    fn with_mux(&self, command: u8, tail: [u8; 4]) -> [u8; 8] {
        let [lo, hi] = self.mux.0.to_le_bytes();
        [
            command, lo, hi, self.mux.1, tail[0], tail[1], tail[2], tail[3],
        ]
    }

    fn step(
        &mut self,
        state: State,
        data: &[u8; 8],
        out: &mut Vec<CanFrame>,
    ) -> Result<(), AbortCode> {
        let command = data[0] >> 5;
        if data[0] == ccs::ABORT << 5 {
            return Ok(()); // The client gave up; back to idle, nothing to answer.
        }
        // Block download segments carry no command specifier.
        if let State::BlockDownload { buf, expected } = state {
            return self.block_download_segment(buf, expected, data, out);
        }
        match (command, state) {
            (ccs::INITIATE_UPLOAD, _) => {
                self.mux = (u16::from_le_bytes([data[1], data[2]]), data[3]);
                let value = self.dictionary.read(self.mux.0, self.mux.1)?;
                if (1..=4).contains(&value.len()) {
                    let mut tail = [0; 4];
                    tail[..value.len()].copy_from_slice(&value);
                    let n = (4 - value.len()) as u8;
                    out.push(self.response(
                        self.with_mux((scs::INITIATE_UPLOAD << 5) | (n << 2) | 0b11, tail),
                    ));
                } else {
                    let size = (value.len() as u32).to_le_bytes();
                    out.push(
                        self.response(self.with_mux((scs::INITIATE_UPLOAD << 5) | 0b01, size)),
                    );
                    self.state = State::Upload {
                        data: value,
                        pos: 0,
                        toggle: 0,
                    };
                }
                Ok(())
            }
            (
                ccs::UPLOAD_SEGMENT,
                State::Upload {
                    data: value,
                    pos,
                    toggle,
                },
            ) => {
                if data[0] & TOGGLE != toggle {
                    return Err(AbortCode::ToggleBitNotAlternated);
                }
                let end = (pos + SEGMENT_BYTES).min(value.len());
                let mut frame = [0u8; 8];
                let last = u8::from(end == value.len());
                frame[0] = (scs::UPLOAD_SEGMENT << 5)
                    | toggle
                    | (((SEGMENT_BYTES - (end - pos)) as u8) << 1)
                    | last;
                frame[1..1 + end - pos].copy_from_slice(&value[pos..end]);
                out.push(self.response(frame));
                if last == 0 {
                    self.state = State::Upload {
                        data: value,
                        pos: end,
                        toggle: toggle ^ TOGGLE,
                    };
                }
                Ok(())
            }
            (ccs::INITIATE_DOWNLOAD, _) => {
                self.mux = (u16::from_le_bytes([data[1], data[2]]), data[3]);
                if data[0] & 0b10 != 0 {
                    let len = if data[0] & 1 != 0 {
                        4 - ((data[0] >> 2) & 0b11) as usize
                    } else {
                        4
                    };
                    self.dictionary
                        .write(self.mux.0, self.mux.1, &data[4..4 + len])?;
                } else {
                    self.state = State::Download {
                        buf: Vec::new(),
                        toggle: 0,
                    };
                }
                out.push(self.response(self.with_mux(scs::INITIATE_DOWNLOAD << 5, [0; 4])));
                Ok(())
            }
            (ccs::DOWNLOAD_SEGMENT, State::Download { mut buf, toggle }) => {
                if data[0] & TOGGLE != toggle {
                    return Err(AbortCode::ToggleBitNotAlternated);
                }
                let count = SEGMENT_BYTES - ((data[0] >> 1) & 0b111) as usize;
                buf.extend_from_slice(&data[1..1 + count]);
                self.check_download_size(&buf)?;
                if data[0] & 1 != 0 {
                    self.dictionary.write(self.mux.0, self.mux.1, &buf)?;
                } else {
                    self.state = State::Download {
                        buf,
                        toggle: toggle ^ TOGGLE,
                    };
                }
                out.push(self.response(command_only((scs::DOWNLOAD_SEGMENT << 5) | toggle)));
                Ok(())
            }
            (ccs::BLOCK_UPLOAD, state) => self.block_upload(state, data, out),
            (ccs::BLOCK_DOWNLOAD, state) => self.block_download(state, data, out),
            _ => Err(AbortCode::InvalidCommandSpecifier),
        }
    }

    fn block_upload(
        &mut self,
        state: State,
        data: &[u8; 8],
        out: &mut Vec<CanFrame>,
    ) -> Result<(), AbortCode> {
        let subcommand = data[0] & 0b11;
        match (subcommand, state) {
            (0, _) => {
                self.mux = (u16::from_le_bytes([data[1], data[2]]), data[3]);
                let block_size = data[4];
                if !(1..=MAX_BLOCK_SIZE).contains(&block_size) {
                    return Err(AbortCode::InvalidBlockSize);
                }
                let value = self.dictionary.read(self.mux.0, self.mux.1)?;
                let size = (value.len() as u32).to_le_bytes();
                // scs = 6, CRC supported, size indicated, ss = 0 (initiate).
                out.push(self.response(self.with_mux((scs::BLOCK_UPLOAD << 5) | 0x06, size)));
                self.state = State::BlockUploadReady {
                    data: value,
                    block_size,
                };
                Ok(())
            }
            (
                3,
                State::BlockUploadReady {
                    data: value,
                    block_size,
                },
            ) => {
                self.send_upload_block(value, 0, block_size, out);
                Ok(())
            }
            (
                2,
                State::BlockUploadAck {
                    data: value,
                    base,
                    sent,
                    ..
                },
            ) => {
                let acked = data[1];
                if acked > sent {
                    return Err(AbortCode::InvalidSequenceNumber);
                }
                let next = (base + acked as usize * SEGMENT_BYTES).min(value.len());
                let all_sent = base + sent as usize * SEGMENT_BYTES >= value.len();
                if acked == sent && all_sent {
                    let last_start = base + (sent as usize - 1) * SEGMENT_BYTES;
                    let unused =
                        (SEGMENT_BYTES - (value.len() - last_start.min(value.len()))) as u8;
                    let [lo, hi] = crc16_xmodem(&value).to_le_bytes();
                    out.push(self.response([
                        (scs::BLOCK_UPLOAD << 5) | (unused << 2) | 1,
                        lo,
                        hi,
                        0,
                        0,
                        0,
                        0,
                        0,
                    ]));
                    self.state = State::BlockUploadEnd;
                } else {
                    let block_size = data[2];
                    if !(1..=MAX_BLOCK_SIZE).contains(&block_size) {
                        return Err(AbortCode::InvalidBlockSize);
                    }
                    self.send_upload_block(value, next, block_size, out);
                }
                Ok(())
            }
            (1, State::BlockUploadEnd) => Ok(()),
            _ => Err(AbortCode::InvalidCommandSpecifier),
        }
    }

    fn send_upload_block(
        &mut self,
        value: Vec<u8>,
        base: usize,
        block_size: u8,
        out: &mut Vec<CanFrame>,
    ) {
        let mut seq = 0;
        let mut start = base;
        loop {
            seq += 1;
            let end = (start + SEGMENT_BYTES).min(value.len());
            let last = end == value.len();
            let mut frame = [0u8; 8];
            frame[0] = seq | if last { 0x80 } else { 0 };
            frame[1..1 + end - start].copy_from_slice(&value[start..end]);
            out.push(self.response(frame));
            start = end;
            if last || seq == block_size {
                break;
            }
        }
        self.state = State::BlockUploadAck {
            data: value,
            base,
            sent: seq,
            block_size,
        };
    }

    fn block_download(
        &mut self,
        state: State,
        data: &[u8; 8],
        out: &mut Vec<CanFrame>,
    ) -> Result<(), AbortCode> {
        match (data[0] & 0b1, state) {
            (0, _) => {
                self.mux = (u16::from_le_bytes([data[1], data[2]]), data[3]);
                // Check the object takes downloads before accepting data for it (not by reading
                // it: a write-only object cannot be read).
                self.dictionary.check_writable(self.mux.0, self.mux.1)?;
                out.push(self.response(self.with_mux(
                    (scs::BLOCK_DOWNLOAD << 5) | 0x04,
                    [self.block_size, 0, 0, 0],
                )));
                self.state = State::BlockDownload {
                    buf: Vec::new(),
                    expected: 1,
                };
                Ok(())
            }
            (1, State::BlockDownloadEnd { mut buf }) => {
                let unused = ((data[0] >> 2) & 0b111) as usize;
                buf.truncate(buf.len().saturating_sub(unused));
                if crc16_xmodem(&buf) != u16::from_le_bytes([data[1], data[2]]) {
                    return Err(AbortCode::CrcError);
                }
                self.dictionary.write(self.mux.0, self.mux.1, &buf)?;
                out.push(self.response(command_only((scs::BLOCK_DOWNLOAD << 5) | 1)));
                Ok(())
            }
            _ => Err(AbortCode::InvalidCommandSpecifier),
        }
    }

    fn block_download_segment(
        &mut self,
        mut buf: Vec<u8>,
        expected: u8,
        data: &[u8; 8],
        out: &mut Vec<CanFrame>,
    ) -> Result<(), AbortCode> {
        let seq = data[0] & 0x7F;
        let last = data[0] & 0x80 != 0;
        let in_order = seq == expected;
        if in_order {
            buf.extend_from_slice(&data[1..8]);
            self.check_download_size(&buf)?;
        }
        let good = if in_order { expected } else { expected - 1 };
        if last || seq == self.block_size {
            out.push(self.response([
                (scs::BLOCK_DOWNLOAD << 5) | 2,
                good,
                self.block_size,
                0,
                0,
                0,
                0,
                0,
            ]));
            self.state = if last && in_order {
                State::BlockDownloadEnd { buf }
            } else {
                State::BlockDownload { buf, expected: 1 }
            };
        } else {
            let expected = if in_order { expected + 1 } else { expected };
            self.state = State::BlockDownload { buf, expected };
        }
        Ok(())
    }
}
