//! The manual's worked examples the fidelity review found untested (its section 5): the
//! heartbeat the quick start expects (0x710 = 05h, line 4148), the statusword upload answer as
//! printed (line 4172), halt (line 4184 and the decision in ERRATA.md), the alternative SRDO 1
//! frames of step 4 (lines 4119-4120), the CRC table (lines 3516-3551), the error register bits
//! (lines 1587-1596), the safety function output bits (lines 3220-3232) and the PDO remapping
//! procedure to its end (lines 1443-1453), and the ramp on a reversal (line 2620).

mod support;

use std::time::{Duration, Instant};

use drivebus::canopen::nmt::{decode_heartbeat, NmtCommand, NmtState};
use drivebus::canopen::pdo::COB_ID_INVALID;
use drivebus::canopen::{CanBus, CanFrame, NodeId, SdoBus};
use drivebus::control::State;
use drivebus::units::Milliseconds;
use ezwheel_swd::srdo::SafetyControl1;
use ezwheel_swd::types::{
    Controlword, ErrorRegister, SafetyFunctionOutput1, SafetyFunctionOutput2,
};
use ezwheel_swd::{HALT, VL_OPERATION_ENABLED};
use support::simulated_swd::{start, NODE};

fn deadline() -> Instant {
    Instant::now() + Duration::from_secs(3)
}

#[test]
fn after_the_nmt_start_the_heartbeat_on_0x710_is_05h() {
    // Step 6.a (lines 4146-4148): "000#01 10" starts node 10h; its heartbeat (CAN-ID 700h + node
    // id) then carries 05h, Operational. The manual gives no default for the producer heartbeat
    // time 1017h (only named, line 1995): it is set to 20 ms first.
    let (mut drive, _node) = start();
    drive
        .producer_heartbeat_time()
        .write(Milliseconds(20.0))
        .unwrap();
    let bus = drive.device().link_mut().bus_mut().bus_mut();
    let start_frame = NmtCommand::Start.frame(Some(NodeId(NODE)));
    assert_eq!(
        (start_frame.id(), start_frame.data()),
        (0x000, &[0x01, 0x10][..])
    );
    bus.send(&start_frame).unwrap();
    let until = Instant::now() + Duration::from_secs(2);
    let mut seen = Vec::new();
    let last = loop {
        let frame = bus
            .recv(Duration::from_millis(500))
            .unwrap()
            .expect("heartbeats keep coming");
        if frame.id() == 0x710 && frame.data() == [0x05] {
            break frame;
        }
        seen.push((frame.id(), frame.data().to_vec()));
        assert!(Instant::now() < until, "no 710h = 05h; frames: {seen:02X?}");
    };
    assert_eq!((last.id(), last.data()), (0x710, &[0x05][..]));
    assert_eq!(
        decode_heartbeat(&last),
        Some((NodeId(NODE), NmtState::Operational))
    );
}

#[test]
fn the_statusword_upload_is_answered_as_printed() {
    // Lines 4171-4172: request 610h "40 41 60 00 00 00 00 00", response 590h
    // "4B 41 60 00 XX 00 00 00" (4Bh: expedited upload of 2 bytes).
    let (mut drive, _node) = start();
    let bus = drive.device().link_mut().bus_mut().bus_mut();
    let request = CanFrame::new(0x610, &[0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0]).unwrap();
    bus.send(&request).unwrap();
    let answer = loop {
        let frame = bus
            .recv(Duration::from_millis(500))
            .unwrap()
            .expect("the node answers");
        if frame.id() == 0x590 {
            break frame;
        }
    };
    assert_eq!(answer.data()[..4], [0x4B, 0x41, 0x60, 0x00]);
    assert_eq!(answer.data()[6..], [0x00, 0x00]);
    // XX: switch on disabled after power-up (0040h, line 2390).
    assert_eq!(answer.data()[4..6], [0x40, 0x00]);
}

#[test]
fn halt_is_bit_8_and_keeps_the_drive_in_operation_enabled() {
    // The quick start's "Halt" frame (line 4184) writes 0040h: bit 6, the vl ramp reference,
    // not the halt bit 8 of the controlword (lines 2319, 2637). ERRATA.md: the crate halts with
    // bit 8 and keeps the other bits.
    let printed = Controlword::from_bits_retain(0x0040);
    assert!(printed.contains(Controlword::OPERATION_MODE_SPECIFIC_6));
    assert!(!printed.contains(Controlword::from_bits_retain(HALT)));

    let (mut drive, _node) = start();
    drive.start_velocity_mode(deadline()).unwrap();
    drive.halt(true).unwrap();
    assert_eq!(
        drive.controlword().read().unwrap().bits(),
        VL_OPERATION_ENABLED | HALT
    );
    // Both halt option codes (605Dh, lines 2776-2777) "stay in operation enabled".
    assert!(matches!(
        drive.halt_option_code().read_raw().unwrap(),
        1 | 2
    ));
    assert_eq!(drive.cia402_state().unwrap(), Some(State::OperationEnabled));
    drive.halt(false).unwrap();
    assert_eq!(drive.cia402_state().unwrap(), Some(State::OperationEnabled));
}

