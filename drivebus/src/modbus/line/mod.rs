//! One Modbus line shared by many handles: an RS-485 line (or one TCP connection to a gateway in
//! front of one) carrying requests for several units, from several threads or async tasks.
//!
//! Each request holds the line for its whole exchange, so requests never interleave on the wire,
//! and the line is handed out first come, first served: a handle polling in a tight loop queues
//! behind the others and cannot starve them. Blocking handles and async tasks wait in the same
//! queue ([`turns`]), so one line may even carry both.
//!
//! A unit that does not answer holds the line for its timeout, then the next request goes out:
//! its silence delays the other units' requests but does not fail them (on RTU the client also
//! drops the silent unit's late answer, see [`Client`](super::client::Client)).
//!
//! A closed line answers every waiting and later request with [`BusError::Closed`]: closed by
//! [`ModbusLine::close`], or by the bus itself answering `Closed` (its connection ended).
//!
//! ```
//! use drivebus::modbus::{ModbusLine, RegisterBus, Table, UnitId};
//! use drivebus::BusError;
//!
//! /// Reads the status register of units 1 to 4 of one line, each from a thread of its own.
//! fn poll_units<B: RegisterBus + Send + 'static>(bus: B) -> Result<(), BusError> {
//!     let line = ModbusLine::new(bus);
//!     let handles: Vec<_> = (1..=4u8)
//!         .map(|unit| {
//!             let mut line = line.clone();
//!             std::thread::spawn(move || {
//!                 let mut status = [0u16; 1];
//!                 line.read_registers(UnitId(unit), Table::Input, 0x0060, &mut status)
//!             })
//!         })
//!         .collect();
//!     for handle in handles {
//!         handle.join().expect("a polling thread panicked")?;
//!     }
//!     Ok(())
//! }
//! ```

mod park;
mod turns;

use std::sync::{Arc, Mutex, PoisonError};

use super::{RegisterBus, RegisterRead, Table, UnitId};
use crate::error::BusError;
use turns::{Turn, Turns};

/// A [`RegisterBus`] (and, with feature `async`, an
/// [`AsyncRegisterBus`](super::AsyncRegisterBus)) shared by clones: every clone talks over the one
/// bus inside, request by request, in the order the requests arrived.
#[derive(Debug)]
pub struct ModbusLine<B> {
    shared: Arc<Shared<B>>,
}

/// The former name of [`ModbusLine`].
#[deprecated(note = "renamed ModbusLine: it is fair, and carries several units")]
pub type SharedBus<B> = ModbusLine<B>;

#[derive(Debug)]
struct Shared<B> {
    turns: Turns,
    /// The bus, out of its slot while a turn uses it: an async request awaits with it, and a
    /// `std` mutex guard must not be held across an await.
    bus: Mutex<Option<B>>,
}

impl<B> Clone for ModbusLine<B> {
    fn clone(&self) -> Self {
        Self {
            shared: Arc::clone(&self.shared),
        }
    }
}

impl<B: Default> Default for ModbusLine<B> {
    fn default() -> Self {
        Self::new(B::default())
    }
}

impl<B> ModbusLine<B> {
    /// Shares `bus`; clone the result for each handle.
    pub fn new(bus: B) -> Self {
        Self {
            shared: Arc::new(Shared {
                turns: Turns::default(),
                bus: Mutex::new(Some(bus)),
            }),
        }
    }

    /// The bus, once every request that arrived earlier is done; held until the guard drops.
    /// A handle that panicked while holding it left no half-sent request behind (each request
    /// completes or fails inside one call), so the line stays usable.
    pub fn lock(&self) -> Result<LineGuard<'_, B>, BusError> {
        park::park_until(self.lock_async())
    }

    /// [`lock`](Self::lock) for async tasks: waits without blocking the thread, on any executor.
    /// Dropping the future gives up its place in the queue.
    pub async fn lock_async(&self) -> Result<LineGuard<'_, B>, BusError> {
        let turn = self
            .shared
            .turns
            .take()
            .await
            .map_err(|_| BusError::Closed)?;
        let bus = self
            .shared
            .bus
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .take();
        Ok(LineGuard {
            bus,
            slot: &self.shared.bus,
            _turn: turn,
        })
    }

    /// Closes the line: every request waiting for it, and every later one, fails with
    /// [`BusError::Closed`]. The request on the wire finishes.
    pub fn close(&self) {
        self.shared.turns.close();
    }

    /// Whether the line was closed.
    pub fn is_closed(&self) -> bool {
        self.shared.turns.is_closed()
    }

    /// Closes the line when `outcome` says its connection ended, and passes it on.
    fn closing_on<T>(&self, outcome: Result<T, BusError>) -> Result<T, BusError> {
        if matches!(outcome, Err(BusError::Closed)) {
            self.close();
        }
        outcome
    }
}

