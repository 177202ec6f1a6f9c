//! SDO client tests against the in-crate server, with fault injection.

use core::time::Duration;
use std::collections::BTreeMap;
use std::vec;
use std::vec::Vec;

use proptest::prelude::*;

use super::server::{ObjectDictionary, SdoServer};
use super::*;
use crate::canopen::{CanFrame, NodeId};

const NODE: NodeId = NodeId(5);
const TIMEOUT: Duration = Duration::from_millis(100);
type Dictionary = BTreeMap<(u16, u8), Vec<u8>>;

fn client() -> SdoClient {
    SdoClient::new(NODE, TIMEOUT)
}

fn server(objects: &[((u16, u8), &[u8])]) -> SdoServer<Dictionary> {
    let dictionary = objects.iter().map(|(k, v)| (*k, v.to_vec())).collect();
    SdoServer::new(NODE, dictionary)
}

fn request(data: [u8; 8]) -> CanFrame {
    CanFrame::new(0x605, &data).unwrap()
}

fn response(data: [u8; 8]) -> CanFrame {
    CanFrame::new(0x585, &data).unwrap()
}

/// Which way a frame travels, for fault hooks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Dir {
    ToServer,
    ToClient,
}

/// Everything the client sent, and how the transfer ended.
struct Outcome {
    progress: Progress,
    sent: Vec<CanFrame>,
}

/// Moves frames between `transfer` and `server`, passing each through `fault`, and advances
/// time to the transfer's deadline whenever the bus falls silent.
fn pump<T: Transfer, D: ObjectDictionary>(
    transfer: &mut T,
    server: &mut SdoServer<D>,
    mut fault: impl FnMut(Dir, CanFrame) -> Vec<CanFrame>,
) -> Outcome {
    let mut now = Duration::ZERO;
    let mut progress = Progress::Pending;
    let mut sent = Vec::new();
    for _ in 0..100_000 {
        let mut to_server = Vec::new();
        while let Some(frame) = transfer.poll_transmit() {
            sent.push(frame);
            to_server.extend(fault(Dir::ToServer, frame));
        }
        if progress != Progress::Pending {
            // Let the server see the client's last word (end or abort frames).
            for frame in to_server {
                server.handle(&frame);
            }
            return Outcome { progress, sent };
        }
        let to_client: Vec<CanFrame> = to_server
            .iter()
            .flat_map(|frame| server.handle(frame))
            .flat_map(|frame| fault(Dir::ToClient, frame))
            .collect();
        if to_client.is_empty() {
            now = transfer
                .deadline()
                .expect("a pending transfer has a deadline");
            progress = transfer.handle_timeout(now);
            continue;
        }
        for frame in to_client {
            progress = transfer.handle(&frame, now);
            if progress != Progress::Pending {
                break;
            }
        }
    }
    panic!("transfer did not finish");
}

fn clean(_: Dir, frame: CanFrame) -> Vec<CanFrame> {
    vec![frame]
}

fn abort_frame(index: u16, subindex: u8, code: AbortCode) -> CanFrame {
    let [lo, hi] = index.to_le_bytes();
    let [a, b, c, d] = code.code().to_le_bytes();
    request([0x80, lo, hi, subindex, a, b, c, d])
}

// --- Encoding against the Lafert manual's worked examples (node 1, COB 0x601). ---

#[test]
fn expedited_downloads_match_the_lafert_manual() {
    let client = SdoClient::new(NodeId(1), TIMEOUT);
    let cases: [(u16, &[u8], [u8; 8]); 3] = [
        (0x6060, &[3], [0x2F, 0x60, 0x60, 0x00, 0x03, 0, 0, 0]),
        (0x6040, &[0x0F, 0], [0x2B, 0x40, 0x60, 0x00, 0x0F, 0, 0, 0]),
        (
            0x60FF,
            &819_200u32.to_le_bytes(),
            [0x23, 0xFF, 0x60, 0x00, 0x00, 0x80, 0x0C, 0x00],
        ),
    ];
    for (index, value, wire) in cases {
        let mut transfer = client.download(index, 0, value, Duration::ZERO);
        let frame = transfer.poll_transmit().unwrap();
        assert_eq!((frame.id(), frame.data()), (0x601, &wire[..]));
        assert_eq!(transfer.poll_transmit(), None);
    }
}

#[test]
fn expedited_upload_request_and_responses_of_each_size() {
    for (command, len) in [(0x4F, 1), (0x4B, 2), (0x47, 3), (0x43, 4), (0x42, 4)] {
        let mut buf = [0u8; 4];
        let mut transfer = client().upload(0x606C, 0, &mut buf, Duration::ZERO);
        assert_eq!(
            transfer.poll_transmit(),
            Some(request([0x40, 0x6C, 0x60, 0, 0, 0, 0, 0]))
        );
        let reply = response([command, 0x6C, 0x60, 0, 0x11, 0x22, 0x33, 0x44]);
        assert_eq!(transfer.handle(&reply, Duration::ZERO), Progress::Done(len));
        assert_eq!(buf[..len], [0x11, 0x22, 0x33, 0x44][..len]);
    }
}

