//! One Modbus line shared by several users: a drive handle and a keep-alive thread polling the
//! same drive on one RS-485 line, where a second connection does not exist. Each request holds
//! the line for its whole exchange, so two users' requests never interleave on the wire.

use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

use super::{RegisterBus, RegisterRead, Table, UnitId};
use crate::error::BusError;

/// A [`RegisterBus`] shared by clones: every clone talks over the one bus inside.
#[derive(Debug, Default)]
pub struct SharedBus<B> {
    bus: Arc<Mutex<B>>,
}

impl<B> Clone for SharedBus<B> {
    fn clone(&self) -> Self {
        Self {
            bus: Arc::clone(&self.bus),
        }
    }
}

impl<B> SharedBus<B> {
    /// Shares `bus`; clone the result for each user.
    pub fn new(bus: B) -> Self {
        Self {
            bus: Arc::new(Mutex::new(bus)),
        }
    }

    /// The bus, held until the guard drops. A user that panicked while holding it left no
    /// half-sent request behind (each request completes or fails inside one call), so the bus
    /// stays usable.
    pub fn lock(&self) -> MutexGuard<'_, B> {
        self.bus.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

impl<B: RegisterBus> RegisterBus for SharedBus<B> {
    fn read_registers(
        &mut self,
        unit: UnitId,
        table: Table,
        start: u16,
        out: &mut [u16],
    ) -> Result<(), BusError> {
        self.lock().read_registers(unit, table, start, out)
    }

    fn write_register(&mut self, unit: UnitId, address: u16, value: u16) -> Result<(), BusError> {
        self.lock().write_register(unit, address, value)
    }

    fn write_registers(
        &mut self,
        unit: UnitId,
        start: u16,
        values: &[u16],
    ) -> Result<(), BusError> {
        self.lock().write_registers(unit, start, values)
    }

    /// The whole batch holds the line, so a pipelining client's requests stay together.
    fn read_register_batch(
        &mut self,
        unit: UnitId,
        reads: &mut [RegisterRead<'_>],
    ) -> Result<(), BusError> {
        self.lock().read_register_batch(unit, reads)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{MemoryBus, Request};

    #[test]
    fn clones_talk_over_one_bus_request_by_request() {
        let mut memory = MemoryBus::new();
        memory
            .set_register(Table::Holding, 1, 0)
            .set_register(Table::Holding, 2, 0);
        let shared = SharedBus::new(memory);
        let threads: std::vec::Vec<_> = (0..4u16)
            .map(|n| {
                let mut bus = shared.clone();
                std::thread::spawn(move || {
                    for _ in 0..50 {
                        bus.write_registers(UnitId(1), 1, &[n, n]).unwrap();
                        let mut out = [0u16; 2];
                        bus.read_registers(UnitId(1), Table::Holding, 1, &mut out)
                            .unwrap();
                        assert_eq!(out[0], out[1], "a pair is never torn by another clone");
                    }
                })
            })
            .collect();
        for thread in threads {
            thread.join().unwrap();
        }
        let writes = shared
            .lock()
            .log()
            .iter()
            .filter(|r| matches!(r, Request::Write { .. }))
            .count();
        assert_eq!(writes, 200, "every clone's writes reached the one bus");
    }
}
