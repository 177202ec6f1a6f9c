//! The CANopen node on an in-process bus against drivebus's SDO client: abort codes, NMT,
//! heartbeat, and the CiA 402 state machine driving the motor.

use std::time::Duration;

use drivebus::canopen::can::in_process::InProcessEndpoint;
use drivebus::canopen::client::BlockingSdo;
use drivebus::canopen::nmt::{decode_heartbeat, NmtCommand, NmtState};
use drivebus::canopen::{CanBus, NodeId, SdoBus};
use drivebus::BusError;
use drivesim::canopen::{InProcessNode, NodeConfig};
use drivesim::Simulator;

fn start(
    description: &str,
    node: u8,
    heartbeat: Option<Duration>,
) -> (BlockingSdo<InProcessEndpoint>, InProcessNode) {
    start_sim(Simulator::load(description).unwrap(), node, heartbeat)
}

/// Runs a node for `sim` in a thread; returns an SDO client on the same in-process bus.
fn start_sim(
    sim: Simulator,
    node: u8,
    heartbeat: Option<Duration>,
) -> (BlockingSdo<InProcessEndpoint>, InProcessNode) {
    let config = NodeConfig {
        node: NodeId(node),
        heartbeat,
    };
    let (client, running) = InProcessNode::start(sim, config);
    let sdo = BlockingSdo::new(client).with_timeout(Duration::from_millis(300));
    (sdo, running)
}

const FIXTURE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/fixtures/enforcement.toml"
);
const LAFERT: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../descriptions/lafert-smartris"
);

fn abort(result: Result<(), BusError>) -> u32 {
    match result {
        Err(BusError::SdoAbort { code, .. }) => code.code(),
        other => panic!("expected an abort, got {other:?}"),
    }
}

fn upload(
    sdo: &mut BlockingSdo<InProcessEndpoint>,
    node: u8,
    index: u16,
    sub: u8,
) -> Result<Vec<u8>, BusError> {
    let mut buf = [0u8; 8];
    let len = sdo.upload(NodeId(node), index, sub, &mut buf)?;
    Ok(buf[..len].to_vec())
}

#[test]
fn sdo_access_is_enforced_with_cia301_abort_codes() {
    let (mut sdo, _node) = start(FIXTURE, 5, None);
    assert_eq!(
        upload(&mut sdo, 5, 0x2000, 0).unwrap(),
        100i16.to_le_bytes()
    );
    assert_eq!(
        abort(sdo.download(NodeId(5), 0x2001, 0, &[1, 0])),
        0x0601_0002,
        "read-only"
    );
    assert_eq!(
        abort(upload(&mut sdo, 5, 0x2002, 0).map(drop)),
        0x0601_0001,
        "write-only"
    );
    assert_eq!(
        abort(upload(&mut sdo, 5, 0x2FFF, 0).map(drop)),
        0x0602_0000,
        "no object"
    );
    assert_eq!(
        abort(upload(&mut sdo, 5, 0x2003, 7).map(drop)),
        0x0609_0011,
        "no subindex"
    );
    assert_eq!(
        abort(sdo.download(NodeId(5), 0x2000, 0, &3001i16.to_le_bytes())),
        0x0609_0031
    );
    assert_eq!(
        abort(sdo.download(NodeId(5), 0x2000, 0, &(-3001i16).to_le_bytes())),
        0x0609_0032
    );
    assert_eq!(
        abort(sdo.download(NodeId(5), 0x2003, 1, &2u16.to_le_bytes())),
        0x0609_0030
    );
    assert_eq!(
        abort(sdo.download(NodeId(5), 0x2000, 0, &[1, 2, 3, 4])),
        0x0607_0010
    );
    sdo.download(NodeId(5), 0x2000, 0, &(-5i16).to_le_bytes())
        .unwrap();
    assert_eq!(
        upload(&mut sdo, 5, 0x2000, 0).unwrap(),
        (-5i16).to_le_bytes()
    );
}

#[test]
fn a_stopped_node_does_not_answer_sdo() {
    let (mut sdo, _node) = start(FIXTURE, 5, None);
    sdo.bus_mut()
        .send(&NmtCommand::Stop.frame(Some(NodeId(5))))
        .unwrap();
    std::thread::sleep(Duration::from_millis(50));
    assert_eq!(upload(&mut sdo, 5, 0x2000, 0), Err(BusError::Timeout));
    sdo.bus_mut().send(&NmtCommand::Start.frame(None)).unwrap();
    std::thread::sleep(Duration::from_millis(50));
    assert!(upload(&mut sdo, 5, 0x2000, 0).is_ok());
}