#[test]
fn foreign_frames_are_ignored() {
    let mut buf = [0u8; 4];
    let mut transfer = client().upload(0x1000, 0, &mut buf, Duration::ZERO);
    transfer.poll_transmit();
    let foreign = [
        CanFrame::new(0x586, &[0x43, 0, 0x10, 0, 1, 2, 3, 4]).unwrap(), // another node
        CanFrame::new(0x185, &[0x43, 0, 0x10, 0]).unwrap(),             // a TPDO
        CanFrame::remote(0x585, 8).unwrap(),                            // a remote frame
        CanFrame::new(0x585, &[]).unwrap(),                             // empty
        response([0x43, 0x01, 0x10, 0, 9, 9, 9, 9]),                    // another object
        response([0x80, 0x01, 0x10, 0, 0, 0, 2, 6]),                    // another object's abort
    ];
    for frame in &foreign {
        assert_eq!(transfer.handle(frame, Duration::ZERO), Progress::Pending);
    }
    assert_eq!(transfer.poll_transmit(), None);
    let reply = response([0x43, 0x00, 0x10, 0, 0x92, 0x01, 0x02, 0x00]);
    assert_eq!(transfer.handle(&reply, Duration::ZERO), Progress::Done(4));
}

/// A read timed out and a stop was written at once: the drive's late answer to the read comes
/// before the answer to the write, and is passed over, not taken for a protocol error.
#[test]
fn a_late_answer_to_an_earlier_transfer_is_passed_over() {
    let data = 6u16.to_le_bytes();
    let mut download = client().download(0x6040, 0, &data, Duration::ZERO);
    download.poll_transmit();
    let late_read = response([0x43, 0x18, 0x10, 1, 0x34, 0x12, 0, 0]); // 1018h:1
    assert_eq!(
        download.handle(&late_read, Duration::ZERO),
        Progress::Pending
    );
    assert_eq!(download.poll_transmit(), None, "no abort");
    let written = response([0x60, 0x40, 0x60, 0, 0, 0, 0, 0]);
    assert_eq!(download.handle(&written, Duration::ZERO), Progress::Done(2));

    let mut buf = [0u8; 4];
    let mut upload = client().upload(0x1000, 0, &mut buf, Duration::ZERO);
    upload.poll_transmit();
    let late_write = response([0x60, 0x40, 0x60, 0, 0, 0, 0, 0]); // 6040h
    assert_eq!(
        upload.handle(&late_write, Duration::ZERO),
        Progress::Pending
    );
    let reply = response([0x43, 0x00, 0x10, 0, 0x92, 0x01, 0x02, 0x00]);
    assert_eq!(upload.handle(&reply, Duration::ZERO), Progress::Done(4));
}

#[test]
fn a_server_abort_ends_the_transfer_with_its_code() {
    let mut buf = [0u8; 4];
    let mut transfer = client().upload(0x2000, 1, &mut buf, Duration::ZERO);
    transfer.poll_transmit();
    let abort = response([0x80, 0x00, 0x20, 1, 0x11, 0x00, 0x09, 0x06]);
    let progress = transfer.handle(&abort, Duration::ZERO);
    assert_eq!(
        progress,
        Progress::Failed(SdoError::Server(AbortCode::SubindexDoesNotExist))
    );
    assert_eq!(
        transfer.poll_transmit(),
        None,
        "no abort is sent back for a server abort"
    );
    assert_eq!(transfer.deadline(), None);
    assert_eq!(
        SdoError::Server(AbortCode::SubindexDoesNotExist).into_bus_error(0x2000, 1),
        crate::BusError::SdoAbort {
            index: 0x2000,
            subindex: 1,
            code: crate::canopen::sdo::AbortCode::from_u32(0x0609_0011)
        }
    );
}

#[test]
fn unknown_objects_abort_through_the_server() {
    let mut server = server(&[]);
    let mut buf = [0u8; 4];
    let outcome = pump(
        &mut client().upload(0x3000, 0, &mut buf, Duration::ZERO),
        &mut server,
        clean,
    );
    assert_eq!(
        outcome.progress,
        Progress::Failed(SdoError::Server(AbortCode::ObjectDoesNotExist))
    );
}