#[test]
fn srdo1_frames_of_step_4_are_the_generated_structs_encoding() {
    // Lines 4119-4120: SRDO 1 carries controlword FFh on 11Fh and its inverse 00h on 120h.
    let normal = SafetyControl1 {
        safety_controlword_1: 0xFF,
    }
    .encode()
    .unwrap();
    let producer = SafetyControl1::producer(NodeId(NODE)).unwrap();
    let [first, second] = producer.pair(normal.as_bytes()).unwrap();
    assert_eq!((first.id(), first.data()), (0x11F, &[0xFF][..]));
    assert_eq!((second.id(), second.data()), (0x120, &[0x00][..]));
}

/// The 256 values of the printed table, tolerating its typo "0xbfba u" (line 3550).
fn printed_crc_table() -> Vec<u16> {
    include_str!("manual_crc_table.txt")
        .lines()
        .filter(|line| !line.starts_with('#'))
        .flat_map(|line| line.split(','))
        .filter_map(|cell| {
            let cell = cell.replace(' ', "");
            let hex = cell.strip_prefix("0x")?.strip_suffix('u')?.to_owned();
            Some(u16::from_str_radix(&hex, 16).unwrap())
        })
        .collect()
}

#[test]
fn the_printed_crc_table_is_the_msb_first_0x1021_table() {
    // Lines 3502-3562: CRC-16-CCITT, polynomial x^16 + x^12 + x^5 + 1, start value 0.
    let table = printed_crc_table();
    assert_eq!(table.len(), 256);
    for (byte, printed) in table.iter().enumerate() {
        let mut crc = (byte as u16) << 8;
        for _ in 0..8 {
            crc = if crc & 0x8000 != 0 {
                (crc << 1) ^ 0x1021
            } else {
                crc << 1
            };
        }
        assert_eq!(*printed, crc, "entry {byte:#04x}");
    }
    // The table drives the signature the crate computes: the quick start's BABDh over SRDO 1
    // with direction 0 (line 4111) is reproduced through it.
    let signed = {
        let mut config = SafetyControl1::config(NodeId(NODE));
        config.communication.direction = drivebus::canopen::srdo::SrdoDirection::Invalid;
        drivebus::canopen::srdo::signature(&config).unwrap()
    };
    assert_eq!(signed, 0xBABD);
}

#[test]
fn error_register_bits_are_the_printed_classes() {
    // Lines 1589-1596: 0 generic, 1 current, 2 voltage, 3 temperature, 4 communication,
    // 5 device specific, 6 reserved, 7 manufacturer specific.
    for (bit, flag) in [
        (0, ErrorRegister::GENERIC),
        (1, ErrorRegister::CURRENT),
        (2, ErrorRegister::VOLTAGE),
        (3, ErrorRegister::TEMPERATURE),
        (4, ErrorRegister::COMMUNICATION),
        (5, ErrorRegister::DEVICE_PROFILE),
        (7, ErrorRegister::MANUFACTURER),
    ] {
        assert_eq!(flag.bits(), 1 << bit, "bit {bit}");
    }
    // An undervoltage error (EMCY 3221h) with generic and voltage set: 05h.
    let register = ErrorRegister::from_bits_retain(0x05);
    assert!(register.contains(ErrorRegister::GENERIC | ErrorRegister::VOLTAGE));
    assert!(!register.contains(ErrorRegister::CURRENT));
}

#[test]
fn safety_function_output_bits_are_the_printed_layout() {
    // Lines 3222-3226: bit 0 STO, 1-3 SBC_1..3, 4-11 SLS_1..8, 12-13 SDI_P_1..2, 14-15 SDI_N_1..2.
    let out1 = SafetyFunctionOutput1::from_bits_retain(0x8011);
    assert!(out1.contains(SafetyFunctionOutput1::STO));
    assert!(out1.contains(SafetyFunctionOutput1::SLS_1));
    assert!(out1.contains(SafetyFunctionOutput1::SDI_N_2));
    assert!(!out1.contains(SafetyFunctionOutput1::SBC_1));
    assert_eq!(SafetyFunctionOutput1::SBC_3.bits(), 1 << 3);
    assert_eq!(SafetyFunctionOutput1::SDI_P_1.bits(), 1 << 12);
    // Lines 3229-3232: bit 0 ERROR_ACK, 1 RESTART_ACK, 2 SBU, 3 SMS, 4-11 SLSa_1..8.
    assert_eq!(SafetyFunctionOutput2::ERROR_ACK.bits(), 1 << 0);
    assert_eq!(SafetyFunctionOutput2::RESTART_ACK.bits(), 1 << 1);
    assert_eq!(SafetyFunctionOutput2::SBU.bits(), 1 << 2);
    assert_eq!(SafetyFunctionOutput2::SMS.bits(), 1 << 3);
    assert_eq!(SafetyFunctionOutput2::SLSA_8.bits(), 1 << 11);
}

