//! The SDO server fed arbitrary client frames.
//!
//! Input: `[block size, frames...]`, each frame `[shape, 8 data bytes]` (see src/can_input.rs).
//! Asserts that
//! * the server answers only frames on its request COB-ID, only with full 8-byte data frames on
//!   its response COB-ID, at most one block of them at a time;
//! * it never adds or removes objects;
//! * an expedited download it confirms stored exactly the bytes sent, an expedited upload
//!   answers exactly the bytes stored;
//! * after any sequence, a client's abort brings it back: a fresh upload of every object reads
//!   the stored bytes.
#![no_main]

use std::collections::BTreeMap;
use std::time::Duration;

use drivebus::canopen::sdo::server::SdoServer;
use drivebus::canopen::sdo::{Progress, SdoClient, Transfer};
use drivebus::canopen::{CanFrame, NodeId};
use fuzz::{can_input, Cursor};
use libfuzzer_sys::fuzz_target;

const NODE: u8 = 3;
const REQUEST_COB: u16 = 0x600 + NODE as u16;
const RESPONSE_COB: u16 = 0x580 + NODE as u16;

type Dictionary = BTreeMap<(u16, u8), Vec<u8>>;

/// Objects of every transfer kind's size: expedited, segmented, several blocks.
fn dictionary() -> Dictionary {
    BTreeMap::from([
        ((0x1000, 0), vec![0x92, 0x01, 0x02, 0x00]),
        ((0x1008, 0), b"drivegen fuzz".to_vec()),
        ((0x2000, 1), vec![0x34, 0x12]),
        ((0x2001, 0), (0..=255).collect()),
    ])
}

fuzz_target!(|data: &[u8]| {
    let mut input = Cursor::new(data);
    let block_size = input.u8();
    let node = NodeId::new(NODE).expect("a node id");
    let mut server = SdoServer::new(node, dictionary()).with_block_size(block_size);
    let keys: Vec<_> = dictionary().into_keys().collect();
    while let Some(frame) = can_input::read(&mut input, REQUEST_COB) {
        let answers = server.handle(&frame);
        check_answers(&frame, &answers);
        check_expedited(&frame, &answers, server.dictionary());
        let now: Vec<_> = server.dictionary().keys().copied().collect();
        assert_eq!(now, keys, "objects added or removed");
    }
    let abort = CanFrame::new(REQUEST_COB, &[0x80, 0, 0, 0, 0, 0, 0, 0]).expect("a frame");
    assert!(
        server.handle(&abort).is_empty(),
        "the server answered an abort"
    );
    for key in keys {
        let stored = server.dictionary()[&key].clone();
        assert_eq!(
            upload(&mut server, node, key),
            stored,
            "upload of {key:04X?}"
        );
    }
});

/// Answers go to the response COB-ID, full data frames, at most a block; none to foreign frames.
fn check_answers(frame: &CanFrame, answers: &[CanFrame]) {
    if frame.id() != REQUEST_COB || frame.is_remote() {
        assert!(
            answers.is_empty(),
            "answered a frame not meant for it: {frame:?}"
        );
    }
    assert!(
        answers.len() <= 127,
        "{} answers to one frame",
        answers.len()
    );
    for answer in answers {
        assert_eq!(answer.id(), RESPONSE_COB);
        assert!(
            !answer.is_remote() && answer.dlc() == 8,
            "answered {answer:?}"
        );
    }
}

/// A confirmed expedited download stored its bytes; an expedited upload answers what is stored.
fn check_expedited(frame: &CanFrame, answers: &[CanFrame], dictionary: &Dictionary) {
    let [answer] = answers else {
        return;
    };
    let request = frame.padded();
    let answer = answer.padded();
    if request[1..4] != answer[1..4] {
        return;
    }
    let key = (u16::from_le_bytes([request[1], request[2]]), request[3]);
    let expedited = |command: u8| command & 0b11 == 0b11;
    let width = |command: u8| 4 - usize::from((command >> 2) & 0b11);
    if request[0] >> 5 == 1 && expedited(request[0]) && answer[0] == 0x60 {
        let sent = &request[4..4 + width(request[0])];
        assert_eq!(dictionary[&key], sent, "confirmed download of {key:04X?}");
    }
    if request[0] >> 5 == 2 && answer[0] >> 5 == 2 && expedited(answer[0]) {
        let answered = &answer[4..4 + width(answer[0])];
        assert_eq!(dictionary[&key], answered, "expedited upload of {key:04X?}");
    }
}

/// Reads `key` with a fresh client through `server`.
fn upload(server: &mut SdoServer<Dictionary>, node: NodeId, key: (u16, u8)) -> Vec<u8> {
    let client = SdoClient::new(node, Duration::from_millis(100));
    let mut buf = vec![0u8; 1024];
    let mut transfer = client.upload(key.0, key.1, &mut buf, Duration::ZERO);
    let mut rounds = 0;
    let len = loop {
        rounds += 1;
        assert!(rounds < 1000, "the upload of {key:04X?} never ends");
        let request = transfer.poll_transmit().expect("the client has a request");
        let mut done = None;
        for answer in server.handle(&request) {
            match transfer.handle(&answer, Duration::ZERO) {
                Progress::Pending => {}
                Progress::Done(len) => done = Some(len),
                Progress::Failed(e) => panic!("the upload of {key:04X?} failed: {e:?}"),
            }
        }
        if let Some(len) = done {
            break len;
        }
    };
    buf.truncate(len);
    buf
}
