//! The Lenze smd's write lock and watchdog served from the description's data (`[lock]`,
//! `[[unlock]]`, `[watchdog]`; manual sections 4.4-4.6): writes while locked answer exception
//! 01, each unlock opens its scope only with its grant and requirement, and every end the
//! simulator can observe (lock command, C01 changed, power-down, serial timeout with n22's
//! action) locks again.

use std::thread::sleep;
use std::time::Duration;

use drivebus::modbus::client::{ModbusTcpClient, TcpConfig};
use drivebus::modbus::{ExceptionCode, RegisterBus, UnitId};
use drivebus::BusError;
use drivesim::Simulator;

const UNIT: UnitId = UnitId(1);
/// #1 drive control: start (0x0008), lock (0x0002); Table 8.
const CONTROL: u16 = 1;
const START: u16 = 0x0008;
const LOCK: u16 = 0x0002;
/// #40 serial speed command, in the `controls` scope.
const SERIAL_SPEED: u16 = 40;
/// #48 unlock controls, #49 unlock parameters.
const UNLOCK_CONTROLS: u16 = 48;
const UNLOCK_PARAMETERS: u16 = 49;
/// C01 (#51) and C12 acceleration time (#61), in the `parameters` scope.
const C01: u16 = 51;
const C12: u16 = 61;

struct Drive {
    sim: Simulator,
    client: ModbusTcpClient,
    _server: drivesim::modbus::tcp::TcpServer,
}

/// A simulated smd (PC400) with these presets.
fn smd(presets: &[(&str, i128)]) -> Drive {
    let sim = Simulator::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../descriptions/lenze-smd"
    ))
    .unwrap();
    for (name, value) in presets {
        sim.preset(name, *value).unwrap();
    }
    let server = sim.serve_modbus_tcp("127.0.0.1:0", UNIT).unwrap();
    let client = ModbusTcpClient::connect(server.local_addr(), &TcpConfig::default()).unwrap();
    Drive {
        sim,
        client,
        _server: server,
    }
}

impl Drive {
    fn write(&mut self, register: u16, value: u16) -> Result<(), BusError> {
        self.client.write_register(UNIT, register, value)
    }

    /// Whether a write of `value` to `register` is refused as locked (exception 01, line 416).
    fn locked(&mut self, register: u16, value: u16) -> bool {
        match self.write(register, value) {
            Ok(()) => false,
            Err(BusError::ModbusException { code, .. }) => {
                assert_eq!(code, ExceptionCode::IllegalFunction, "#{register}");
                true
            }
            Err(other) => panic!("#{register}: {other}"),
        }
    }
}

#[test]
fn writes_wait_for_the_unlock_of_their_scope() {
    let mut d = smd(&[("control_source", 11), ("user_password", 123)]);
    assert!(d.locked(CONTROL, START));
    assert!(d.locked(SERIAL_SPEED, 100));
    assert!(d.locked(C12, 100));
    // #48 = 0 unlocks the controls (line 409) but not the parameters (C94 is 123).
    d.write(UNLOCK_CONTROLS, 0).unwrap();
    assert!(!d.locked(CONTROL, START));
    assert!(!d.locked(SERIAL_SPEED, 100));
    assert!(d.locked(C12, 100));
    // #49 with a wrong password opens nothing, with C94 the parameters (line 421).
    d.write(UNLOCK_PARAMETERS, 7).unwrap();
    assert!(d.locked(C12, 100));
    d.write(UNLOCK_PARAMETERS, 123).unwrap();
    assert!(!d.locked(C12, 100));
    // Reads always work (line 417).
    let mut word = [0u16; 1];
    d.client
        .read_registers(UNIT, drivebus::modbus::Table::Holding, C12, &mut word)
        .unwrap();
    assert_eq!(word, [100]);
}

#[test]
fn the_controls_unlock_needs_c01_10_or_11() {
    let mut d = smd(&[("control_source", 8)]);
    d.write(UNLOCK_CONTROLS, 0).unwrap();
    assert!(
        d.locked(CONTROL, START),
        "C01 = 8: monitoring only (line 411)"
    );
}

#[test]
fn the_password_on_48_unlocks_controls_and_parameters() {
    let mut d = smd(&[("control_source", 10), ("user_password", 5)]);
    d.write(UNLOCK_CONTROLS, 5).unwrap();
    assert!(!d.locked(CONTROL, START));
    assert!(!d.locked(C12, 100));
}