#[test]
fn heartbeats_report_the_nmt_state() {
    let (mut sdo, _node) = start(FIXTURE, 5, Some(Duration::from_millis(20)));
    sdo.bus_mut()
        .send(&NmtCommand::Start.frame(Some(NodeId(5))))
        .unwrap();
    let bus = sdo.bus_mut();
    let mut states = Vec::new();
    while states.len() < 6 {
        let frame = bus
            .recv(Duration::from_secs(1))
            .unwrap()
            .expect("heartbeats keep coming");
        if let Some((node, state)) = decode_heartbeat(&frame) {
            assert_eq!(node, NodeId(5));
            states.push(state);
        }
    }
    assert_eq!(states[0], NmtState::Initializing, "boot-up first");
    assert_eq!(*states.last().unwrap(), NmtState::Operational);
}

#[test]
fn cia402_reaches_operation_enabled_and_the_motor_follows() {
    let (mut sdo, _node) = start(LAFERT, 1, None);
    let statusword = |sdo: &mut BlockingSdo<InProcessEndpoint>| {
        u16::from_le_bytes(upload(sdo, 1, 0x6041, 0).unwrap().try_into().unwrap())
    };
    assert_eq!(statusword(&mut sdo) & 0x4F, 0x40, "switch on disabled");
    for (controlword, mask, state) in [
        (0x06u16, 0x6F, 0x21),
        (0x07, 0x6F, 0x23),
        (0x0F, 0x6F, 0x27),
    ] {
        sdo.download(NodeId(1), 0x6040, 0, &controlword.to_le_bytes())
            .unwrap();
        assert_eq!(
            statusword(&mut sdo) & mask,
            state,
            "after controlword {controlword:#x}"
        );
    }
    sdo.download(NodeId(1), 0x60FF, 0, &1000i32.to_le_bytes())
        .unwrap();
    std::thread::sleep(Duration::from_millis(50));
    let actual = i32::from_le_bytes(upload(&mut sdo, 1, 0x606C, 0).unwrap().try_into().unwrap());
    assert_eq!(
        actual, 1000,
        "no profile acceleration described: the speed jumps"
    );
    sdo.download(NodeId(1), 0x6040, 0, &0x02u16.to_le_bytes())
        .unwrap();
    assert_eq!(statusword(&mut sdo) & 0x6F, 0x07, "quick stop active");
    let stopped = i32::from_le_bytes(upload(&mut sdo, 1, 0x606C, 0).unwrap().try_into().unwrap());
    assert_eq!(stopped, 0);
}

#[test]
fn a_fault_sends_emcy_and_the_fault_reset_clears_it() {
    let sim = Simulator::load(LAFERT).unwrap();
    let (mut sdo, _node) = start_sim(sim.clone(), 1, None);
    sim.with(|drive| drive.inject_fault(0x3210));
    let emcy = |sdo: &mut BlockingSdo<InProcessEndpoint>| loop {
        let frame = sdo
            .bus_mut()
            .recv(Duration::from_secs(1))
            .unwrap()
            .expect("an EMCY");
        if let Some(emcy) = drivebus::canopen::emcy::Emcy::decode(&frame) {
            return emcy;
        }
    };
    let raised = emcy(&mut sdo);
    assert_eq!((raised.node, raised.code), (NodeId(1), 0x3210));
    let statusword =
        u16::from_le_bytes(upload(&mut sdo, 1, 0x6041, 0).unwrap().try_into().unwrap());
    assert_eq!(statusword & 0x4F, 0x08, "fault");
    sdo.download(NodeId(1), 0x6040, 0, &0x80u16.to_le_bytes())
        .unwrap();
    assert!(
        emcy(&mut sdo).is_reset(),
        "error reset after the fault reset"
    );
}

#[test]
fn saved_parameters_survive_an_nmt_reset() {
    const SAVE: u32 = 0x6576_6173; // "save", CiA 301 1010h
    let (mut sdo, _node) = start(LAFERT, 1, None);
    let mode = |sdo: &mut BlockingSdo<InProcessEndpoint>| upload(sdo, 1, 0x6060, 0).unwrap()[0];
    let reset = |sdo: &mut BlockingSdo<InProcessEndpoint>| {
        sdo.bus_mut()
            .send(&NmtCommand::ResetNode.frame(Some(NodeId(1))))
            .unwrap();
        std::thread::sleep(Duration::from_millis(50));
    };
    sdo.download(NodeId(1), 0x6060, 0, &[3]).unwrap();
    reset(&mut sdo);
    assert_eq!(mode(&mut sdo), 0, "not saved: lost");
    sdo.download(NodeId(1), 0x6060, 0, &[3]).unwrap();
    assert_eq!(
        abort(sdo.download(NodeId(1), 0x1010, 1, &1u32.to_le_bytes())),
        0x0609_0030,
        "not \"save\""
    );
    sdo.download(NodeId(1), 0x1010, 1, &SAVE.to_le_bytes())
        .unwrap();
    let capability = upload(&mut sdo, 1, 0x1010, 1).unwrap();
    assert_ne!(
        capability,
        SAVE.to_le_bytes(),
        "the trigger is not kept as a value"
    );
    reset(&mut sdo);
    assert_eq!(mode(&mut sdo), 3, "saved: kept");
}

