//! SDO block upload and download (CiA 301 §7.2.4.3.9 ff.), with the CRC-16 of the whole value.

use core::time::Duration;

use super::client::{read_size, size_bytes, DownloadState, UploadState, SEGMENT_BYTES};
use super::{
    ccs, command_only, scs, specifier, AbortCode, Channel, Download, Progress, SdoClient, Upload,
};
use crate::canopen::frame::CanFrame;

/// Largest number of segments in one block.
pub const MAX_BLOCK_SIZE: u8 = 127;

const CRC16: crc::Crc<u16> = crc::Crc::<u16>::new(&crc::CRC_16_XMODEM);

/// The block-transfer CRC (CRC-16/XMODEM, the CCITT polynomial 0x1021 from 0) of a value.
pub fn crc16_xmodem(data: &[u8]) -> u16 {
    CRC16.checksum(data)
}

/// Client "block" subcommands (low bits of byte 0).
const CS_INITIATE: u8 = 0;
const CS_END: u8 = 1;
const CS_ACK: u8 = 2;
const CS_START_UPLOAD: u8 = 3;
/// "CRC supported" bit of the initiate frames.
const CRC_SUPPORTED: u8 = 0x04;
/// "Last segment" bit of a block segment.
const LAST: u8 = 0x80;

/// Where a block upload stands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum UploadBlock {
    Initiate {
        block_size: u8,
    },
    Receiving {
        /// Sequence number the next segment must carry.
        expected: u8,
        block_size: u8,
        /// Bytes accepted so far, counting the last segment as a full 7.
        received: usize,
        size: Option<usize>,
        crc: bool,
    },
    End {
        received: usize,
        size: Option<usize>,
        crc: bool,
    },
}

/// Where a block download stands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum DownloadBlock {
    Initiate,
    /// Segments of the current block are being handed to the caller.
    Sending {
        base: usize,
        seq: u8,
        block_size: u8,
    },
    /// The block is out; waiting for the server's acknowledgement.
    Ack {
        base: usize,
        sent: u8,
        last: bool,
    },
    End,
}

const fn block_size_valid(size: u8) -> bool {
    size >= 1 && size <= MAX_BLOCK_SIZE
}

impl SdoClient {
    /// Starts a block upload of `index:subindex` asking for `block_size` segments per block.
    /// A server that answers with a normal upload response is followed into segmented mode.
    pub fn block_upload<'a>(
        &self,
        index: u16,
        subindex: u8,
        buf: &'a mut [u8],
        block_size: u8,
        now: Duration,
    ) -> Upload<'a> {
        let block_size = block_size.clamp(1, MAX_BLOCK_SIZE);
        let mut ch = Channel::new(self, index, subindex, now);
        let command = (ccs::BLOCK_UPLOAD << 5) | CRC_SUPPORTED | CS_INITIATE;
        // Protocol switch threshold 0: the server decides.
        ch.send(ch.initiate(command, [block_size, 0, 0, 0]), now);
        Upload {
            ch,
            buf,
            state: UploadState::Block(UploadBlock::Initiate { block_size }),
        }
    }

    /// Starts a block download of `data` to `index:subindex`.
    pub fn block_download<'a>(
        &self,
        index: u16,
        subindex: u8,
        data: &'a [u8],
        now: Duration,
    ) -> Download<'a> {
        let mut ch = Channel::new(self, index, subindex, now);
        // s = 1: the size is indicated.
        let command = (ccs::BLOCK_DOWNLOAD << 5) | CRC_SUPPORTED | 0x02 | CS_INITIATE;
        ch.send(ch.initiate(command, size_bytes(data.len())), now);
        Download {
            ch,
            data,
            state: DownloadState::Block(DownloadBlock::Initiate),
        }
    }
}