#[test]
fn silence_times_out_and_aborts_on_the_bus() {
    let mut buf = [0u8; 4];
    let mut transfer = client().upload(0x1018, 1, &mut buf, Duration::from_secs(1));
    transfer.poll_transmit();
    let deadline = transfer.deadline().unwrap();
    assert_eq!(deadline, Duration::from_secs(1) + TIMEOUT);
    assert_eq!(
        transfer.handle_timeout(deadline - Duration::from_millis(1)),
        Progress::Pending
    );
    let progress = transfer.handle_timeout(deadline);
    assert_eq!(
        progress,
        Progress::Failed(SdoError::Client(AbortCode::ProtocolTimedOut))
    );
    assert_eq!(
        transfer.poll_transmit(),
        Some(abort_frame(0x1018, 1, AbortCode::ProtocolTimedOut))
    );
    assert_eq!(
        SdoError::Client(AbortCode::ProtocolTimedOut).into_bus_error(0x1018, 1),
        crate::BusError::Timeout
    );
}

#[test]
fn timeout_in_the_middle_of_a_segmented_upload() {
    let value = [7u8; 30];
    let mut server = server(&[((0x2001, 0), &value)]);
    let mut buf = [0u8; 64];
    let mut segments = 0;
    // The server's third segment is lost.
    let outcome = pump(
        &mut client().upload(0x2001, 0, &mut buf, Duration::ZERO),
        &mut server,
        |dir, frame| {
            if dir == Dir::ToClient && frame.data()[0] & 0xE0 == 0 {
                segments += 1;
                if segments == 3 {
                    return vec![];
                }
            }
            vec![frame]
        },
    );
    assert_eq!(
        outcome.progress,
        Progress::Failed(SdoError::Client(AbortCode::ProtocolTimedOut))
    );
    assert_eq!(
        outcome.sent.last(),
        Some(&abort_frame(0x2001, 0, AbortCode::ProtocolTimedOut))
    );
}

#[test]
fn wrong_toggle_bit_from_the_server_aborts() {
    let mut buf = [0u8; 32];
    let mut transfer = client().upload(0x1008, 0, &mut buf, Duration::ZERO);
    transfer.poll_transmit();
    transfer.handle(
        &response([0x41, 0x08, 0x10, 0, 14, 0, 0, 0]),
        Duration::ZERO,
    );
    assert_eq!(
        transfer.poll_transmit(),
        Some(request([0x60, 0, 0, 0, 0, 0, 0, 0]))
    );
    // Toggle must be 0 on the first segment.
    let progress = transfer.handle(
        &response([0x10, b'a', b'b', b'c', b'd', b'e', b'f', b'g']),
        Duration::ZERO,
    );
    assert_eq!(
        progress,
        Progress::Failed(SdoError::Client(AbortCode::ToggleBitNotAlternated))
    );
    assert_eq!(
        transfer.poll_transmit(),
        Some(abort_frame(0x1008, 0, AbortCode::ToggleBitNotAlternated))
    );
}

#[test]
fn wrong_toggle_bit_in_a_download_acknowledgement_aborts() {
    let data = [1u8; 20];
    let mut transfer = client().download(0x2002, 0, &data, Duration::ZERO);
    transfer.poll_transmit();
    transfer.handle(&response([0x60, 0x02, 0x20, 0, 0, 0, 0, 0]), Duration::ZERO);
    let segment = transfer.poll_transmit().unwrap();
    assert_eq!(
        segment.data()[0],
        0x00,
        "first segment: toggle 0, 7 bytes, more follow"
    );
    let progress = transfer.handle(&response([0x30, 0, 0, 0, 0, 0, 0, 0]), Duration::ZERO);
    assert_eq!(
        progress,
        Progress::Failed(SdoError::Client(AbortCode::ToggleBitNotAlternated))
    );
    assert_eq!(
        transfer.poll_transmit(),
        Some(abort_frame(0x2002, 0, AbortCode::ToggleBitNotAlternated))
    );
}

#[test]
fn an_unexpected_server_command_aborts() {
    // An upload answered with a download response.
    let mut buf = [0u8; 4];
    let mut transfer = client().upload(0x2003, 0, &mut buf, Duration::ZERO);
    transfer.poll_transmit();
    let progress = transfer.handle(&response([0x60, 0x03, 0x20, 0, 0, 0, 0, 0]), Duration::ZERO);
    assert_eq!(
        progress,
        Progress::Failed(SdoError::Client(AbortCode::InvalidCommandSpecifier))
    );
    assert_eq!(
        transfer.poll_transmit(),
        Some(abort_frame(0x2003, 0, AbortCode::InvalidCommandSpecifier))
    );
    // A segmented download answered mid-way with an upload segment.
    let mut transfer = client().download(0x2003, 0, &[0; 10], Duration::ZERO);
    transfer.poll_transmit();
    transfer.handle(&response([0x60, 0x03, 0x20, 0, 0, 0, 0, 0]), Duration::ZERO);
    transfer.poll_transmit();
    let progress = transfer.handle(&response([0x00, 0, 0, 0, 0, 0, 0, 0]), Duration::ZERO);
    assert_eq!(
        progress,
        Progress::Failed(SdoError::Client(AbortCode::InvalidCommandSpecifier))
    );
}

