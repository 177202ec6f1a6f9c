//! The Modbus manual's worked examples that need a moving drive (001_ad8624675505a5b5.txt), run
//! on the built-in simulator, whose behaviour comes from the description alone: the speed
//! polarity (line 1348) and the communication loss timer (lines 809, 1276-1279, 458).

use std::time::Duration;

use drivesim::{Drive, Simulator};

const DRIVE_STATUS_RUN_VELOCITY: i128 = 0x0001;
const DRIVE_STATUS_STANDBY: i128 = 0x0002;
const DRIVE_STATUS_ALARM: i128 = 0x0010;
const RUN: i128 = 0x0003;

/// A Smartris in velocity mode with a 3000 rpm full scale, as a motor L (line 703).
fn smartris() -> Simulator {
    let sim = Simulator::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../descriptions/lafert-smartris"
    ))
    .unwrap();
    sim.preset("operation_mode", 2).unwrap();
    sim.preset("full_scale_velocity", 3000).unwrap();
    sim
}

fn value(drive: &Drive, name: &str) -> i128 {
    let store = drive.store();
    store.int(store.id(name).unwrap()).unwrap()
}

fn write(drive: &mut Drive, name: &str, raw: i128) {
    let id = drive.store().id(name).unwrap();
    let data_type = drive.store().parameter(id).data_type;
    drive
        .write(id, &drivesim::raw::from_int(data_type, raw))
        .unwrap_or_else(|refusal| panic!("{name} = {raw} refused: {refusal:?}"));
}

#[test]
fn setpoint_3000_with_polarity_1_runs_the_motor_at_minus_3000_rpm() {
    // Line 1348: "In case of speed setpoint = 3.000 rpm, sending 0x0043 = 1 the motor begins to
    // run at -3000 rpm".
    smartris().with(|drive| {
        write(drive, "control_word", RUN);
        write(drive, "speed_setpoint", 3000);
        drive.tick(Duration::from_secs(3));
        assert_eq!(value(drive, "velocity_average"), 3000, "polarity 0: × 1");
        write(drive, "speed_polarity", 1);
        // The default ramps (2000 ms each way, line 712-713) take it through 0 to -3000.
        drive.tick(Duration::from_secs(5));
        assert_eq!(value(drive, "velocity_average"), -3000, "polarity 1: × -1");
        assert_eq!(
            value(drive, "speed_setpoint"),
            3000,
            "the setpoint itself is kept"
        );
        write(drive, "speed_polarity", 0);
        drive.tick(Duration::from_secs(5));
        assert_eq!(value(drive, "velocity_average"), 3000);
    });
}

#[test]
fn silence_longer_than_the_communication_loss_time_is_alarm_0x7521() {
    // Line 809: no valid message within 0x0036 while the motor runs → alarm, the motor stops by
    // inertia; Table 2 line 458: 0x7521 Modbus Communication Lost.
    let sim = smartris();
    sim.preset("communication_loss_time", 1000).unwrap();
    sim.with(|drive| {
        write(drive, "control_word", RUN);
        write(drive, "speed_setpoint", 1000);
        drive.tick(Duration::from_millis(900));
        drive.heard();
        drive.tick(Duration::from_millis(900));
        assert_eq!(
            value(drive, "drive_status"),
            DRIVE_STATUS_RUN_VELOCITY,
            "a request within 1000 ms keeps it running"
        );
        drive.tick(Duration::from_millis(200));
        assert_eq!(value(drive, "drive_status"), DRIVE_STATUS_ALARM);
        assert_eq!(value(drive, "error_code"), 0x7521);
        assert_eq!(drive.fault(), Some(0x7521));
        drive.tick(Duration::from_millis(1));
        assert_eq!(value(drive, "velocity_average"), 0, "the motor stopped");
    });
}

#[test]
fn the_communication_loss_timer_watches_only_a_running_motor_and_0_disables_it() {
    // Line 809: "when the motor is running"; line 1278: "0x0036 = 0 → … disabled".
    let sim = smartris();
    sim.preset("communication_loss_time", 1000).unwrap();
    sim.with(|drive| {
        drive.tick(Duration::from_secs(10));
        assert_eq!(value(drive, "drive_status"), DRIVE_STATUS_STANDBY);
        assert_eq!(drive.fault(), None);
    });
    let disabled = smartris();
    disabled.with(|drive| {
        assert_eq!(
            value(drive, "communication_loss_time"),
            0,
            "default 0, line 707"
        );
        write(drive, "control_word", RUN);
        write(drive, "speed_setpoint", 1000);
        drive.tick(Duration::from_secs(10));
        assert_eq!(value(drive, "drive_status"), DRIVE_STATUS_RUN_VELOCITY);
        assert_eq!(value(drive, "velocity_average"), 1000);
    });
}

#[test]
fn speed_ramp_1000_ms_is_0_to_full_scale_in_1_s() {
    // Lines 1317 and 1324: 0x0040 / 0x0041 = 0x03E8 (1000) → from 0 to max velocity (and back) in 1 s.
    let sim = smartris();
    sim.preset("speed_ramp_up", 1000).unwrap();
    sim.preset("speed_ramp_down", 1000).unwrap();
    sim.with(|drive| {
        write(drive, "control_word", RUN);
        write(drive, "speed_setpoint", 3000);
        drive.tick(Duration::from_millis(500));
        assert_eq!(value(drive, "velocity_average"), 1500);
        drive.tick(Duration::from_millis(500));
        assert_eq!(value(drive, "velocity_average"), 3000);
        write(drive, "speed_setpoint", 0);
        drive.tick(Duration::from_millis(250));
        assert_eq!(value(drive, "velocity_average"), 2250);
        drive.tick(Duration::from_millis(750));
        assert_eq!(value(drive, "velocity_average"), 0);
    });
}

#[test]
fn the_node_sends_its_heartbeat_every_200_ms() {
    use drivebus::canopen::nmt::decode_heartbeat;
    use drivebus::canopen::NodeId;
    use drivesim::canopen::{Node, NodeConfig};

    // Guide 4702-4709: 700h + node id, one byte; line 4719: "a default time at 200 ms". The
    // node is stepped by hand (sans-I/O), so the period is exact, not a wall-clock measurement.
    let sim = smartris();
    let config = NodeConfig {
        node: NodeId(1),
        heartbeat: None, // the period comes from 1017h
    };
    let mut node = Node::new(sim.clone(), config, sim.variant());
    node.boot(Duration::ZERO);
    let mut sent = Vec::new();
    for ms in (0..=1000).step_by(10) {
        let now = Duration::from_millis(ms);
        if let Some(frame) = node.poll(now) {
            assert_eq!(frame.id(), 0x701);
            assert_eq!(frame.data().len(), 1);
            assert!(decode_heartbeat(&frame).is_some());
            sent.push(ms);
        }
    }
    assert_eq!(sent, [0, 200, 400, 600, 800, 1000]);
}
