//! The Lenze smd run from its description alone (no smd code in the simulator): Start and Stop
//! through register #1, the output frequency #25 ramping to the serial speed #40 with C12 / C13,
//! the operational status of Table 11 in #26 DL, the serial watchdog's n22 actions, FC 04 read
//! as FC 03, several bits in one write to #1, FC 16 with one register, and no broadcast. Requests
//! are Modbus PDUs given to the sans-I/O server; time is advanced by hand. Line numbers are those
//! of the manual, shared/seeds/004_e90b7fce7c8d5710.txt.

use std::time::Duration;

use drivebus::modbus::UnitId;
use drivesim::modbus::{ModbusServer, Units};
use drivesim::{Drive, Simulator};

const DESCRIPTION: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../descriptions/lenze-smd");

/// Table 11 (lines 668-681): the operational status, #26 DL.
const FAULT: u16 = 1;
const STOP: u16 = 3;
const RUN_AT_0HZ: u16 = 5;
const RUN: u16 = 6;
const ACCEL: u16 = 7;
const DECEL: u16 = 8;
const INHIBIT: u16 = 13;

/// Table 8 (lines 542-551) and section 7.3 (lines 1069-1072).
const CMD_STOP: u16 = 0x0004;
const CMD_START: u16 = 0x0008;
const CMD_SERIAL_REFERENCE: u16 = 0x0100;

/// Registers (Table 6 and the PC507 column of section 6.2).
const COMMAND_SPEED: u16 = 24;
const ACTUAL_SPEED: u16 = 25;
const LOAD_AND_STATUS: u16 = 26;
const SERIAL_SPEED: u16 = 40;
const C12_PC507: u16 = 61;
const C13_PC507: u16 = 62;
const C61_PC507: u16 = 110;
const N22_PC507: u16 = 132;
const N23_PC507: u16 = 133;

/// A PC507 drive under Modbus control (C01 = 11, section 7.1 step 1) and its server.
struct Smd {
    drive: Drive,
    server: ModbusServer,
}

impl Smd {
    fn new() -> Self {
        Self::configured(507)
    }

    /// A drive in parameter configuration `number` (400 or 507, section 3.3, line 314).
    fn configured(number: i128) -> Self {
        let checked = drivegen::check(std::path::Path::new(DESCRIPTION));
        let device = checked.device.expect("the smd description is valid");
        let server = ModbusServer::new(&device, Some(&format!("pc{number}")));
        let mut drive = Drive::new(device);
        for (name, value) in [("parameter_configuration", number), ("control_source", 11)] {
            let id = drive.store().id(name).unwrap();
            drive.preset(id, value);
        }
        Self { drive, server }
    }

    /// The answer PDU to `request`.
    fn ask(&mut self, request: &[u8]) -> Vec<u8> {
        let mut out = [0u8; 256];
        let len = self.server.handle(&mut self.drive, request, &mut out);
        out[..len].to_vec()
    }

    /// FC 03 (or FC 04) of one register.
    fn read_with(&mut self, function: u8, register: u16) -> u16 {
        let [hi, lo] = register.to_be_bytes();
        let answer = self.ask(&[function, hi, lo, 0x00, 0x01]);
        assert_eq!(
            answer[..2],
            [function, 0x02],
            "read #{register}: {answer:02x?}"
        );
        u16::from_be_bytes([answer[2], answer[3]])
    }

    fn read(&mut self, register: u16) -> u16 {
        self.read_with(0x03, register)
    }

    /// The operational status, #26 DL.
    fn status(&mut self) -> u16 {
        self.read(LOAD_AND_STATUS) & 0x00FF
    }

    /// FC 06; the answer PDU (the echo, or an exception).
    fn write(&mut self, register: u16, value: u16) -> Vec<u8> {
        let ([hi, lo], [vh, vl]) = (register.to_be_bytes(), value.to_be_bytes());
        self.ask(&[0x06, hi, lo, vh, vl])
    }

    fn write_ok(&mut self, register: u16, value: u16) {
        let answer = self.write(register, value);
        let ([hi, lo], [vh, vl]) = (register.to_be_bytes(), value.to_be_bytes());
        assert_eq!(
            answer,
            [0x06, hi, lo, vh, vl],
            "write {value:#06x} to #{register}"
        );
    }

    /// Section 4.9: unlock controls and parameters with the password C94 (factory 0) on #48,
    /// serial speed reference, the speed on #40.
    fn unlock_with_speed(&mut self, speed: u16) {
        self.write_ok(48, 0);
        self.write_ok(1, CMD_SERIAL_REFERENCE);
        self.write_ok(SERIAL_SPEED, speed);
    }