#[test]
fn values_larger_than_the_buffer_abort_with_out_of_memory() {
    let value = [1u8; 20];
    let mut server = server(&[((0x2004, 0), &value), ((0x2005, 0), &[1, 2, 3])]);
    let mut small = [0u8; 10];
    let outcome = pump(
        &mut client().upload(0x2004, 0, &mut small, Duration::ZERO),
        &mut server,
        clean,
    );
    assert_eq!(
        outcome.progress,
        Progress::Failed(SdoError::Client(AbortCode::OutOfMemory))
    );
    let mut tiny = [0u8; 2];
    let outcome = pump(
        &mut client().upload(0x2005, 0, &mut tiny, Duration::ZERO),
        &mut server,
        clean,
    );
    assert_eq!(
        outcome.progress,
        Progress::Failed(SdoError::Client(AbortCode::OutOfMemory))
    );
}

#[test]
fn a_segmented_upload_shorter_than_announced_aborts() {
    let mut buf = [0u8; 32];
    let mut transfer = client().upload(0x2006, 0, &mut buf, Duration::ZERO);
    transfer.poll_transmit();
    transfer.handle(
        &response([0x41, 0x06, 0x20, 0, 10, 0, 0, 0]),
        Duration::ZERO,
    );
    transfer.poll_transmit();
    // Last segment (c = 1) with 7 bytes: 7 != 10.
    let progress = transfer.handle(&response([0x01, 1, 2, 3, 4, 5, 6, 7]), Duration::ZERO);
    assert_eq!(
        progress,
        Progress::Failed(SdoError::Client(AbortCode::LengthMismatch))
    );
}

#[test]
fn duplicated_initiate_responses_after_the_end_are_ignored() {
    let mut server = server(&[((0x2007, 0), &[5, 6])]);
    let mut buf = [0u8; 4];
    let mut transfer = client().upload(0x2007, 0, &mut buf, Duration::ZERO);
    let outcome = pump(&mut transfer, &mut server, clean);
    assert_eq!(outcome.progress, Progress::Done(2));
    let late = response([0x4B, 0x07, 0x20, 0, 5, 6, 0, 0]);
    assert_eq!(transfer.handle(&late, Duration::ZERO), Progress::Pending);
    assert_eq!(transfer.poll_transmit(), None);
}

// --- Block transfers. ---

#[test]
fn block_crc_is_crc16_xmodem() {
    assert_eq!(block::crc16_xmodem(b"123456789"), 0x31C3);
    assert_eq!(block::crc16_xmodem(&[]), 0);
}

#[test]
fn block_upload_recovers_from_a_lost_segment() {
    let value: Vec<u8> = (0..100).collect();
    let mut server = server(&[((0x2100, 0), &value)]);
    let mut buf = [0u8; 128];
    let mut dropped = false;
    let mut acks = Vec::new();
    let outcome = pump(
        &mut client().block_upload(0x2100, 0, &mut buf, 10, Duration::ZERO),
        &mut server,
        |dir, frame| {
            if dir == Dir::ToServer && frame.data()[0] == 0xA2 {
                acks.push(frame.data()[1]);
            }
            // Segment 4 of the first block is lost once.
            if dir == Dir::ToClient && frame.data()[0] == 4 && !dropped {
                dropped = true;
                return vec![];
            }
            vec![frame]
        },
    );
    assert_eq!(outcome.progress, Progress::Done(100));
    assert_eq!(&buf[..100], &value[..]);
    assert_eq!(
        acks[0], 3,
        "the client acknowledges the last segment in sequence"
    );
    assert_eq!(
        outcome.sent.last().unwrap().data()[0],
        0xA1,
        "the client confirms the end"
    );
}

#[test]
fn block_upload_with_a_bad_crc_aborts() {
    let value = [9u8; 20];
    let mut server = server(&[((0x2101, 0), &value)]);
    let mut buf = [0u8; 32];
    let outcome = pump(
        &mut client().block_upload(0x2101, 0, &mut buf, 127, Duration::ZERO),
        &mut server,
        |dir, frame| {
            let data = frame.data();
            if dir == Dir::ToClient && data[0] & 0xE3 == 0xC1 {
                let mut corrupted = frame.padded();
                corrupted[1] ^= 0xFF;
                return vec![response(corrupted)];
            }
            vec![frame]
        },
    );
    assert_eq!(
        outcome.progress,
        Progress::Failed(SdoError::Client(AbortCode::CrcError))
    );
    assert_eq!(
        outcome.sent.last(),
        Some(&abort_frame(0x2101, 0, AbortCode::CrcError))
    );
}

