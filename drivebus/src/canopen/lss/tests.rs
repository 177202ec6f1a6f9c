//! Frame layouts checked against python canopen 2.4.1's `LssMaster` (`canopen/lss.py`), which
//! packs each command as CiA 305 lays it out.

use super::command::RangePart;
use super::*;
use crate::canopen::frame::CanFrame;
use crate::canopen::NodeId;

fn answer(data: [u8; 8]) -> CanFrame {
    CanFrame::new(SLAVE_COB, &data).unwrap()
}

#[test]
fn commands_are_framed_as_python_canopen_frames_them() {
    let cases: [(Command, [u8; 8]); 8] = [
        // send_switch_state_global(CONFIGURATION_STATE): message[0] = 0x04, message[1] = mode.
        (
            Command::SwitchGlobal(LssMode::Configuration),
            [0x04, 1, 0, 0, 0, 0, 0, 0],
        ),
        // __send_lss_address(0x43, serial): struct.pack('<I') into bytes 1-4.
        (
            Command::SwitchSelective(IdentityWord::Serial, 0x1234_5678),
            [0x43, 0x78, 0x56, 0x34, 0x12, 0, 0, 0],
        ),
        // __send_configure(0x11, 5).
        (
            Command::ConfigureNodeId(NewNodeId::Id(NodeId(5))),
            [0x11, 5, 0, 0, 0, 0, 0, 0],
        ),
        // configure_bit_timing(2): __send_configure(0x13, 0, 2).
        (
            Command::ConfigureBitTiming { table: 0, index: 2 },
            [0x13, 0, 2, 0, 0, 0, 0, 0],
        ),
        // activate_bit_timing(1000): '<H' into bytes 1-2.
        (
            Command::ActivateBitTiming { delay_ms: 1000 },
            [0x15, 0xE8, 0x03, 0, 0, 0, 0, 0],
        ),
        (Command::Store, [0x17, 0, 0, 0, 0, 0, 0, 0]),
        (Command::InquireNodeId, [0x5E, 0, 0, 0, 0, 0, 0, 0]),
        // __send_fast_scan_message: struct.pack('<BIBBB', 0x51, id, bit, sub, next).
        (
            Command::Fastscan {
                id: 0xA0B0_C0D0,
                bit: 31,
                sub: 3,
                next: 0,
            },
            [0x51, 0xD0, 0xC0, 0xB0, 0xA0, 31, 3, 0],
        ),
    ];
    for (command, bytes) in cases {
        let frame = command.encode();
        assert_eq!(
            (frame.id(), frame.data()),
            (MASTER_COB, &bytes[..]),
            "{command:?}"
        );
        assert_eq!(Command::decode(&frame), Some(command), "decodes back");
    }
}

#[test]
fn every_range_part_and_inquiry_decodes_back() {
    for part in RangePart::ALL {
        let command = Command::IdentifyRemote(part, 7);
        assert_eq!(Command::decode(&command.encode()), Some(command));
    }
    for word in IdentityWord::ALL {
        let command = Command::Inquire(word);
        assert_eq!(Command::decode(&command.encode()), Some(command));
    }
}

#[test]
fn node_ids_0_and_128_to_254_cannot_be_configured() {
    for raw in [0u8, 128, 200, 254] {
        assert_eq!(NewNodeId::new(raw), Err(LssError::InvalidNodeId(raw)));
    }
    assert_eq!(NewNodeId::new(1), Ok(NewNodeId::Id(NodeId(1))));
    assert_eq!(NewNodeId::new(127), Ok(NewNodeId::Id(NodeId(127))));
    assert_eq!(NewNodeId::new(255), Ok(NewNodeId::Unconfigured));
}