/// The bus of a [`ModbusLine`], held: dereferences to it; dropping it hands the line to the
/// next request in the queue.
#[derive(Debug)]
pub struct LineGuard<'a, B> {
    /// Always `Some` until dropped (the slot is only empty while a guard exists).
    bus: Option<B>,
    slot: &'a Mutex<Option<B>>,
    // Dropped after `drop` put the bus back, so the next holder finds it.
    _turn: Turn<'a>,
}

impl<B> Drop for LineGuard<'_, B> {
    fn drop(&mut self) {
        *self.slot.lock().unwrap_or_else(PoisonError::into_inner) = self.bus.take();
    }
}

impl<B> core::ops::Deref for LineGuard<'_, B> {
    type Target = B;
    fn deref(&self) -> &B {
        self.bus
            .as_ref()
            .expect("a line guard holds its bus until dropped")
    }
}

impl<B> core::ops::DerefMut for LineGuard<'_, B> {
    fn deref_mut(&mut self) -> &mut B {
        self.bus
            .as_mut()
            .expect("a line guard holds its bus until dropped")
    }
}

impl<B: RegisterBus> RegisterBus for ModbusLine<B> {
    fn read_registers(
        &mut self,
        unit: UnitId,
        table: Table,
        start: u16,
        out: &mut [u16],
    ) -> Result<(), BusError> {
        let outcome = self.lock()?.read_registers(unit, table, start, out);
        self.closing_on(outcome)
    }

    fn write_register(&mut self, unit: UnitId, address: u16, value: u16) -> Result<(), BusError> {
        let outcome = self.lock()?.write_register(unit, address, value);
        self.closing_on(outcome)
    }

    fn write_registers(
        &mut self,
        unit: UnitId,
        start: u16,
        values: &[u16],
    ) -> Result<(), BusError> {
        let outcome = self.lock()?.write_registers(unit, start, values);
        self.closing_on(outcome)
    }

    /// The whole batch holds the line, so a pipelining client's requests stay together.
    fn read_register_batch(
        &mut self,
        unit: UnitId,
        reads: &mut [RegisterRead<'_>],
    ) -> Result<(), BusError> {
        let outcome = self.lock()?.read_register_batch(unit, reads);
        self.closing_on(outcome)
    }
}

#[cfg(feature = "async")]
impl<B: super::AsyncRegisterBus> super::AsyncRegisterBus for ModbusLine<B> {
    async fn read_registers(
        &mut self,
        unit: UnitId,
        table: Table,
        start: u16,
        out: &mut [u16],
    ) -> Result<(), BusError> {
        let mut bus = self.lock_async().await?;
        let outcome = bus.read_registers(unit, table, start, out).await;
        drop(bus);
        self.closing_on(outcome)
    }

    async fn write_register(
        &mut self,
        unit: UnitId,
        address: u16,
        value: u16,
    ) -> Result<(), BusError> {
        let mut bus = self.lock_async().await?;
        let outcome = bus.write_register(unit, address, value).await;
        drop(bus);
        self.closing_on(outcome)
    }

    async fn write_registers(
        &mut self,
        unit: UnitId,
        start: u16,
        values: &[u16],
    ) -> Result<(), BusError> {
        let mut bus = self.lock_async().await?;
        let outcome = bus.write_registers(unit, start, values).await;
        drop(bus);
        self.closing_on(outcome)
    }

    /// The whole batch holds the line, so a pipelining client's requests stay together.
    async fn read_register_batch(
        &mut self,
        unit: UnitId,
        reads: &mut [RegisterRead<'_>],
    ) -> Result<(), BusError> {
        let mut bus = self.lock_async().await?;
        let outcome = bus.read_register_batch(unit, reads).await;
        drop(bus);
        self.closing_on(outcome)
    }
}

#[cfg(test)]
mod tests;