#[test]
fn block_upload_follows_a_server_that_switches_to_segmented() {
    let mut buf = [0u8; 16];
    let mut transfer = client().block_upload(0x1008, 0, &mut buf, 16, Duration::ZERO);
    assert_eq!(
        transfer.poll_transmit(),
        Some(request([0xA4, 0x08, 0x10, 0, 16, 0, 0, 0]))
    );
    transfer.handle(&response([0x41, 0x08, 0x10, 0, 3, 0, 0, 0]), Duration::ZERO);
    assert_eq!(
        transfer.poll_transmit(),
        Some(request([0x60, 0, 0, 0, 0, 0, 0, 0]))
    );
    let progress = transfer.handle(
        &response([0x09, b'a', b'b', b'c', 0, 0, 0, 0]),
        Duration::ZERO,
    );
    assert_eq!(progress, Progress::Done(3));
    assert_eq!(&buf[..3], b"abc");
}

#[test]
fn block_download_resends_after_a_partial_acknowledgement() {
    let value: Vec<u8> = (0..60).collect();
    let mut server = server(&[((0x2102, 0), &[])]).with_block_size(5);
    let mut dropped = false;
    let outcome = pump(
        &mut client().block_download(0x2102, 0, &value, Duration::ZERO),
        &mut server,
        |dir, frame| {
            if dir == Dir::ToServer && frame.data()[0] == 2 && !dropped {
                dropped = true;
                return vec![];
            }
            vec![frame]
        },
    );
    assert_eq!(outcome.progress, Progress::Done(60));
    assert_eq!(server.dictionary()[&(0x2102, 0)], value);
}

/// One write-only object, as a device keeps a command register: downloads only.
#[derive(Default)]
struct WriteOnlyObject(Vec<u8>);

impl ObjectDictionary for WriteOnlyObject {
    fn read(&mut self, _: u16, _: u8) -> Result<Vec<u8>, AbortCode> {
        Err(AbortCode::WriteOnly)
    }
    fn write(&mut self, _: u16, _: u8, data: &[u8]) -> Result<(), AbortCode> {
        self.0 = data.to_vec();
        Ok(())
    }
}

#[test]
fn block_downloads_reach_write_only_objects() {
    let mut server = SdoServer::new(NODE, WriteOnlyObject::default());
    let value: Vec<u8> = (0..20).collect();
    let outcome = pump(
        &mut client().block_download(0x2106, 0, &value, Duration::ZERO),
        &mut server,
        clean,
    );
    assert_eq!(outcome.progress, Progress::Done(20));
    assert_eq!(server.dictionary().0, value);
}

#[test]
fn block_downloads_to_unknown_objects_abort_before_the_data() {
    let mut server = server(&[]);
    let outcome = pump(
        &mut client().block_download(0x2107, 0, &[1; 20], Duration::ZERO),
        &mut server,
        clean,
    );
    assert_eq!(
        outcome.progress,
        Progress::Failed(SdoError::Server(AbortCode::ObjectDoesNotExist))
    );
    assert_eq!(outcome.sent.len(), 1, "only the initiate request went out");
}

#[test]
fn block_download_rejects_an_invalid_block_size() {
    let mut transfer = client().block_download(0x2103, 0, &[1; 9], Duration::ZERO);
    assert_eq!(
        transfer.poll_transmit(),
        Some(request([0xC6, 0x03, 0x21, 0, 9, 0, 0, 0]))
    );
    let progress = transfer.handle(&response([0xA4, 0x03, 0x21, 0, 0, 0, 0, 0]), Duration::ZERO);
    assert_eq!(
        progress,
        Progress::Failed(SdoError::Client(AbortCode::InvalidBlockSize))
    );
}

#[test]
fn block_download_rejects_an_acknowledgement_past_the_block() {
    let mut transfer = client().block_download(0x2104, 0, &[1; 9], Duration::ZERO);
    transfer.poll_transmit();
    transfer.handle(&response([0xA4, 0x04, 0x21, 0, 4, 0, 0, 0]), Duration::ZERO);
    assert_eq!(transfer.poll_transmit().unwrap().data()[0], 0x01);
    assert_eq!(
        transfer.poll_transmit().unwrap().data()[0],
        0x82,
        "second segment is the last"
    );
    assert_eq!(transfer.poll_transmit(), None);
    let progress = transfer.handle(&response([0xA2, 3, 4, 0, 0, 0, 0, 0]), Duration::ZERO);
    assert_eq!(
        progress,
        Progress::Failed(SdoError::Client(AbortCode::InvalidSequenceNumber))
    );
}

#[test]
fn block_download_with_a_crc_mismatch_is_aborted_by_the_server() {
    let mut server = server(&[((0x2105, 0), &[])]);
    let outcome = pump(
        &mut client().block_download(0x2105, 0, &[3; 30], Duration::ZERO),
        &mut server,
        |dir, frame| {
            if dir == Dir::ToServer && frame.data()[0] & 0xE3 == 0xC1 {
                let mut corrupted = frame.padded();
                corrupted[2] ^= 0x01;
                return vec![request(corrupted)];
            }
            vec![frame]
        },
    );
    assert_eq!(
        outcome.progress,
        Progress::Failed(SdoError::Server(AbortCode::CrcError))
    );
}

