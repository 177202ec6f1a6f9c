//! An independent CiA 402 master, python-canopen 2.4.1's `BaseNode402`, drives our device side:
//! [`Cia402Device`] behind our SDO server, over candump stdio (tests/peers/cia402_master.py).
#![cfg(feature = "canopen")]

mod support;

use std::collections::BTreeMap;
use std::time::{Duration, Instant};
use std::vec::Vec;

use drivebus::canopen::can::candump::CandumpBus;
use drivebus::canopen::sdo::server::{ObjectDictionary, SdoServer};
use drivebus::canopen::sdo::AbortCode;
use drivebus::canopen::{CanBus, NodeId};
use drivebus::control::device::Cia402Device;
use drivebus::control::State;
use support::{spawn_peer, stop, NODE};

/// The CiA 402 objects of a node whose controlword drives a [`Cia402Device`].
struct Cia402Objects {
    device: Cia402Device,
    others: BTreeMap<(u16, u8), Vec<u8>>,
}

impl ObjectDictionary for Cia402Objects {
    fn read(&mut self, index: u16, subindex: u8) -> Result<Vec<u8>, AbortCode> {
        match (index, subindex) {
            (0x6041, 0) => Ok(self.device.statusword().to_le_bytes().to_vec()),
            (0x6040, 0) => Ok(self.device.controlword().to_le_bytes().to_vec()),
            key => self.others.read(key.0, key.1),
        }
    }

    fn write(&mut self, index: u16, subindex: u8, data: &[u8]) -> Result<(), AbortCode> {
        match (index, subindex, data) {
            (0x6040, 0, &[low, high]) => {
                self.device
                    .write_controlword(u16::from_le_bytes([low, high]));
                Ok(())
            }
            (0x6060, 0, &[mode]) => {
                self.others.insert((0x6061, 0), vec![mode]);
                self.others.write(0x6060, 0, data)
            }
            (0x6040 | 0x6060, 0, _) => Err(AbortCode::LengthMismatch),
            _ => self.others.write(index, subindex, data),
        }
    }
}

#[test]
fn base_node_402_enables_and_switches_mode_on_our_device() {
    let eds = support::peers_dir().join("cia402_peer.eds");
    let mut child = spawn_peer(
        "cia402_master.py",
        &[eds.display().to_string(), NODE.to_string()],
    );
    let mut bus = CandumpBus::from_child(&mut child).expect("piped stdio");
    let others = BTreeMap::from([
        ((0x6060, 0), vec![0]),
        ((0x6061, 0), vec![0]),
        ((0x6502, 0), 0x0000_0005u32.to_le_bytes().to_vec()),
    ]);
    let objects = Cia402Objects {
        device: Cia402Device::default(),
        others,
    };
    let mut server = SdoServer::new(NodeId(NODE), objects);
    let deadline = Instant::now() + Duration::from_secs(60);
    let status = loop {
        if let Some(status) = child.try_wait().expect("peer status") {
            break Some(status);
        }
        if Instant::now() > deadline {
            break None;
        }
        match bus.recv(Duration::from_millis(5)) {
            Ok(Some(frame)) => {
                for answer in server.handle(&frame) {
                    bus.send(&answer).expect("send to the master");
                }
            }
            Ok(None) => {}
            Err(_) => std::thread::sleep(Duration::from_millis(5)),
        }
    };
    let stderr = stop(&mut child);
    assert!(
        status.is_some_and(|s| s.success()),
        "BaseNode402 scenario failed ({status:?}); run tests/peers/setup.sh if python-canopen is missing\n{stderr}"
    );
    assert!(stderr.contains("reached OPERATION ENABLED"), "{stderr}");
    assert!(stderr.contains("mode PROFILED VELOCITY"), "{stderr}");
    let objects = server.dictionary();
    assert_eq!(objects.device.state(), State::SwitchOnDisabled);
    assert_eq!(objects.others.get(&(0x6060, 0)), Some(&vec![3]));
}