impl Upload<'_> {
    pub(crate) fn on_block(
        &mut self,
        block: UploadBlock,
        data: &[u8; 8],
        now: Duration,
    ) -> Progress {
        match block {
            UploadBlock::Initiate { block_size } => {
                let answers_initiate =
                    specifier(data) == scs::INITIATE_UPLOAD || specifier(data) == scs::BLOCK_UPLOAD;
                if answers_initiate && !self.ch.mux_matches(data) {
                    return Progress::Pending;
                }
                if specifier(data) == scs::INITIATE_UPLOAD {
                    // The server switched to the normal protocol, as CiA 301 allows.
                    return self.on_initiate(data, now);
                }
                // Server block-upload frames carry their subcommand in bit 0 only.
                if specifier(data) != scs::BLOCK_UPLOAD || data[0] & 1 != CS_INITIATE {
                    return self.ch.abort(AbortCode::InvalidCommandSpecifier);
                }
                let size = (data[0] & 0x02 != 0).then(|| read_size(data));
                if size.is_some_and(|size| size > self.buf.len()) {
                    return self.ch.abort(AbortCode::OutOfMemory);
                }
                self.state = UploadState::Block(UploadBlock::Receiving {
                    expected: 1,
                    block_size,
                    received: 0,
                    size,
                    crc: data[0] & CRC_SUPPORTED != 0,
                });
                self.ch.send(
                    command_only((ccs::BLOCK_UPLOAD << 5) | CS_START_UPLOAD),
                    now,
                );
                Progress::Pending
            }
            UploadBlock::Receiving {
                expected,
                block_size,
                received,
                size,
                crc,
            } => {
                self.ch.touch(now);
                let seq = data[0] & !LAST;
                let last = data[0] & LAST != 0;
                if seq == 0 || seq > block_size {
                    return self.ch.abort(AbortCode::InvalidSequenceNumber);
                }
                let in_order = seq == expected;
                let mut received = received;
                if in_order {
                    let room = self.buf.len().saturating_sub(received);
                    // Only the last segment may carry padding past the buffer's end.
                    if room < SEGMENT_BYTES && !last {
                        return self.ch.abort(AbortCode::OutOfMemory);
                    }
                    let take = room.min(SEGMENT_BYTES);
                    self.buf[received..received + take].copy_from_slice(&data[1..1 + take]);
                    received += SEGMENT_BYTES;
                }
                // Out-of-order segments are dropped; the acknowledgement makes the server
                // repeat everything after the last good one.
                let good = if in_order { expected } else { expected - 1 };
                // A block ends at its last sequence number, or early at the value's last
                // segment (in order or not: an out-of-order one is acknowledged short).
                let block_over = last || seq == block_size;
                if !block_over {
                    self.state = UploadState::Block(UploadBlock::Receiving {
                        expected: if in_order { expected + 1 } else { expected },
                        block_size,
                        received,
                        size,
                        crc,
                    });
                    return Progress::Pending;
                }
                let ack = [
                    (ccs::BLOCK_UPLOAD << 5) | CS_ACK,
                    good,
                    block_size,
                    0,
                    0,
                    0,
                    0,
                    0,
                ];
                self.ch.send(ack, now);
                self.state = UploadState::Block(if last && in_order {
                    UploadBlock::End {
                        received,
                        size,
                        crc,
                    }
                } else {
                    UploadBlock::Receiving {
                        expected: 1,
                        block_size,
                        received,
                        size,
                        crc,
                    }
                });
                Progress::Pending
            }
            UploadBlock::End {
                received,
                size,
                crc,
            } => {
                if specifier(data) != scs::BLOCK_UPLOAD || data[0] & 1 != CS_END {
                    return self.ch.abort(AbortCode::InvalidCommandSpecifier);
                }
                let unused = ((data[0] >> 2) & 0b111) as usize;
                let len = received.saturating_sub(unused);
                if len > self.buf.len() {
                    return self.ch.abort(AbortCode::OutOfMemory);
                }
                if size.is_some_and(|size| size != len) {
                    return self.ch.abort(AbortCode::LengthMismatch);
                }
                if crc && crc16_xmodem(&self.buf[..len]) != u16::from_le_bytes([data[1], data[2]]) {
                    return self.ch.abort(AbortCode::CrcError);
                }
                self.ch
                    .send(command_only((ccs::BLOCK_UPLOAD << 5) | CS_END), now);
                self.ch.done(len)
            }
        }
    }
}

impl Download<'_> {
    /// Hands out the next segment of the current block, lazily, so a 127-segment block needs
    /// no queue.
    pub(crate) fn next_block_segment(&mut self, block: DownloadBlock) -> Option<CanFrame> {
        let DownloadBlock::Sending {
            base,
            seq,
            block_size,
        } = block
        else {
            return None;
        };
        let start = (base + (seq as usize - 1) * SEGMENT_BYTES).min(self.data.len());
        let end = (start + SEGMENT_BYTES).min(self.data.len());
        let last = end == self.data.len();
        let mut frame = [0u8; 8];
        frame[0] = seq | if last { LAST } else { 0 };
        frame[1..1 + end - start].copy_from_slice(&self.data[start..end]);
        self.state = DownloadState::Block(if last || seq == block_size {
            DownloadBlock::Ack {
                base,
                sent: seq,
                last,
            }
        } else {
            DownloadBlock::Sending {
                base,
                seq: seq + 1,
                block_size,
            }
        });
        Some(self.ch.frame(frame))
    }

    pub(crate) fn on_block(
        &mut self,
        block: DownloadBlock,
        data: &[u8; 8],
        now: Duration,
    ) -> Progress {
        let subcommand = data[0] & 0b11;
        if specifier(data) != scs::BLOCK_DOWNLOAD {
            return self.ch.abort(AbortCode::InvalidCommandSpecifier);
        }
        match block {
            DownloadBlock::Initiate if subcommand == CS_INITIATE => {
                if !self.ch.mux_matches(data) {
                    return Progress::Pending;
                }
                self.start_block(0, data[4], now)
            }
            DownloadBlock::Ack { base, sent, last } if subcommand == CS_ACK => {
                let acked = data[1];
                if acked > sent {
                    return self.ch.abort(AbortCode::InvalidSequenceNumber);
                }
                let len = self.data.len();
                if !(last && acked == sent) {
                    let base = (base + acked as usize * SEGMENT_BYTES).min(len);
                    return self.start_block(base, data[2], now);
                }
                let last_start = (base + (sent as usize - 1) * SEGMENT_BYTES).min(len);
                let unused = (SEGMENT_BYTES - (len - last_start)) as u8;
                let [lo, hi] = crc16_xmodem(self.data).to_le_bytes();
                let end = (ccs::BLOCK_DOWNLOAD << 5) | (unused << 2) | CS_END;
                self.ch.send([end, lo, hi, 0, 0, 0, 0, 0], now);
                self.state = DownloadState::Block(DownloadBlock::End);
                Progress::Pending
            }
            DownloadBlock::End if subcommand == CS_END => self.ch.done(self.data.len()),
            // Segments are handed out on demand; nothing is expected from the server meanwhile.
            _ => self.ch.abort(AbortCode::InvalidCommandSpecifier),
        }
    }

    fn start_block(&mut self, base: usize, block_size: u8, now: Duration) -> Progress {
        if !block_size_valid(block_size) {
            return self.ch.abort(AbortCode::InvalidBlockSize);
        }
        self.ch.touch(now);
        self.state = DownloadState::Block(DownloadBlock::Sending {
            base,
            seq: 1,
            block_size,
        });
        Progress::Pending
    }
}