    /// Advances time by `ms`, with the master polling the status every 20 ms (section 4.8 step
    /// 8), so the watchdog stays fed.
    fn run_for(&mut self, ms: u64) {
        for _ in 0..ms / 20 {
            self.drive.tick(Duration::from_millis(20));
            self.status();
        }
    }

    /// Advances time by `ms` without a request.
    fn silence(&mut self, ms: u64) {
        self.drive.tick(Duration::from_millis(ms));
    }
}

#[test]
fn the_drive_powers_up_stopped_and_reports_its_family() {
    let mut smd = Smd::new();
    assert_eq!(smd.status(), STOP, "ERRATA.md E20");
    assert_eq!(smd.read(ACTUAL_SPEED), 0);
    // Note 2 (line 581): "The smd Series drives return 69 (45H)"; frame at line 478.
    assert_eq!(
        smd.ask(&[0x03, 0x00, 0x13, 0x00, 0x01]),
        [0x03, 0x02, 0x00, 0x45]
    );
    // Note 3 (line 590): #21 always reads zero.
    assert_eq!(smd.read(21), 0);
}

#[test]
fn start_ramps_the_output_to_the_serial_speed_with_c12() {
    let mut smd = Smd::new();
    // "412 would be 41.2 Hz" (line 1073); C12 = 5.0 s and C11 = 50.0 Hz (defaults, lines 889-890):
    // 10 Hz a second (ERRATA.md E21).
    smd.unlock_with_speed(412);
    smd.write_ok(1, CMD_START);
    assert_eq!(smd.status(), ACCEL);
    assert_eq!(smd.read(COMMAND_SPEED), 412);
    smd.run_for(1000);
    assert_eq!(smd.read(ACTUAL_SPEED), 100, "10.0 Hz after 1 s");
    assert_eq!(smd.status(), ACCEL);
    smd.run_for(3000);
    assert_eq!(smd.read(ACTUAL_SPEED), 400, "40.0 Hz after 4 s");
    smd.run_for(200);
    assert_eq!(smd.read(ACTUAL_SPEED), 412, "at the command");
    assert_eq!(smd.status(), RUN);
    // The 6-word block (Table 10, lines 621-632) shows the same: command, actual, load/status.
    let block = smd.ask(&[0x03, 0x00, 0x18, 0x00, 0x06]);
    assert_eq!(
        block[..8],
        [0x03, 0x0C, 0x01, 0x9C, 0x01, 0x9C, 0x00, RUN as u8]
    );
}

#[test]
fn a_shorter_c12_ramps_faster_and_c13_ramps_down() {
    let mut smd = Smd::new();
    smd.unlock_with_speed(300);
    smd.write_ok(C12_PC507, 10); // 1.0 s from 0 to 50 Hz: 50 Hz a second
    smd.write_ok(C13_PC507, 20); // 2.0 s from 50 Hz to 0: 25 Hz a second
    smd.write_ok(1, CMD_START);
    smd.run_for(400);
    assert_eq!(smd.read(ACTUAL_SPEED), 200);
    smd.run_for(200);
    assert_eq!((smd.read(ACTUAL_SPEED), smd.status()), (300, RUN));
    // A lower command: DECEL (line 676) along C13.
    smd.write_ok(SERIAL_SPEED, 100);
    assert_eq!(smd.status(), DECEL);
    smd.run_for(400);
    assert_eq!(smd.read(ACTUAL_SPEED), 200, "25 Hz a second down");
    smd.run_for(400);
    assert_eq!((smd.read(ACTUAL_SPEED), smd.status()), (100, RUN));
    // A command of 0 while started: RUN AT 0Hz (line 673) once the output is there.
    smd.write_ok(SERIAL_SPEED, 0);
    smd.run_for(400);
    assert_eq!((smd.read(ACTUAL_SPEED), smd.status()), (0, RUN_AT_0HZ));
}

#[test]
fn stop_coasts_the_output_to_zero_at_once() {
    let mut smd = Smd::new();
    smd.unlock_with_speed(300);
    smd.write_ok(1, CMD_START);
    smd.run_for(3000);
    assert_eq!(smd.read(ACTUAL_SPEED), 300);
    // "STOP DRIVE (COAST TO STOP)" (line 544), 0004H (line 1069): the output ends at once
    // (ERRATA.md E22).
    smd.write_ok(1, CMD_STOP);
    assert_eq!(smd.status(), STOP);
    smd.run_for(20);
    assert_eq!((smd.read(ACTUAL_SPEED), smd.read(COMMAND_SPEED)), (0, 0));
    // Started again, it ramps from 0.
    smd.write_ok(1, CMD_START);
    smd.run_for(500);
    assert_eq!((smd.read(ACTUAL_SPEED), smd.status()), (50, ACCEL));
}

