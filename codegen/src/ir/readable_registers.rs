//! What a Modbus request planner needs from a description: the device's limits, the registers it
//! lets a client read past when it refuses reads over unlisted addresses (`read_gaps = false`),
//! and those it lists as write-only, which no read may cover.

use super::{Device, ModbusAddress, Table};

/// Consecutive readable registers of one table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RegisterRun {
    /// The table.
    pub table: Table,
    /// First register.
    pub start: u16,
    /// How many registers, at least 1.
    pub count: u16,
}

/// A device's Modbus limits as a request planner takes them (`drivebus::modbus::ModbusLimits`),
/// derived once for the generated `MODBUS_LIMITS` and the CLI alike.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PlannerLimits {
    /// Most registers one read request may ask for.
    pub max_read_registers: u16,
    /// Most registers one write request may carry.
    pub max_write_registers: u16,
    /// Whether the device implements FC 0x10.
    pub write_multiple: bool,
    /// Whether a read may span addresses the description does not list.
    pub read_gaps: bool,
    /// What a read may cover besides the requested registers ([`Device::registers_to_read_past`]).
    pub readable: Vec<RegisterRun>,
    /// What no read may cover ([`Device::unreadable_register_runs`]).
    pub unreadable: Vec<RegisterRun>,
    /// The reads answered beyond the limit, as listed (`[modbus] read_blocks`).
    pub read_blocks: Vec<RegisterRun>,
    /// The values answered whole at one address ([`Device::whole_value_reads`]).
    pub whole_values: Vec<RegisterRun>,
}

impl Device {
    /// The planner's limits; `None` where the description has no `[modbus]` (the Modbus
    /// specification's limits then apply).
    pub fn planner_limits(&self) -> Option<PlannerLimits> {
        let m = self.modbus.as_ref()?;
        Some(PlannerLimits {
            max_read_registers: m.max_read_registers,
            max_write_registers: m.max_write_registers,
            write_multiple: m.writes_multiple_registers(),
            read_gaps: m.read_gaps,
            readable: self.registers_to_read_past(),
            unreadable: self.unreadable_register_runs(),
            read_blocks: m
                .read_blocks
                .iter()
                .map(|b| RegisterRun {
                    table: b.table,
                    start: b.address,
                    count: b.words,
                })
                .collect(),
            whole_values: self.whole_value_reads(),
        })
    }

    /// The readable values the device answers with more words than they occupy in the map
    /// (`occupies` < `words`; Lenze smd C99: 4 words at one register), each as the read of its
    /// words at its address, in any variant, sorted and without repeats.
    pub fn whole_value_reads(&self) -> Vec<RegisterRun> {
        let mut reads: Vec<RegisterRun> = self
            .parameters
            .iter()
            .flat_map(|p| &p.modbus)
            .filter(|a| a.access.read && a.occupies < a.words)
            .map(|a| RegisterRun {
                table: a.table,
                start: a.address,
                count: a.words,
            })
            .collect();
        reads.sort_unstable_by_key(|r| (r.table, r.start, r.count));
        reads.dedup();
        reads
    }

    /// What a request planner may read past besides the registers it was asked for: nothing
    /// where the device reads unlisted addresses too (`read_gaps`, the planner then need not
    /// know), else [`Device::readable_register_runs`].
    pub fn registers_to_read_past(&self) -> Vec<RegisterRun> {
        match &self.modbus {
            Some(modbus) if !modbus.read_gaps => self.readable_register_runs(),
            _ => Vec::new(),
        }
    }

    /// The registers readable in every variant, merged into runs sorted by table and address.
    /// Addresses limited to some variants are left out: a planner must not read past a register
    /// the drive at hand may not have.
    pub fn readable_register_runs(&self) -> Vec<RegisterRun> {
        let in_every_variant = self.parameters.iter().filter(|p| p.variants.is_empty());
        runs(
            in_every_variant
                .flat_map(|p| &p.modbus)
                .filter(|a| a.access.read && a.variant.is_none()),
        )
    }

    /// The registers listed without read access (write-only ones) in any variant, merged into
    /// runs sorted by table and address: a planner must not read past them even where the device
    /// reads unlisted addresses, since it would refuse the whole request.
    pub fn unreadable_register_runs(&self) -> Vec<RegisterRun> {
        runs(
            self.parameters
                .iter()
                .flat_map(|p| &p.modbus)
                .filter(|a| !a.access.read),
        )
    }
}

/// The registers of `addresses`, merged into runs sorted by table and address.
fn runs<'a>(addresses: impl Iterator<Item = &'a ModbusAddress>) -> Vec<RegisterRun> {
    let mut spans: Vec<(Table, u32, u32)> = addresses
        .filter(|a| a.occupies > 0)
        .map(|a| {
            let start = u32::from(a.address);
            (a.table, start, start + u32::from(a.occupies))
        })
        .collect();
    spans.sort_unstable();
    let mut runs: Vec<(Table, u32, u32)> = Vec::with_capacity(spans.len());
    for (table, start, end) in spans {
        match runs.last_mut() {
            Some(run) if run.0 == table && start <= run.2 => run.2 = run.2.max(end),
            _ => runs.push((table, start, end)),
        }
    }
    runs.into_iter()
        .filter_map(|(table, start, end)| {
            // Runs past register 0xFFFF are cut (such addresses fail validation anyway).
            let start = u16::try_from(start).ok()?;
            let count = (end.min(0x1_0000) - u32::from(start)).min(u16::MAX.into()) as u16;
            Some(RegisterRun {
                table,
                start,
                count,
            })
        })
        .collect()
}