#[test]
fn block_upload_rejects_a_sequence_number_outside_the_block() {
    let mut buf = [0u8; 64];
    let mut transfer = client().block_upload(0x2106, 0, &mut buf, 4, Duration::ZERO);
    transfer.poll_transmit();
    transfer.handle(
        &response([0xC6, 0x06, 0x21, 0, 40, 0, 0, 0]),
        Duration::ZERO,
    );
    assert_eq!(
        transfer.poll_transmit(),
        Some(request([0xA3, 0, 0, 0, 0, 0, 0, 0]))
    );
    let progress = transfer.handle(&response([5, 1, 2, 3, 4, 5, 6, 7]), Duration::ZERO);
    assert_eq!(
        progress,
        Progress::Failed(SdoError::Client(AbortCode::InvalidSequenceNumber))
    );
    assert_eq!(
        transfer.poll_transmit(),
        Some(abort_frame(0x2106, 0, AbortCode::InvalidSequenceNumber))
    );
}

#[test]
fn block_upload_end_checks_the_announced_size() {
    let mut buf = [0u8; 64];
    let mut transfer = client().block_upload(0x2107, 0, &mut buf, 4, Duration::ZERO);
    transfer.poll_transmit();
    transfer.handle(
        &response([0xC6, 0x07, 0x21, 0, 10, 0, 0, 0]),
        Duration::ZERO,
    );
    transfer.poll_transmit();
    transfer.handle(&response([0x81, 1, 2, 3, 4, 5, 6, 7]), Duration::ZERO);
    assert_eq!(
        transfer.poll_transmit(),
        Some(request([0xA2, 1, 4, 0, 0, 0, 0, 0]))
    );
    // End frame: 0 unused bytes, so 7 bytes, but 10 were announced.
    let progress = transfer.handle(&response([0xC1, 0, 0, 0, 0, 0, 0, 0]), Duration::ZERO);
    assert_eq!(
        progress,
        Progress::Failed(SdoError::Client(AbortCode::LengthMismatch))
    );
}

#[test]
fn block_download_with_a_lost_acknowledgement_times_out() {
    let mut server = server(&[((0x2108, 0), &[])]).with_block_size(4);
    let outcome = pump(
        &mut client().block_download(0x2108, 0, &[1; 100], Duration::ZERO),
        &mut server,
        |dir, frame| {
            if dir == Dir::ToClient && frame.data()[0] == 0xA2 {
                vec![]
            } else {
                vec![frame]
            }
        },
    );
    assert_eq!(
        outcome.progress,
        Progress::Failed(SdoError::Client(AbortCode::ProtocolTimedOut))
    );
    assert_eq!(
        outcome.sent.last(),
        Some(&abort_frame(0x2108, 0, AbortCode::ProtocolTimedOut))
    );
}

#[test]
fn block_download_end_answered_with_the_wrong_command_aborts() {
    let mut transfer = client().block_download(0x2109, 0, &[1, 2], Duration::ZERO);
    transfer.poll_transmit();
    transfer.handle(&response([0xA4, 0x09, 0x21, 0, 4, 0, 0, 0]), Duration::ZERO);
    assert_eq!(
        transfer.poll_transmit(),
        Some(request([0x81, 1, 2, 0, 0, 0, 0, 0]))
    );
    transfer.handle(&response([0xA2, 1, 4, 0, 0, 0, 0, 0]), Duration::ZERO);
    let end = transfer.poll_transmit().unwrap();
    assert_eq!(
        end.data()[0],
        0xC1 | (5 << 2),
        "5 bytes of the last segment unused"
    );
    assert_eq!(
        u16::from_le_bytes([end.data()[1], end.data()[2]]),
        block::crc16_xmodem(&[1, 2])
    );
    let progress = transfer.handle(&response([0xA2, 1, 4, 0, 0, 0, 0, 0]), Duration::ZERO);
    assert_eq!(
        progress,
        Progress::Failed(SdoError::Client(AbortCode::InvalidCommandSpecifier))
    );
}

#[test]
fn a_download_initiate_answered_as_an_upload_aborts() {
    let mut transfer = client().download(0x200A, 0, &[1, 2, 3, 4, 5], Duration::ZERO);
    assert_eq!(
        transfer.poll_transmit(),
        Some(request([0x21, 0x0A, 0x20, 0, 5, 0, 0, 0]))
    );
    let progress = transfer.handle(&response([0x43, 0x0A, 0x20, 0, 0, 0, 0, 0]), Duration::ZERO);
    assert_eq!(
        progress,
        Progress::Failed(SdoError::Client(AbortCode::InvalidCommandSpecifier))
    );
}