#[test]
fn answers_decode_into_typed_values_and_error_codes() {
    let cases = [
        ([0x44, 0, 0, 0, 0, 0, 0, 0], Response::SwitchSelective),
        (
            [0x11, 0, 0, 0, 0, 0, 0, 0],
            Response::Confirmed(Confirmed::NodeId, Ok(())),
        ),
        (
            [0x11, 1, 0, 0, 0, 0, 0, 0],
            Response::Confirmed(Confirmed::NodeId, Err(ConfigureError::NodeIdOutOfRange)),
        ),
        (
            [0x13, 1, 0, 0, 0, 0, 0, 0],
            Response::Confirmed(
                Confirmed::BitTiming,
                Err(ConfigureError::BitTimingNotSupported),
            ),
        ),
        (
            [0x17, 2, 0, 0, 0, 0, 0, 0],
            Response::Confirmed(Confirmed::Store, Err(ConfigureError::StorageAccess)),
        ),
        (
            [0x13, 0xFF, 9, 0, 0, 0, 0, 0],
            Response::Confirmed(
                Confirmed::BitTiming,
                Err(ConfigureError::Vendor {
                    command: Confirmed::BitTiming,
                    specific: 9,
                }),
            ),
        ),
        (
            [0x5D, 0x04, 0x03, 0x02, 0x01, 0, 0, 0],
            Response::Inquired(IdentityWord::Serial, 0x0102_0304),
        ),
        ([0x5E, 0xFF, 0, 0, 0, 0, 0, 0], Response::NodeId(0xFF)),
        ([0x4F, 0, 0, 0, 0, 0, 0, 0], Response::IdentifySlave),
        ([0x50, 0, 0, 0, 0, 0, 0, 0], Response::IdentifyNonConfigured),
    ];
    for (bytes, response) in cases {
        assert_eq!(
            Response::decode(&answer(bytes)),
            Some(response),
            "{bytes:02X?}"
        );
        assert_eq!(response.to_bytes(), bytes, "encodes back");
    }
}

#[test]
fn frames_that_are_not_lss_answers_decode_to_nothing() {
    let not_answers = [
        CanFrame::new(MASTER_COB, &[0x44, 0, 0, 0, 0, 0, 0, 0]).unwrap(),
        CanFrame::new(SLAVE_COB, &[]).unwrap(),
        CanFrame::new(SLAVE_COB, &[0x5A, 1, 2]).unwrap(),
        CanFrame::new(SLAVE_COB, &[0x11]).unwrap(),
        CanFrame::new(SLAVE_COB, &[0x99, 0, 0, 0, 0, 0, 0, 0]).unwrap(),
        CanFrame::remote(SLAVE_COB, 8).unwrap(),
    ];
    for frame in not_answers {
        assert_eq!(Response::decode(&frame), None, "{frame:?}");
    }
}

#[test]
fn a_selective_switch_fails_on_a_second_answer_within_the_settle_time() {
    let ms = core::time::Duration::from_millis;
    let commands = IdentityWord::ALL.map(|w| Command::SwitchSelective(w, 1));
    let mut exchange = Exchange::new(&commands, ms(100), ms(0));
    let sent = core::iter::from_fn(|| exchange.poll_transmit()).count();
    assert_eq!(sent, 4);
    let yes = answer([0x44, 0, 0, 0, 0, 0, 0, 0]);
    assert_eq!(exchange.handle(&yes, ms(5)), Progress::Pending);
    assert_eq!(
        exchange.deadline(),
        Some(ms(25)),
        "settles a fifth of the timeout"
    );
    assert_eq!(
        exchange.handle(&yes, ms(6)),
        Progress::Failed(LssError::SeveralAnswers)
    );
}

#[test]
fn an_unanswered_command_fails_at_its_deadline_and_not_before() {
    let ms = core::time::Duration::from_millis;
    let mut exchange = Exchange::single(Command::InquireNodeId, ms(50), ms(10));
    assert!(exchange.poll_transmit().is_some());
    assert_eq!(exchange.handle_timeout(ms(59)), Progress::Pending);
    assert_eq!(
        exchange.handle_timeout(ms(60)),
        Progress::Failed(LssError::NoAnswer)
    );
}