/// A node-relative default (`$NODEID+0x180`, a vendor EDS whose limits 0x181..=0x18F allow node
/// IDs 1..=15 only) holds its value on the node's own id: 0x185 on node 5, 0x190 on node 16
/// (what the drive computes, though its limits refuse it), never the bare offset 0x180.
#[test]
fn node_relative_defaults_hold_the_node_id() {
    let eds = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../codegen/tests/eds/node_id_default_narrowed.eds"
    );
    let sim = Simulator::load(eds).unwrap();
    let before = sim.with(|d| {
        let id = d.store().id("cob_id_used_by_tpdo1").unwrap();
        d.store().int(id)
    });
    assert_eq!(before, Some(0x181), "the description's default node id 1");
    for (node, cob_id) in [(5u8, 0x185u32), (16, 0x190)] {
        let (mut sdo, _node) = start(eds, node, None);
        let read = upload(&mut sdo, node, 0x1800, 1).unwrap();
        assert_eq!(read, cob_id.to_le_bytes(), "node {node}");
        let gateway = upload(&mut sdo, node, 0x2010, 0).unwrap();
        assert_eq!(
            gateway,
            (0x100 + u16::from(node)).to_le_bytes(),
            "node {node}"
        );
    }
}

const SWD: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../descriptions/ezwheel-swd");

/// Writes `controlword` to 6040h, then reads 6041h.
fn command(sdo: &mut BlockingSdo<InProcessEndpoint>, controlword: u16) -> u16 {
    sdo.download(NodeId(1), 0x6040, 0, &controlword.to_le_bytes())
        .unwrap();
    u16::from_le_bytes(upload(sdo, 1, 0x6041, 0).unwrap().try_into().unwrap())
}

#[test]
fn cia402_statuswords_are_the_device_sides_in_every_state_a_master_sees() {
    // drivebus::control::device decides them: CiA 402's state coding, bit 4 while the power is
    // on, bit 9 clear (the SWD declares no `honours-remote`). The SWD's quick stop option code
    // is 6 (605Ah default, manual line 2727): quick stop active stays, enable operation resumes
    // (transition 16, line 2275; the quick start, line 4163).
    let sim = Simulator::load(SWD).unwrap();
    let (mut sdo, _node) = start_sim(sim.clone(), 1, None);
    let statusword =
        u16::from_le_bytes(upload(&mut sdo, 1, 0x6041, 0).unwrap().try_into().unwrap());
    assert_eq!(statusword, 0x0040, "switch on disabled");
    for (controlword, expected, state) in [
        (0x06, 0x0021, "ready to switch on"),
        (0x07, 0x0033, "switched on"),
        (0x0F, 0x0037, "operation enabled"),
        (0x02, 0x0017, "quick stop active"),
        (0x0F, 0x0037, "operation enabled (transition 16)"),
        (0x00, 0x0040, "switch on disabled"),
    ] {
        let statusword = command(&mut sdo, controlword);
        assert_eq!(statusword, expected, "{state} after {controlword:#06x}");
    }
    sim.with(|drive| drive.inject_fault(0x3210));
    let statusword =
        u16::from_le_bytes(upload(&mut sdo, 1, 0x6041, 0).unwrap().try_into().unwrap());
    assert_eq!(statusword, 0x0008, "fault");
    assert_eq!(command(&mut sdo, 0x80), 0x0040, "fault reset");
}

#[test]
fn without_an_option_code_or_the_quirk_quick_stop_active_is_left_only_by_disable_voltage() {
    // Lafert: no 605Ah, no `quick-stop-to-operation-enabled` quirk; the planner goes through
    // switch on disabled, and so must a master of the simulated drive.
    let (mut sdo, _node) = start(LAFERT, 1, None);
    for controlword in [0x06, 0x07, 0x0F] {
        command(&mut sdo, controlword);
    }
    assert_eq!(command(&mut sdo, 0x02), 0x0017, "quick stop active");
    assert_eq!(command(&mut sdo, 0x0F), 0x0017, "no transition 16");
    assert_eq!(
        command(&mut sdo, 0x06),
        0x0017,
        "no shutdown from quick stop active"
    );
    assert_eq!(command(&mut sdo, 0x00), 0x0040, "transition 12");
}