#[test]
fn a_server_abort_in_the_middle_of_a_segmented_download() {
    let mut transfer = client().download(0x200B, 0, &[0; 30], Duration::ZERO);
    transfer.poll_transmit();
    transfer.handle(&response([0x60, 0x0B, 0x20, 0, 0, 0, 0, 0]), Duration::ZERO);
    transfer.poll_transmit();
    let abort = response([0x80, 0x0B, 0x20, 0, 0x20, 0, 0, 0x08]);
    assert_eq!(
        transfer.handle(&abort, Duration::ZERO),
        Progress::Failed(SdoError::Server(AbortCode::CannotStore))
    );
    assert_eq!(transfer.poll_transmit(), None);
    assert_eq!(
        transfer.handle_timeout(Duration::from_secs(60)),
        Progress::Pending,
        "finished transfers do not time out"
    );
}

// --- Property tests: random lengths through every mode. ---

#[derive(Debug, Clone, Copy)]
enum Mode {
    Normal,
    Block(u8),
}

fn lengths() -> impl Strategy<Value = usize> {
    prop_oneof![
        Just(0usize),
        Just(7),
        Just(8),
        Just(889),
        Just(890),
        0usize..1200
    ]
}

fn modes() -> impl Strategy<Value = Mode> {
    prop_oneof![Just(Mode::Normal), (1u8..=127).prop_map(Mode::Block)]
}

fn roundtrip(value: &[u8], mode: Mode) -> Result<(), TestCaseError> {
    let mut server = server(&[((0x2200, 1), &[])]);
    if let Mode::Block(size) = mode {
        server = server.with_block_size(size);
    }
    let download = match mode {
        Mode::Normal => pump(
            &mut client().download(0x2200, 1, value, Duration::ZERO),
            &mut server,
            clean,
        ),
        Mode::Block(_) => pump(
            &mut client().block_download(0x2200, 1, value, Duration::ZERO),
            &mut server,
            clean,
        ),
    };
    prop_assert_eq!(download.progress, Progress::Done(value.len()));
    prop_assert_eq!(&server.dictionary()[&(0x2200, 1)], value);
    let mut buf = vec![0u8; value.len() + 3];
    let upload = match mode {
        Mode::Normal => pump(
            &mut client().upload(0x2200, 1, &mut buf, Duration::ZERO),
            &mut server,
            clean,
        ),
        Mode::Block(size) => pump(
            &mut client().block_upload(0x2200, 1, &mut buf, size, Duration::ZERO),
            &mut server,
            clean,
        ),
    };
    prop_assert_eq!(upload.progress, Progress::Done(value.len()));
    prop_assert_eq!(&buf[..value.len()], value);
    Ok(())
}

#[test]
fn boundary_lengths_round_trip_in_every_mode() {
    for len in [0usize, 1, 4, 5, 7, 8, 14, 15, 889, 890] {
        let value: Vec<u8> = (0..len).map(|i| (i * 31 + 7) as u8).collect();
        for mode in [Mode::Normal, Mode::Block(1), Mode::Block(127)] {
            roundtrip(&value, mode).unwrap_or_else(|e| panic!("{len} bytes, {mode:?}: {e}"));
        }
    }
}

proptest! {
    #[test]
    fn transfers_of_any_length_round_trip(
        value in lengths().prop_flat_map(|len| proptest::collection::vec(any::<u8>(), len)),
        mode in modes(),
    ) {
        roundtrip(&value, mode)?;
    }

    /// A lost segment inside a block is repeated after the acknowledgement; a lost block end
    /// leaves the client waiting, so it times out and aborts.
    #[test]
    fn block_uploads_with_one_lost_segment(len in 8usize..900, lost in 1u8..=20, size in 2u8..=20) {
        let first_block = size.min(len.div_ceil(7) as u8);
        prop_assume!(lost <= first_block);
        let value: Vec<u8> = (0..len).map(|i| i as u8).collect();
        let mut server = server(&[((0x2201, 0), &value)]);
        let mut buf = vec![0u8; len];
        let mut dropped = false;
        let outcome = pump(
            &mut client().block_upload(0x2201, 0, &mut buf, size, Duration::ZERO),
            &mut server,
            |dir, frame| {
                // The first frame after the initiate response with this sequence number.
                let is_segment = frame.data()[0] & 0x7F == lost && frame.data()[0] & 0xE0 != 0xC0;
                if dir == Dir::ToClient && is_segment && !dropped {
                    dropped = true;
                    return vec![];
                }
                vec![frame]
            },
        );
        if lost == first_block {
            prop_assert_eq!(outcome.progress, Progress::Failed(SdoError::Client(AbortCode::ProtocolTimedOut)));
            prop_assert_eq!(outcome.sent.last(), Some(&abort_frame(0x2201, 0, AbortCode::ProtocolTimedOut)));
        } else {
            prop_assert_eq!(outcome.progress, Progress::Done(len));
            prop_assert_eq!(buf, value);
        }
    }
}

