//! The CiA 402 driver against an independent device: python-canopen 2.4.1's LocalNode with a
//! controlword write callback running the CiA 402 state machine (tests/peers/cia402_relay.py).
#![cfg(feature = "canopen")]

mod support;

use std::process::{Child, ChildStdin};
use std::time::{Duration, Instant};

use drivebus::canopen::can::candump::CandumpBus;
use drivebus::canopen::client::BlockingSdo;
use drivebus::canopen::{CanOpenLink, NodeId, ObjectAddress};
use drivebus::control::driver::{self, ControlError, StuckReason};
use drivebus::control::{Blocker, State, Target};
use drivebus::{Device, VariantId};
use support::{expect_frame, is_boot_up, spawn_peer, stop, NODE, STARTUP};

#[path = "support/cia402_objects.rs"]
mod objects;

use objects::{Controlword, Mode, ModesDisplay, Objects, Standard};

type Link = CanOpenLink<BlockingSdo<CandumpBus<ChildStdin>>>;

/// The CiA 402 relay, killed by PID when dropped.
struct Peer {
    child: Child,
    device: Device<Link>,
}

impl Peer {
    /// Starts a peer whose fault reset needs bit 7 held high for `hold_ms`.
    fn start(hold_ms: u32) -> Self {
        let eds = support::peers_dir().join("cia402_peer.eds");
        let args = [
            eds.display().to_string(),
            NODE.to_string(),
            hold_ms.to_string(),
        ];
        let mut child = spawn_peer("cia402_relay.py", &args);
        let bus = CandumpBus::from_child(&mut child).expect("piped stdio");
        let mut sdo = BlockingSdo::new(bus).with_timeout(Duration::from_secs(2));
        if let Err(why) = expect_frame(&mut sdo, STARTUP, "boot-up from the peer", is_boot_up) {
            let stderr = stop(&mut child);
            panic!(
                "python CiA 402 relay did not start ({why}); run tests/peers/setup.sh\n{stderr}"
            );
        }
        let device = Device::new(CanOpenLink::new(sdo, NodeId(NODE)), VariantId::default());
        Self { child, device }
    }

    fn state(&mut self) -> Option<State> {
        driver::state::<Standard, _>(&mut self.device).expect("statusword")
    }

    fn write_controlword(&mut self, value: u16) {
        self.device
            .write_raw::<Controlword>(value)
            .expect("controlword write");
    }

    /// Writes a test trigger object of the peer (0x2001 fault, 0x2002 STO).
    fn poke(&mut self, index: u16, value: u8) {
        let address = ObjectAddress {
            index,
            subindex: 0,
            bytes: 1,
        };
        drivebus::Link::write(self.device.link_mut(), &address, &[value]).expect("trigger write");
    }
}

impl Drop for Peer {
    fn drop(&mut self) {
        stop(&mut self.child);
    }
}

fn soon() -> Instant {
    Instant::now() + Duration::from_secs(5)
}

#[test]
fn enables_disables_and_quick_stops_a_cia402_node() {
    let mut peer = Peer::start(0);
    assert_eq!(peer.state(), Some(State::SwitchOnDisabled));
    driver::drive_to::<Standard, _>(&mut peer.device, Target::OperationEnabled, soon()).unwrap();
    assert_eq!(peer.state(), Some(State::OperationEnabled));
    driver::quick_stop::<Standard, _>(&mut peer.device, soon()).unwrap();
    assert_eq!(peer.state(), Some(State::QuickStopActive));
    // Without transition 16 declared, operation is re-enabled through switch on disabled.
    driver::drive_to::<Standard, _>(&mut peer.device, Target::OperationEnabled, soon()).unwrap();
    assert_eq!(peer.state(), Some(State::OperationEnabled));
    driver::drive_to::<Standard, _>(&mut peer.device, Target::SwitchedOn, soon()).unwrap();
    assert_eq!(peer.state(), Some(State::SwitchedOn));
    driver::drive_to::<Standard, _>(&mut peer.device, Target::SwitchOnDisabled, soon()).unwrap();
    assert_eq!(peer.state(), Some(State::SwitchOnDisabled));
}

#[test]
fn resets_a_fault_on_a_rising_edge_even_with_bit_7_left_high() {
    let mut peer = Peer::start(0);
    // Bit 7 is already high when the fault comes: writing 0x80 again is no edge.
    peer.write_controlword(0x0080);
    peer.poke(0x2001, 1);
    peer.write_controlword(0x0080);
    assert_eq!(peer.state(), Some(State::Fault), "no reset without an edge");
    driver::fault_reset::<Standard, _>(&mut peer.device, soon()).unwrap();
    assert_eq!(peer.state(), Some(State::SwitchOnDisabled));
    driver::drive_to::<Standard, _>(&mut peer.device, Target::OperationEnabled, soon()).unwrap();
    assert_eq!(peer.state(), Some(State::OperationEnabled));
}

#[test]
fn a_drive_needing_a_long_fault_reset_pulse_resets_only_with_the_hold_quirk() {
    let mut peer = Peer::start(150);
    peer.poke(0x2001, 1);
    let deadline = Instant::now() + Duration::from_millis(600);
    let error = driver::fault_reset::<Standard, _>(&mut peer.device, deadline).unwrap_err();
    match error {
        ControlError::Stuck {
            state: Some("fault"),
            reason: StuckReason::NoResponse { transition, .. },
            ..
        } => {
            assert_eq!(transition.name, "15")
        }
        other => panic!("expected stuck in fault on transition 15, got {other}"),
    }
    driver::fault_reset::<Objects<250, false>, _>(&mut peer.device, soon()).unwrap();
    assert_eq!(peer.state(), Some(State::SwitchOnDisabled));
}

#[test]
fn safe_torque_off_is_reported_at_once_and_the_drive_stays_disabled() {
    let mut peer = Peer::start(0);
    peer.poke(0x2002, 1);
    let started = Instant::now();
    let error =
        driver::drive_to::<Objects<0, true>, _>(&mut peer.device, Target::OperationEnabled, soon())
            .unwrap_err();
    assert!(
        started.elapsed() < Duration::from_secs(2),
        "reported before the deadline"
    );
    assert_eq!(
        error,
        ControlError::Stuck {
            target: "operation enabled",
            state: Some("switch on disabled"),
            status: 0x0240,
            reason: StuckReason::Blocked(Blocker::SafeTorqueOff),
        }
    );
    assert_eq!(peer.state(), Some(State::SwitchOnDisabled));
}

#[test]
fn sets_a_manufacturer_mode_confirmed_by_the_display() {
    let mut peer = Peer::start(0);
    driver::set_mode::<Standard, _>(&mut peer.device, Mode(-3), soon()).unwrap();
    let shown = peer.device.read::<ModesDisplay>().unwrap();
    assert_eq!(shown, Mode(-3));
    driver::set_mode::<Standard, _>(&mut peer.device, Mode(3), soon()).unwrap();
    assert_eq!(peer.device.read::<ModesDisplay>().unwrap(), Mode(3));
}
