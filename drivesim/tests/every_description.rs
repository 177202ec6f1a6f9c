//! Every shipped description becomes a working simulator: each readable Modbus register answers
//! with data (not an exception) and each readable CANopen object has its type's length.

use std::path::{Path, PathBuf};

use drivebus::canopen::sdo::server::ObjectDictionary;
use drivebus::modbus::pdu::{function, MAX_PDU};
use drivegen::ir::{DataType, Table};
use drivesim::canopen::Dictionary;
use drivesim::Simulator;

fn descriptions() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../descriptions");
    let mut found: Vec<PathBuf> = std::fs::read_dir(&root)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.join("device.toml").exists())
        .collect();
    found.sort();
    assert!(found.len() >= 4, "the shipped descriptions: {found:?}");
    found
}

#[test]
fn every_readable_register_answers() {
    for path in descriptions() {
        let sim = Simulator::load(&path).unwrap();
        let server = sim.modbus_server();
        let device = sim.with(|drive| drive.store().device().clone());
        for parameter in &device.parameters {
            let served = sim.variant();
            if !parameter.variants.is_empty()
                && !served.is_some_and(|v| parameter.variants.iter().any(|p| p == v))
            {
                continue; // absent in the variant served
            }
            for address in parameter.modbus.iter().filter(|a| a.access.read) {
                if address.variant.is_some() && address.variant.as_deref() != sim.variant() {
                    continue;
                }
                let code = match address.table {
                    Table::Holding => function::READ_HOLDING_REGISTERS,
                    Table::Input => function::READ_INPUT_REGISTERS,
                };
                let [hi, lo] = address.address.to_be_bytes();
                let request = [code, hi, lo, 0, 1];
                let mut out = [0u8; MAX_PDU];
                let len = sim.with(|drive| server.handle(drive, &request, &mut out));
                assert_eq!(
                    (out[0], len),
                    (code, 4),
                    "{}: {} at {:#06x}",
                    path.display(),
                    parameter.name,
                    address.address
                );
            }
        }
    }
}

#[test]
fn every_readable_object_has_its_length() {
    for path in descriptions() {
        let sim = Simulator::load(&path).unwrap();
        let device = sim.with(|drive| drive.store().device().clone());
        let mut dictionary = Dictionary::new(sim.clone(), &device, sim.variant());
        for parameter in &device.parameters {
            for address in parameter
                .canopen
                .iter()
                .filter(|a| a.access.read && a.variant.is_none())
            {
                let value = dictionary
                    .read(address.index, address.subindex)
                    .unwrap_or_else(|e| panic!("{}: {}: {e:?}", path.display(), parameter.name));
                if let DataType::Unsigned(_) | DataType::Signed(_) = parameter.data_type {
                    assert_eq!(
                        value.len(),
                        parameter.data_type.bytes() as usize,
                        "{}",
                        parameter.name
                    );
                }
            }
        }
    }
}