#[test]
fn several_bits_in_register_1_stop_only_or_get_exception_04() {
    let mut smd = Smd::new();
    smd.unlock_with_speed(300);
    smd.write_ok(1, CMD_START);
    smd.run_for(1000);
    // Note 1 (lines 569-571): several bits without STOP → exception 04 (line 247), nothing done.
    assert_eq!(smd.write(1, CMD_START | 0x0001), [0x86, 0x04]);
    assert_eq!(smd.write(1, 0x0040 | 0x0080), [0x86, 0x04]);
    assert_eq!(smd.status(), ACCEL, "still running");
    // Several bits with STOP: "the drive responds to stop bit only".
    smd.write_ok(1, CMD_STOP | CMD_START);
    assert_eq!(smd.status(), STOP);
    smd.run_for(20);
    assert_eq!(smd.read(ACTUAL_SPEED), 0);
    // One bit that is no command (bit 4 is UNUSED, line 546) is data out of range, 03.
    assert_eq!(smd.write(1, 0x0010), [0x86, 0x03]);
}

#[test]
fn function_code_04_reads_what_03_reads() {
    // "function codes 03 and 04 are treated identically" (line 237).
    let mut smd = Smd::new();
    smd.unlock_with_speed(250);
    smd.write_ok(1, CMD_START);
    smd.run_for(1000);
    for register in [19, 21, 24, 25, 26, SERIAL_SPEED, 50, C12_PC507, N23_PC507] {
        assert_eq!(
            smd.read_with(0x04, register),
            smd.read_with(0x03, register),
            "#{register}"
        );
    }
    let block = |smd: &mut Smd, function: u8| smd.ask(&[function, 0x00, 0x18, 0x00, 0x06]);
    let (fc03, fc04) = (block(&mut smd, 0x03), block(&mut smd, 0x04));
    assert_eq!(fc04[0], 0x04);
    assert_eq!(fc04[1..], fc03[1..], "the 6-word status block");
    // The same limits: two words at #25 and a register that does not exist.
    assert_eq!(smd.ask(&[0x04, 0x00, 0x19, 0x00, 0x02]), [0x84, 0x03]);
    assert_eq!(smd.ask(&[0x04, 0x00, 0x02, 0x00, 0x01]), [0x84, 0x02]);
}

#[test]
fn function_code_16_writes_one_register_only() {
    // "we will accept only a single register to be written" (line 235); "Use either Modbus
    // function code 16 with a length of 1 or Modbus function code 06" (line 1052).
    let mut smd = Smd::new();
    smd.write_ok(48, 0);
    let one = [0x10, 0x00, 0x28, 0x00, 0x01, 0x02, 0x01, 0x9C];
    assert_eq!(smd.ask(&one), [0x10, 0x00, 0x28, 0x00, 0x01]);
    assert_eq!(smd.read(SERIAL_SPEED), 412);
    let two = [0x10, 0x00, 0x3D, 0x00, 0x02, 0x04, 0x00, 0x0A, 0x00, 0x0A];
    assert_eq!(smd.ask(&two), [0x90, 0x03]);
    assert_eq!(smd.read(C12_PC507), 50, "C12 untouched");
    // Start through FC 16.
    smd.ask(&[0x10, 0x00, 0x01, 0x00, 0x01, 0x02, 0x01, 0x00]);
    assert_eq!(
        smd.ask(&[0x10, 0x00, 0x01, 0x00, 0x01, 0x02, 0x00, 0x08]),
        [0x10, 0x00, 0x01, 0x00, 0x01]
    );
    assert_eq!(smd.status(), ACCEL);
}

/// Runs the drive at 30 Hz with the watchdog set to `n22` and n23 = 100 ms, then goes silent.
fn silent_after_running(n22: u16) -> Smd {
    let mut smd = Smd::new();
    smd.unlock_with_speed(300);
    smd.write_ok(N22_PC507, n22);
    smd.write_ok(N23_PC507, 100);
    smd.write_ok(1, CMD_START);
    smd.run_for(3000);
    assert_eq!((smd.read(ACTUAL_SPEED), smd.status()), (300, RUN));
    smd.silence(150);
    smd
}

