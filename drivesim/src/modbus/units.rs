//! Several simulated drives behind one Modbus port, a unit id each: drives sharing an RS-485
//! line, or a Modbus TCP gateway in front of them. A request to a unit id nobody holds gets no
//! answer, as on a real line.

use drivebus::modbus::UnitId;

use super::ModbusServer;
use crate::Simulator;

/// One drive at its unit id, with its request handler.
#[derive(Debug, Clone)]
struct Unit {
    id: UnitId,
    sim: Simulator,
    server: ModbusServer,
}

/// The drives one Modbus port serves, by unit id.
#[derive(Debug, Clone)]
pub struct Units {
    units: Vec<Unit>,
}

/// Unit id 0: a broadcast, executed by every unit whose description accepts broadcasts
/// (`[modbus] broadcast`) and answered by none.
const BROADCAST: u8 = 0;

impl Units {
    /// The drives at their unit ids; the first of several drives given the same id answers.
    pub fn new(drives: impl IntoIterator<Item = (UnitId, Simulator)>) -> Self {
        let units = drives
            .into_iter()
            .map(|(id, sim)| Unit {
                id,
                server: sim.modbus_server(),
                sim,
            })
            .collect();
        Self { units }
    }

    /// One drive at `unit`.
    pub fn one(sim: Simulator, unit: UnitId) -> Self {
        Self::new([(unit, sim)])
    }

    /// The unit id of the first drive (the one a Modbus TCP request to unit 0xFF reaches).
    pub fn first(&self) -> Option<UnitId> {
        self.units.first().map(|u| u.id)
    }

    /// Handles the request `pdu` sent to unit id `to`: the length of the response PDU written
    /// into `response` by the drive at `to`, or `None` when nobody answers (no drive has that
    /// id, or a broadcast, which every drive that accepts broadcasts executes).
    pub fn handle(&self, to: u8, pdu: &[u8], response: &mut [u8]) -> Option<usize> {
        if to == BROADCAST {
            for unit in self.units.iter().filter(|u| u.server.accepts_broadcast()) {
                unit.sim
                    .with(|drive| unit.server.handle(drive, pdu, response));
            }
            return None;
        }
        let unit = self.units.iter().find(|u| u.id.0 == to)?;
        Some(
            unit.sim
                .with(|drive| unit.server.handle(drive, pdu, response)),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lafert() -> Simulator {
        Simulator::load(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../descriptions/lafert-smartris"
        ))
        .unwrap()
    }

    /// FC 0x04, one input register at 0x0064 (the Lafert DC link voltage).
    const READ_DC_LINK: [u8; 5] = [0x04, 0x00, 0x64, 0x00, 0x01];

    #[test]
    fn each_unit_answers_for_its_own_drive_and_other_ids_stay_silent() {
        let (a, b) = (lafert(), lafert());
        a.preset("bus_dc_link", 0x1356).unwrap();
        b.preset("bus_dc_link", 0x0010).unwrap();
        let units = Units::new([(UnitId(3), a), (UnitId(9), b)]);
        let mut response = [0u8; 8];
        assert_eq!(units.handle(3, &READ_DC_LINK, &mut response), Some(4));
        assert_eq!(response[..4], [0x04, 0x02, 0x13, 0x56]);
        assert_eq!(units.handle(9, &READ_DC_LINK, &mut response), Some(4));
        assert_eq!(response[..4], [0x04, 0x02, 0x00, 0x10]);
        assert_eq!(units.handle(4, &READ_DC_LINK, &mut response), None);
        assert_eq!(units.handle(0, &READ_DC_LINK, &mut response), None);
        assert_eq!(units.first(), Some(UnitId(3)));
    }
}