// --- Frames cut short (found by the soak: a truncated upload response read as zeros). ---

#[test]
fn a_response_cut_short_is_not_taken_for_data() {
    let mut buf = [0u8; 2];
    let mut transfer = client().upload(0x2102, 0, &mut buf, Duration::ZERO);
    transfer.poll_transmit();
    // "4B 02 21 00 34 12 00 00" with its last four bytes lost: padded, it would read 0x0034.
    let cut = CanFrame::new(0x585, &[0x4B, 0x02, 0x21, 0x00, 0x34]).unwrap();
    assert_eq!(transfer.handle(&cut, Duration::ZERO), Progress::Pending);
    assert_eq!(transfer.poll_transmit(), None, "nothing to abort");
    let whole = response([0x4B, 0x02, 0x21, 0x00, 0x34, 0x12, 0, 0]);
    assert_eq!(transfer.handle(&whole, Duration::ZERO), Progress::Done(2));
    assert_eq!(buf, [0x34, 0x12]);
}

#[test]
fn a_request_cut_short_is_not_executed() {
    let mut server = server(&[((0x2102, 0), &[0x78, 0x56])]);
    // "2B 02 21 00 34 12 00 00" cut after the first value byte: padded, it would write 0x0034.
    let cut = CanFrame::new(0x605, &[0x2B, 0x02, 0x21, 0x00, 0x34]).unwrap();
    assert_eq!(server.handle(&cut), Vec::<CanFrame>::new());
    assert_eq!(server.dictionary()[&(0x2102, 0)], [0x78, 0x56]);
    let whole = request([0x2B, 0x02, 0x21, 0x00, 0x34, 0x12, 0, 0]);
    assert_eq!(
        server.handle(&whole),
        vec![response([0x60, 0x02, 0x21, 0x00, 0, 0, 0, 0])]
    );
    assert_eq!(server.dictionary()[&(0x2102, 0)], [0x34, 0x12]);
}

// --- A client that never stops sending: the server's buffer is bounded. ---

/// Sends a segmented download to 2100h:00 of endless 7-byte segments; returns how many segments
/// the server took before its answer was an abort, and that answer.
fn endless_segmented_download<D: ObjectDictionary>(server: &mut SdoServer<D>) -> (usize, CanFrame) {
    let initiate = server.handle(&request([0x21, 0x00, 0x21, 0x00, 0, 0, 0, 0]));
    assert_eq!(
        initiate,
        vec![response([0x60, 0x00, 0x21, 0x00, 0, 0, 0, 0])]
    );
    for segment in 0..100_000 {
        let toggle = ((segment % 2) as u8) << 4;
        let answer = server.handle(&request([toggle, 1, 2, 3, 4, 5, 6, 7]));
        if answer[0].data()[0] == 0x80 {
            return (segment, answer[0]);
        }
    }
    panic!("the server buffered 700,000 bytes of one download");
}

#[test]
fn an_endless_segmented_download_is_aborted_at_the_limit() {
    let mut bounded = server(&[((0x2100, 0), &[0])]).with_max_download(20);
    let (segments, abort) = endless_segmented_download(&mut bounded);
    assert_eq!(segments, 2, "21 bytes are over the limit");
    assert_eq!(
        abort,
        response([0x80, 0x00, 0x21, 0x00, 0x05, 0x00, 0x04, 0x05])
    );
    let (segments, _) = endless_segmented_download(&mut server(&[((0x2100, 0), &[0])]));
    assert_eq!(segments, server::DEFAULT_MAX_DOWNLOAD / 7);
}

#[test]
fn an_endless_block_download_is_aborted_at_the_limit() {
    let mut server = server(&[((0x2100, 0), &[0])]).with_max_download(20);
    let initiate = server.handle(&request([0xC0, 0x00, 0x21, 0x00, 0, 0, 0, 0]));
    assert_eq!(initiate[0].data()[0], 0xA4);
    let answers: Vec<CanFrame> = (1..=3)
        .flat_map(|seq| server.handle(&request([seq, 1, 2, 3, 4, 5, 6, 7])))
        .collect();
    assert_eq!(
        answers,
        vec![response([0x80, 0x00, 0x21, 0x00, 0x05, 0x00, 0x04, 0x05])],
        "the third segment (21 bytes) is over the limit"
    );
    // The transfer is over: the next download starts afresh.
    assert_eq!(
        server.handle(&request([0x2F, 0x00, 0x21, 0x00, 9, 0, 0, 0])),
        vec![response([0x60, 0x00, 0x21, 0x00, 0, 0, 0, 0])]
    );
}
