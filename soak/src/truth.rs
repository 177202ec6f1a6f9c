//! What the simulator holds: the values every read is checked against.

use drivesim::store::ParamId;
use drivesim::Simulator;

use crate::endpoint::REGISTERS;

/// The soak device's registers as the simulator holds them.
#[derive(Debug, Clone)]
pub struct Truth {
    sim: Simulator,
    ids: [ParamId; REGISTERS],
}

impl Truth {
    /// Finds `register_0` ..= `register_7` in `sim`.
    pub fn new(sim: &Simulator) -> Result<Self, String> {
        let ids = sim.with(|drive| {
            let mut ids = [0; REGISTERS];
            for (slot, id) in ids.iter_mut().enumerate() {
                let name = format!("register_{slot}");
                *id = drive.store().id(&name).ok_or(name)?;
            }
            Ok::<_, String>(ids)
        })?;
        Ok(Self {
            sim: sim.clone(),
            ids,
        })
    }

    /// The values held now.
    pub fn snapshot(&self) -> [u16; REGISTERS] {
        self.sim.with(|drive| {
            self.ids
                .map(|id| drive.store().int(id).unwrap_or_default() as u16)
        })
    }
}
