//! Random valid descriptions as CANopen nodes: every object of the default variant takes a value
//! that fills its type (high bits set, negative for signed types, the edge of its range or its
//! last allowed value, a full-length string) by SDO download, holds it, and gives it back by SDO
//! upload — expedited, segmented and block transfers alike, for every width and odd width.

#[allow(dead_code)] // Shared with codegen's tests; each uses part of it.
#[path = "../../codegen/tests/support/random_description.rs"]
mod random_description;

use std::time::Duration;

use drivebus::canopen::can::in_process::InProcessBus;
use drivebus::canopen::client::BlockingSdo;
use drivebus::canopen::{NodeId, SdoBus};
use drivegen::ir::{DataType, Number, Parameter};
use drivesim::canopen::{Node, NodeConfig};
use drivesim::{raw, Simulator};

const NODE: NodeId = NodeId(5);

/// Bytes of a value that exercises `p`'s whole width and still passes its checks.
fn telling_bytes(p: &Parameter) -> Vec<u8> {
    let described = p
        .allowed
        .last()
        .copied()
        .or(p.range.as_ref().map(|r| r.max));
    if let Some(number) = described {
        return raw::from_number(p.data_type, number);
    }
    if let Some(int) = random_description::telling_integer(p) {
        return raw::from_int(p.data_type, int);
    }
    match p.data_type {
        DataType::String(n) | DataType::Octets(n) => (0..n).map(|i| b'a' + i as u8 % 26).collect(),
        ty => raw::from_number(ty, Number::Float(-1.5)),
    }
}

/// Whether `p` exists in the default variant `v0` and has a CANopen object. The included CiA 402
/// objects are left out: the simulator's CiA 402 behaviour computes the statusword and the mode
/// display from its state machine, and the controlword drives it.
fn tested(p: &Parameter) -> bool {
    let in_default_variant = p.variants.is_empty() || p.variants.iter().any(|v| v == "v0");
    let profile = random_description::CIA402.contains(&p.name.as_str());
    in_default_variant && p.command.is_none() && !p.canopen.is_empty() && !profile
}

fn check(path: &std::path::Path, block_transfers: bool) -> usize {
    let device = drivegen::check(path).device.unwrap();
    let sim = Simulator::load(path).unwrap();
    let bus = InProcessBus::new();
    let mut endpoint = bus.endpoint();
    let mut sdo = BlockingSdo::new(bus.endpoint()).with_timeout(Duration::from_secs(2));
    if block_transfers {
        sdo = sdo.with_block_transfers(5, 3);
    }
    let node_sim = sim.clone();
    let (stop, stopped) = std::sync::mpsc::channel::<()>();
    let node = std::thread::spawn(move || {
        let config = NodeConfig {
            node: NODE,
            heartbeat: None,
        };
        let mut node = Node::new(node_sim.clone(), config, node_sim.variant());
        node.run_while(&mut endpoint, || stopped.try_recv().is_err())
            .unwrap();
    });
    let mut checked = 0;
    for p in device.parameters.iter().filter(|p| tested(p)) {
        let object = &p.canopen[0];
        let bytes = telling_bytes(p);
        let at = format!("{}: {} ({:?})", path.display(), p.name, p.data_type);
        if object.access.write {
            sdo.download(NODE, object.index, object.subindex, &bytes)
                .unwrap_or_else(|e| panic!("{at}: download: {e:?}"));
        } else if let Some(value) = raw::to_int(p.data_type, &bytes) {
            sim.preset(&p.name, value).unwrap();
        } else {
            continue;
        }
        let held = sim.with(|drive| {
            drive
                .store()
                .bytes(drive.store().id(&p.name).unwrap())
                .to_vec()
        });
        assert_eq!(held, bytes, "{at}: held by the simulator");
        if object.access.read {
            let mut out = [0u8; 64];
            let len = sdo
                .upload(NODE, object.index, object.subindex, &mut out)
                .unwrap_or_else(|e| panic!("{at}: upload: {e:?}"));
            assert_eq!(&out[..len], &bytes[..], "{at}: uploaded");
            checked += 1;
        }
    }
    stop.send(()).unwrap();
    node.join().unwrap();
    checked
}

#[test]
fn every_object_round_trips_through_sdo() {
    let dir = std::env::temp_dir().join(format!("drivesim-random-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let paths = random_description::valid_descriptions(24, &dir);
    let checked: usize = paths
        .iter()
        .enumerate()
        .map(|(i, path)| check(path, i % 2 == 1))
        .sum();
    assert!(checked >= 20, "only {checked} objects were read back");
    let _ = std::fs::remove_dir_all(&dir);
}