#[test]
fn a_reversal_decelerates_to_zero_then_accelerates() {
    // Line 2620: "When the setpoint direction is reversed, the nominal deceleration ramp is used
    // to return to zero speed. The acceleration ramp is then used to reach the new setpoint."
    // Deceleration 1000 rpm/s, acceleration 500 rpm/s (the default, lines 2643-2644), so the
    // two ramps are told apart.
    use drivebus::canopen::sdo::server::ObjectDictionary;
    let sim = drivesim::Simulator::load(support::simulated_swd::DESCRIPTION).unwrap();
    let device = sim.with(|drive| drive.store().device().clone());
    let mut od = drivesim::canopen::Dictionary::new(sim.clone(), &device, sim.variant());
    od.write(0x6049, 1, &1000u32.to_le_bytes()).unwrap();
    for word in [0x06u16, 0x07, 0x0F, 0x7F] {
        od.write(0x6040, 0, &word.to_le_bytes()).unwrap();
    }
    let speed = |od: &mut drivesim::canopen::Dictionary| {
        i32::from_le_bytes(od.read(0x606C, 0).unwrap().try_into().unwrap())
    };
    od.write(0x6042, 0, &500i16.to_le_bytes()).unwrap();
    sim.with(|drive| drive.tick(Duration::from_secs(2)));
    assert_eq!(speed(&mut od), 500);
    od.write(0x6042, 0, &(-500i16).to_le_bytes()).unwrap();
    // 0.25 s on the deceleration ramp: 500 - 250 = 250 (the acceleration ramp would give 375).
    sim.with(|drive| drive.tick(Duration::from_millis(250)));
    let after_quarter = speed(&mut od);
    assert!((240..=260).contains(&after_quarter), "{after_quarter}");
    // Zero after 0.5 s, then -100 after another 0.2 s on the acceleration ramp (500 rpm/s).
    sim.with(|drive| drive.tick(Duration::from_millis(450)));
    let after = speed(&mut od);
    assert!((-110..=-90).contains(&after), "{after}");
}

#[test]
fn the_remapping_procedure_ends_with_save_reset_and_start() {
    // Lines 1443-1453 on the simulated SWD, steps 1-9 for TPDO 2 (not valid by default, line
    // 1325): pre-operational, disable, unmap, map, enable mapping, valid, save, reset
    // communication, start.
    let (mut drive, _node) = start();
    let node = NodeId(NODE);
    let nmt = |drive: &mut support::simulated_swd::SimulatedSwd, command: NmtCommand| {
        let bus = drive.device().link_mut().bus_mut().bus_mut();
        bus.send(&command.frame(Some(node))).unwrap();
        std::thread::sleep(Duration::from_millis(30));
    };
    nmt(&mut drive, NmtCommand::EnterPreOperational);
    let cob_id = drive.tpdo2_cob_id().read().unwrap();
    assert_ne!(cob_id & COB_ID_INVALID, 0, "not valid by default");
    let bus = drive.device().link_mut().bus_mut();
    bus.download(node, 0x1A01, 0, &[0]).unwrap();
    bus.download(node, 0x1A01, 1, &0x6041_0010u32.to_le_bytes())
        .unwrap();
    bus.download(node, 0x1A01, 2, &0x6064_0020u32.to_le_bytes())
        .unwrap();
    bus.download(node, 0x1A01, 0, &[2]).unwrap();
    bus.download(node, 0x1801, 1, &0x4000_0290u32.to_le_bytes())
        .unwrap();
    // Step 7: save the communication parameters ("save" to 1010h; sub 1, the one supported,
    // lines 1950-1952).
    bus.download(node, 0x1010, 1, b"save").unwrap();
    nmt(&mut drive, NmtCommand::ResetCommunication);
    nmt(&mut drive, NmtCommand::Start);
    assert_eq!(drive.tpdo2_cob_id().read().unwrap(), 0x4000_0290);
    assert_eq!(drive.tpdo2_mapping_count().read().unwrap(), 2);
    assert_eq!(drive.tpdo2_mapping_entry(2).read().unwrap(), 0x6064_0020);
}