#[test]
fn n22_1_coasts_to_inhibit() {
    // "it will COAST to a STOP and status display (c61) will show inhibit state 'Inh'" (line 383).
    let mut smd = silent_after_running(1);
    assert_eq!(smd.status(), INHIBIT);
    assert_eq!(smd.read(ACTUAL_SPEED), 0);
    // The timeout ended the unlock (line 414): a start is refused with 01 until unlocked.
    assert_eq!(smd.write(1, CMD_START), [0x86, 0x01]);
    smd.write_ok(48, 0);
    smd.write_ok(1, CMD_START);
    assert_eq!(smd.status(), ACCEL);
}

#[test]
fn n22_2_ramps_to_a_stop_with_c13() {
    // "it will RAMP to a STOP and status display (c61) will show inhibit state 'Stp'" (line 384).
    let mut smd = silent_after_running(2);
    assert_eq!(smd.status(), DECEL);
    // C13 = 5.0 s from 50 Hz: 10 Hz a second; 150 ms of silence took 1.5 Hz.
    assert_eq!(smd.read(ACTUAL_SPEED), 285);
    smd.run_for(1000);
    assert_eq!(smd.read(ACTUAL_SPEED), 185);
    smd.run_for(2000);
    assert_eq!((smd.read(ACTUAL_SPEED), smd.status()), (0, STOP));
}

#[test]
fn n22_3_trips_fc3() {
    // "it will TRIP with an 'FC3' fault" (line 385): code 24 (line 1007), FAULT (line 669).
    let mut smd = silent_after_running(3);
    assert_eq!(smd.status(), FAULT);
    assert_eq!(smd.read(ACTUAL_SPEED), 0);
    assert_eq!(smd.read(C61_PC507), 24);
}

#[test]
fn n22_0_keeps_running_in_silence() {
    // "n22 = 0: Not Active - The Watchdog Timer is disabled" (line 382).
    let mut smd = silent_after_running(0);
    assert_eq!((smd.read(ACTUAL_SPEED), smd.status()), (300, RUN));
}

#[test]
fn a_broadcast_is_not_executed() {
    // "the smd drive does not support the broadcast function" (line 214).
    let sim = Simulator::load(DESCRIPTION).unwrap();
    sim.preset("parameter_configuration", 507).unwrap();
    sim.preset("control_source", 11).unwrap();
    let units = Units::one(sim.clone(), UnitId(10));
    let mut out = [0u8; 256];
    let unlock = [0x06, 0x00, 0x30, 0x00, 0x00];
    let c09 = [0x06, 0x00, 0x3A, 0x00, 0x05];
    assert_eq!(units.handle(0, &unlock, &mut out), None);
    assert_eq!(units.handle(0, &c09, &mut out), None);
    let network_address =
        |sim: &Simulator| sim.with(|d| d.store().int(d.store().id("network_address").unwrap()));
    assert_eq!(network_address(&sim), Some(1), "C09 keeps its default");
    // The same writes to the drive's own address are executed.
    assert_eq!(units.handle(10, &unlock, &mut out), Some(5));
    assert_eq!(units.handle(10, &c09, &mut out), Some(5));
    assert_eq!(network_address(&sim), Some(5));
}

#[test]
fn c09_takes_the_addresses_1_to_247() {
    // "Set Parameter C09 (Network Address) to a valid address (1-247)" (lines 338, 887, 1022).
    let mut smd = Smd::new();
    smd.write_ok(48, 0);
    for bad in [0, 248] {
        assert_eq!(smd.write(58, bad), [0x86, 0x03], "C09 = {bad}");
    }
    for good in [1, 10, 247] {
        smd.write_ok(58, good);
        assert_eq!(smd.read(58), good);
    }
}

#[test]
fn c25_takes_8n1_in_both_configurations() {
    // c25 = 1, 9600 8N1 (line 944, 1041), marked "(PV507)" only at line 210 (ERRATA.md E13);
    // c25 is #95 in PC400 and #103 in PC507 (line 348).
    for (number, c25) in [(400, 95), (507, 103)] {
        let mut smd = Smd::configured(number);
        smd.write_ok(48, 0);
        smd.write_ok(c25, 1);
        assert_eq!(smd.read(c25), 1, "PC{number}");
        assert_eq!(
            smd.write(c25, 4),
            [0x86, 0x03],
            "PC{number}: 4 is no setting"
        );
    }
}