#[test]
fn the_lock_command_ends_every_unlock() {
    let mut d = smd(&[("control_source", 11)]);
    d.write(UNLOCK_CONTROLS, 0).unwrap(); // C94 = 0: controls and parameters (line 412)
    d.write(UNLOCK_PARAMETERS, 0).unwrap();
    assert!(!d.locked(C12, 100));
    d.write(CONTROL, LOCK).unwrap();
    assert!(d.locked(CONTROL, START));
    assert!(d.locked(C12, 100));
}

#[test]
fn changing_c01_ends_the_controls_unlock() {
    let mut d = smd(&[("control_source", 11)]);
    d.write(UNLOCK_CONTROLS, 0).unwrap();
    d.write(C01, 10).unwrap(); // still serial control
    assert!(!d.locked(CONTROL, START));
    d.write(C01, 8).unwrap(); // line 414: "C01 is changed to a value different than 10 or 11"
    assert!(d.locked(CONTROL, START));
}

#[test]
fn changing_c01_ends_only_the_controls_part_of_the_password_unlock() {
    // #48 = C94 opens both scopes; line 414 ties the C01 rule to the controls (ERRATA.md E26).
    let mut d = smd(&[("control_source", 11), ("user_password", 5)]);
    d.write(UNLOCK_CONTROLS, 5).unwrap();
    d.write(C01, 8).unwrap();
    assert!(d.locked(CONTROL, START));
    assert!(!d.locked(C12, 100), "the parameters stay unlocked");
    d.write(C01, 11).unwrap();
    assert!(d.locked(CONTROL, START), "C01 back at 11 does not unlock");
    d.write(UNLOCK_CONTROLS, 5).unwrap();
    assert!(!d.locked(CONTROL, START), "a new grant does");
}

#[test]
fn a_power_down_ends_the_parameter_unlock_too() {
    // Line 425 names no power-down, but the drive powers up locked (lines 1055, 1059; E19).
    let mut d = smd(&[("control_source", 11)]);
    d.write(UNLOCK_PARAMETERS, 0).unwrap();
    assert!(!d.locked(C12, 100));
    d.sim.with(|drive| drive.reboot());
    assert!(d.locked(C12, 100));
}

#[test]
fn a_power_down_ends_the_controls_unlock() {
    let mut d = smd(&[("control_source", 11)]);
    d.write(UNLOCK_CONTROLS, 0).unwrap();
    d.sim.with(|drive| drive.reboot());
    assert!(d.locked(CONTROL, START));
}

#[test]
fn a_serial_timeout_locks_and_trips_fc3() {
    // n22 = 3: trip with FC3 (line 385), code 24 (line 1007); n23 = 300 ms.
    let mut d = smd(&[
        ("control_source", 11),
        ("serial_timeout_action", 3),
        ("serial_fault_time", 300),
    ]);
    d.write(UNLOCK_CONTROLS, 0).unwrap();
    for _ in 0..8 {
        sleep(Duration::from_millis(50)); // well within n23: the watchdog is fed
        assert!(!d.locked(CONTROL, START));
    }
    assert_eq!(d.sim.with(|drive| drive.fault()), None);
    sleep(Duration::from_millis(400));
    assert!(d.locked(CONTROL, START));
    assert_eq!(d.sim.with(|drive| drive.fault()), Some(24));
}

#[test]
fn the_watchdog_is_off_with_n22_0_and_while_locked() {
    let mut d = smd(&[
        ("control_source", 11),
        ("serial_timeout_action", 0),
        ("serial_fault_time", 50),
    ]);
    d.write(UNLOCK_CONTROLS, 0).unwrap();
    sleep(Duration::from_millis(120));
    assert!(!d.locked(CONTROL, START), "n22 = 0: not active (line 382)");
    let d = smd(&[("serial_timeout_action", 3), ("serial_fault_time", 50)]);
    sleep(Duration::from_millis(120));
    d.sim.with(|_| ());
    assert_eq!(
        d.sim.with(|drive| drive.fault()),
        None,
        "never unlocked: the timer does not run (line 376)"
    );
}

#[test]
fn a_timeout_with_parameters_only_unlocked_locks_but_does_not_stop() {
    // Line 376: "watchdog timer will disable write permission but will not stop the drive".
    let mut d = smd(&[("serial_timeout_action", 3), ("serial_fault_time", 50)]);
    d.write(UNLOCK_PARAMETERS, 0).unwrap();
    assert!(!d.locked(C12, 100));
    sleep(Duration::from_millis(120));
    assert!(d.locked(C12, 100));
    assert_eq!(d.sim.with(|drive| drive.fault()), None);
}
