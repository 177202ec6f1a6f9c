//! What a Modbus request planner needs from a description: the device's limits, the registers it
//! lets a client read past when it refuses reads over unlisted addresses (`read_gaps = false`),
//! and those it lists as write-only, which no read may cover.

use std::sync::OnceLock;

use drivebus_model::modbus::{ModbusLimits, RegisterSpan};

use super::{Device, ModbusAddress, ModbusCaps, Table};

/// The register lists of a device's [`ModbusLimits`], derived from its parameters once, the
/// first time the device lends its limits, and kept beside its `[modbus]` capabilities.
#[derive(Debug, Clone, Default)]
pub(crate) struct RegisterLists {
    readable: Vec<RegisterSpan>,
    unreadable: Vec<RegisterSpan>,
    read_blocks: Vec<RegisterSpan>,
    whole_values: Vec<RegisterSpan>,
}

/// Where a device's register lists are kept once derived.
pub(crate) type RegisterListsCell = OnceLock<RegisterLists>;

impl Device {
    /// The device's Modbus limits as the runtime's request planner takes them, borrowed from the
    /// device: the generated `MODBUS_LIMITS` is written from them, and the CLI plans its reads
    /// with them. The Modbus specification's limits where the description has no `[modbus]`.
    pub fn modbus_limits(&self) -> ModbusLimits<'_> {
        let Some(m) = self.modbus.as_ref() else {
            return ModbusLimits::SPEC;
        };
        let lists = m.register_lists.get_or_init(|| self.register_lists(m));
        ModbusLimits {
            max_read_registers: m.max_read_registers,
            max_write_registers: m.max_write_registers,
            write_multiple: m.writes_multiple_registers(),
            read_gaps: m.read_gaps,
            readable: &lists.readable,
            unreadable: &lists.unreadable,
            read_blocks: &lists.read_blocks,
            whole_values: &lists.whole_values,
        }
    }

    fn register_lists(&self, m: &ModbusCaps) -> RegisterLists {
        RegisterLists {
            readable: self.registers_to_read_past(),
            unreadable: self.unreadable_register_runs(),
            read_blocks: m
                .read_blocks
                .iter()
                .map(|b| RegisterSpan {
                    table: b.table,
                    start: b.address,
                    count: b.words,
                })
                .collect(),
            whole_values: self.whole_value_reads(),
        }
    }

    /// The readable values the device answers with more words than they occupy in the map
    /// (`occupies` < `words`; Lenze smd C99: 4 words at one register), each as the read of its
    /// words at its address, in any variant, sorted and without repeats.
    pub fn whole_value_reads(&self) -> Vec<RegisterSpan> {
        let mut reads: Vec<RegisterSpan> = self
            .parameters
            .iter()
            .flat_map(|p| &p.modbus)
            .filter(|a| a.access.read && a.occupies < a.words)
            .map(|a| RegisterSpan {
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
    pub fn registers_to_read_past(&self) -> Vec<RegisterSpan> {
        match &self.modbus {
            Some(modbus) if !modbus.read_gaps => self.readable_register_runs(),
            _ => Vec::new(),
        }
    }

    /// The registers readable in every variant, merged into runs sorted by table and address.
    /// Addresses limited to some variants are left out: a planner must not read past a register
    /// the drive at hand may not have.
    pub fn readable_register_runs(&self) -> Vec<RegisterSpan> {
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
    pub fn unreadable_register_runs(&self) -> Vec<RegisterSpan> {
        runs(
            self.parameters
                .iter()
                .flat_map(|p| &p.modbus)
                .filter(|a| !a.access.read),
        )
    }
}

/// The registers of `addresses`, merged into runs sorted by table and address.
fn runs<'a>(addresses: impl Iterator<Item = &'a ModbusAddress>) -> Vec<RegisterSpan> {
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
            Some(RegisterSpan {
                table,
                start,
                count,
            })
        })
        .collect()
}
