//! The request planner: the fewest read requests that fetch a set of values within a device's
//! [`ModbusLimits`].
//!
//! Reads are planned one at a time ([`next_read`]), so a caller without an allocator can interleave
//! planning and reading; [`plan`] collects a whole plan. The greedy choice — start at the lowest
//! value not yet read and take every pending value that fits — is optimal: any plan must cover
//! that value with a read starting at or below it, and moving that read up to start exactly at the
//! value covers everything it covered before (nothing pending lies lower).
//!
//! Rules: input and holding registers are never mixed; a multi-word value is always read whole by
//! one request, so its words arrive in their word order; a read never exceeds
//! `max_read_registers`; without `read_gaps` a read only covers registers some value occupies
//! (adjacent and overlapping values still coalesce); and a read never covers a register listed as
//! unreadable that no requested value occupies. The greedy choice stays optimal under these rules:
//! they only forbid registers, and a read moved up to start at the lowest value covers a subset of
//! what it covered before.

use crate::error::BusError;

use super::address::{ModbusAddress, ModbusLimits, RegisterSpan, Table, MAX_VALUE_WORDS};
use super::pdu::{Request, MAX_READ_REGISTERS};

/// One read request of a plan.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct PlannedRead {
    /// Register table.
    pub table: Table,
    /// First register.
    pub start: u16,
    /// Number of registers.
    pub count: u16,
    /// Whether this is the read of one value the device answers whole beyond its read limit
    /// ([`ModbusLimits::whole_values`]): it then covers only that value, since the registers
    /// after its address hold other parameters.
    pub whole_value: bool,
}

impl PlannedRead {
    /// The register offset of `item` inside this read, if the read covers all of it.
    pub fn offset_of(&self, item: &ModbusAddress) -> Option<usize> {
        if self.whole_value {
            let same =
                (item.table, item.address, item.words) == (self.table, self.start, self.count);
            return same.then_some(0);
        }
        let offset = (item.address as usize).checked_sub(self.start as usize)?;
        (item.table == self.table && offset + item.words as usize <= self.count as usize)
            .then_some(offset)
    }

    /// The Modbus request for this read.
    pub fn request(&self) -> Request<'static> {
        Request::read_registers(self.table, self.start, self.count)
    }
}

/// Registers one request may read on this device.
fn read_limit(limits: &ModbusLimits) -> usize {
    limits.max_read_registers.min(MAX_READ_REGISTERS) as usize
}

/// Checks that `item` can be read at all under `limits`.
pub fn check_item(limits: &ModbusLimits, item: &ModbusAddress) -> Result<(), BusError> {
    let words = item.words as usize;
    if words == 0 || words > MAX_VALUE_WORDS {
        return Err(BusError::Unsupported("value wider than 32 registers"));
    }
    if words > read_limit(limits) && !is_whole_value(limits, item) {
        return Err(BusError::Unsupported(
            "value wider than the device's read limit",
        ));
    }
    if item.address as usize + words > 0x1_0000 {
        return Err(BusError::Unsupported("value runs past register 0xFFFF"));
    }
    Ok(())
}

/// Whether the device answers `item` whole although it is wider than the read limit
/// ([`ModbusLimits::whole_values`]).
fn is_whole_value(limits: &ModbusLimits, item: &ModbusAddress) -> bool {
    limits.whole_values.iter().any(|span| span.is_exactly(item))
}

fn end(item: &ModbusAddress) -> usize {
    item.address as usize + item.words as usize
}

/// Plans the next read for `len` items, where `item(i)` is item `i`'s address and whether it has
/// been read already. `None` once every item is read.
///
/// The items already read still count as requested registers for bridging gaps. A value wider
/// than the read limit that the device answers whole ([`ModbusLimits::whole_values`]) is read
/// alone; where the lowest pending value lies in one of the device's
/// [`read_blocks`](ModbusLimits::read_blocks) and the block covers more pending values than the
/// ordinary read would, the whole block is read instead (the Lenze smd status block #24-#29 in
/// one request, not six).
pub fn next_read(
    limits: &ModbusLimits,
    len: usize,
    item: impl Fn(usize) -> (ModbusAddress, bool),
) -> Result<Option<PlannedRead>, BusError> {
    let mut first: Option<ModbusAddress> = None;
    for i in 0..len {
        let (address, done) = item(i);
        check_item(limits, &address)?;
        let lower = first.is_none_or(|f| (address.table, address.address) < (f.table, f.address));
        if !done && lower {
            first = Some(address);
        }
    }
    let Some(first) = first else {
        return Ok(None);
    };
    if first.words as usize > read_limit(limits) {
        return Ok(Some(PlannedRead {
            table: first.table,
            start: first.address,
            count: first.words,
            whole_value: true,
        }));
    }
    let read = ordinary_read(limits, first, len, &item);
    Ok(Some(block_instead(limits, read, len, &item)))
}

/// The longest read from `first` (the lowest pending value) within the limit, the readable
/// registers and the unreadable barriers.
fn ordinary_read(
    limits: &ModbusLimits,
    first: ModbusAddress,
    len: usize,
    item: impl Fn(usize) -> (ModbusAddress, bool),
) -> PlannedRead {
    let start = first.address as usize;
    let mut limit = start + read_limit(limits);
    if !limits.read_gaps {
        // Extend the run of requested and listed readable registers from `start` until it
        // stops growing.
        let mut reach = start;
        loop {
            let readable = limits
                .readable
                .iter()
                .filter(|span| span.table == first.table && span.start as usize <= reach)
                .map(RegisterSpan::end);
            let grown = (0..len)
                .map(|i| item(i).0)
                .filter(|a| a.table == first.table && a.address as usize <= reach)
                .map(|a| end(&a))
                .chain(readable)
                .fold(reach, usize::max);
            if grown == reach || grown >= limit {
                reach = grown;
                break;
            }
            reach = grown;
        }
        limit = limit.min(reach);
    }
    if let Some(barrier) = first_unreadable(limits, first.table, start..limit, len, &item) {
        limit = limit.min(barrier);
    }
    let last = (0..len)
        .map(&item)
        .filter(|(a, done)| {
            !done && a.table == first.table && a.address as usize >= start && end(a) <= limit
        })
        .map(|(a, _)| end(&a))
        .fold(end(&first), usize::max);
    PlannedRead {
        table: first.table,
        start: first.address,
        count: (last - start) as u16,
        whole_value: false,
    }
}

/// The first register of `table` in `within` that the device lists as unreadable and no item
/// occupies: a read over `within` must stop before it. (Past the first item, since the
/// registers of an item are never such a barrier.)
fn first_unreadable(
    limits: &ModbusLimits,
    table: Table,
    within: core::ops::Range<usize>,
    len: usize,
    item: impl Fn(usize) -> (ModbusAddress, bool),
) -> Option<usize> {
    let occupied = |register: usize| {
        (0..len).any(|i| {
            let a = item(i).0;
            a.table == table && (a.address as usize..end(&a)).contains(&register)
        })
    };
    limits
        .unreadable
        .iter()
        .filter(|span| span.table == table && span.end() > within.start)
        .filter(|span| (span.start as usize) < within.end)
        .filter_map(|span| {
            let mut registers = (span.start as usize).max(within.start)..span.end().min(within.end);
            registers.find(|&r| !occupied(r))
        })
        .min()
}

/// The whole plan for `items`: every item lies inside one of the returned reads.
#[cfg(any(feature = "std", test))]
pub fn plan(
    limits: &ModbusLimits,
    items: &[ModbusAddress],
) -> Result<std::vec::Vec<PlannedRead>, BusError> {
    let mut done = std::vec![false; items.len()];
    let mut reads = std::vec::Vec::new();
    while let Some(read) = next_read(limits, items.len(), |i| (items[i], done[i]))? {
        for (item, done) in items.iter().zip(done.iter_mut()) {
            *done |= read.offset_of(item).is_some();
        }
        reads.push(read);
    }
    Ok(reads)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::modbus::address::WordOrder;
    use proptest::prelude::*;
    use std::vec::Vec;

    fn at(table: Table, address: u16, words: u16) -> ModbusAddress {
        ModbusAddress {
            table,
            address,
            words,
            word_order: WordOrder::LowFirst,
        }
    }

    fn limits(max: u16, read_gaps: bool) -> ModbusLimits<'static> {
        ModbusLimits {
            max_read_registers: max,
            read_gaps,
            ..ModbusLimits::SPEC
        }
    }

    fn read(table: Table, start: u16, count: u16) -> PlannedRead {
        PlannedRead {
            table,
            start,
            count,
            whole_value: false,
        }
    }

    #[test]
    fn lafert_status_block_is_one_request() {
        // 0x0060..=0x0070 with the LOW/HIGH pairs 0x61/0x62 and 0x6B/0x6C as 32-bit values.
        let mut items: Vec<_> = (0x60..=0x70)
            .filter(|a| ![0x61, 0x62, 0x6B, 0x6C].contains(a))
            .map(|a| at(Table::Input, a, 1))
            .collect();
        items.push(at(Table::Input, 0x61, 2));
        items.push(at(Table::Input, 0x6B, 2));
        for read_gaps in [true, false] {
            let plan = plan(&limits(125, read_gaps), &items).unwrap();
            assert_eq!(plan, [read(Table::Input, 0x60, 17)]);
        }
    }

    #[test]
    fn tables_stay_apart_and_limits_hold() {
        let items = [
            at(Table::Holding, 0x3C, 1),
            at(Table::Input, 0x3C, 1),
            at(Table::Holding, 0x3D, 2),
        ];
        let plan = plan(&limits(125, true), &items).unwrap();
        assert_eq!(
            plan,
            [read(Table::Input, 0x3C, 1), read(Table::Holding, 0x3C, 3)]
        );
        // A pair never straddles two requests: with room for 2, 0x3C goes alone.
        let plan = super::plan(&limits(2, true), &items).unwrap();
        assert_eq!(
            plan,
            [
                read(Table::Input, 0x3C, 1),
                read(Table::Holding, 0x3C, 1),
                read(Table::Holding, 0x3D, 2)
            ]
        );
    }

    #[test]
    fn gaps_are_read_only_when_allowed() {
        let items = [at(Table::Holding, 10, 1), at(Table::Holding, 12, 1)];
        assert_eq!(
            plan(&limits(125, true), &items).unwrap(),
            [read(Table::Holding, 10, 3)]
        );
        assert_eq!(
            plan(&limits(125, false), &items).unwrap(),
            [read(Table::Holding, 10, 1), read(Table::Holding, 12, 1)]
        );
        // Overlapping values bridge each other.
        let items = [
            at(Table::Holding, 10, 2),
            at(Table::Holding, 11, 2),
            at(Table::Holding, 13, 1),
        ];
        assert_eq!(
            plan(&limits(125, false), &items).unwrap(),
            [read(Table::Holding, 10, 4)]
        );
    }

    #[test]
    fn listed_readable_registers_bridge_gaps_where_unlisted_ones_may_not_be_read() {
        // Lafert: 0x60..=0x70 are all listed; 0x71 is not.
        const LISTED: &[RegisterSpan] = &[
            RegisterSpan {
                table: Table::Input,
                start: 0x60,
                count: 0x11,
            },
            RegisterSpan {
                table: Table::Holding,
                start: 0x28,
                count: 1,
            },
        ];
        let limits = ModbusLimits {
            readable: LISTED,
            ..limits(125, false)
        };
        let items = [at(Table::Input, 0x60, 1), at(Table::Input, 0x64, 1)];
        assert_eq!(
            plan(&limits, &items).unwrap(),
            [read(Table::Input, 0x60, 5)]
        );
        // Another table's listing bridges nothing, and nothing bridges past the listing.
        let items = [at(Table::Holding, 0x60, 1), at(Table::Holding, 0x64, 1)];
        assert_eq!(plan(&limits, &items).unwrap().len(), 2);
        let items = [at(Table::Input, 0x70, 1), at(Table::Input, 0x72, 1)];
        assert_eq!(plan(&limits, &items).unwrap().len(), 2);
        // With gaps allowed the listing changes nothing.
        let open = ModbusLimits {
            read_gaps: true,
            ..limits
        };
        assert_eq!(plan(&open, &items).unwrap(), [read(Table::Input, 0x70, 3)]);
    }

    #[test]
    fn reads_stop_before_unreadable_registers_even_where_gaps_may_be_read() {
        // A write-only holding register at 16 between readable ones at 0 and 56.
        const WRITE_ONLY: &[RegisterSpan] = &[RegisterSpan::holding(16, 1)];
        let items = [at(Table::Holding, 0, 1), at(Table::Holding, 56, 1)];
        for read_gaps in [true, false] {
            let limits = ModbusLimits {
                unreadable: WRITE_ONLY,
                ..limits(125, read_gaps)
            };
            assert_eq!(
                plan(&limits, &items).unwrap(),
                [read(Table::Holding, 0, 1), read(Table::Holding, 56, 1)]
            );
        }
        let limits = ModbusLimits {
            unreadable: WRITE_ONLY,
            ..limits(125, true)
        };
        // Up to the register, and from just after it, gaps are still read.
        let items = [at(Table::Holding, 10, 1), at(Table::Holding, 15, 1)];
        assert_eq!(
            plan(&limits, &items).unwrap(),
            [read(Table::Holding, 10, 6)]
        );
        let items = [at(Table::Holding, 17, 1), at(Table::Holding, 20, 1)];
        assert_eq!(
            plan(&limits, &items).unwrap(),
            [read(Table::Holding, 17, 4)]
        );
        // A requested value on the register itself is read, and bridges nothing unreadable.
        let items = [at(Table::Holding, 14, 1), at(Table::Holding, 16, 1)];
        assert_eq!(
            plan(&limits, &items).unwrap(),
            [read(Table::Holding, 14, 3)]
        );
        // The other table is not affected.
        let items = [at(Table::Input, 0, 1), at(Table::Input, 56, 1)];
        assert_eq!(plan(&limits, &items).unwrap(), [read(Table::Input, 0, 57)]);
    }

    #[test]
    fn single_register_devices_get_one_read_per_register() {
        let items = [
            at(Table::Input, 1, 1),
            at(Table::Input, 2, 1),
            at(Table::Input, 1, 1),
        ];
        assert_eq!(
            plan(&limits(1, true), &items).unwrap(),
            [read(Table::Input, 1, 1), read(Table::Input, 2, 1)]
        );
        assert_eq!(
            plan(&limits(1, true), &[at(Table::Input, 1, 2)]),
            Err(BusError::Unsupported(
                "value wider than the device's read limit"
            ))
        );
        assert!(plan(&limits(125, true), &[at(Table::Input, 0xFFFF, 2)]).is_err());
        assert!(plan(&limits(125, true), &[at(Table::Input, 0, 0)]).is_err());
        assert_eq!(plan(&limits(125, true), &[]).unwrap(), []);
    }

    /// The fewest reads, by exhaustive search over reads starting at an item and ending at an
    /// item's end (every optimal plan can be shifted to such reads).
    fn optimum(limits: &ModbusLimits, items: &[ModbusAddress]) -> usize {
        let n = items.len();
        let requested = |table, register: usize| readable(limits, items, table, register);
        let mut windows = Vec::new();
        for s in items {
            for e in items {
                let (start, stop) = (s.address as usize, end(e));
                let ok = s.table == e.table
                    && stop > start
                    && stop - start <= read_limit(limits)
                    && (limits.read_gaps || (start..stop).all(|r| requested(s.table, r)))
                    && !(start..stop).any(|r| forbidden(limits, items, s.table, r));
                if ok {
                    let cover = read(s.table, s.address, (stop - start) as u16);
                    let mask = (0..n).filter(|&i| cover.offset_of(&items[i]).is_some());
                    windows.push(mask.fold(0u32, |m, i| m | 1 << i));
                }
            }
        }
        let mut best = std::vec![usize::MAX; 1 << n];
        best[0] = 0;
        for mask in 0..(1usize << n) {
            if best[mask] == usize::MAX {
                continue;
            }
            for w in &windows {
                let next = mask | *w as usize;
                best[next] = best[next].min(best[mask] + 1);
            }
        }
        best[(1 << n) - 1]
    }

    /// Whether some item occupies `register` of `table`.
    fn occupied(items: &[ModbusAddress], table: Table, register: usize) -> bool {
        items
            .iter()
            .any(|a| a.table == table && (a.address as usize..end(a)).contains(&register))
    }

    /// Whether some span covers `register` of `table`.
    fn covered(spans: &[RegisterSpan], table: Table, register: usize) -> bool {
        spans
            .iter()
            .any(|s| s.table == table && (s.start as usize..s.end()).contains(&register))
    }

    /// Whether a plan may read `register` where gaps may not be read: requested or listed.
    fn readable(
        limits: &ModbusLimits,
        items: &[ModbusAddress],
        table: Table,
        register: usize,
    ) -> bool {
        occupied(items, table, register) || covered(limits.readable, table, register)
    }

    /// Whether no plan may read `register`: listed as unreadable, and no item occupies it.
    fn forbidden(
        limits: &ModbusLimits,
        items: &[ModbusAddress],
        table: Table,
        register: usize,
    ) -> bool {
        covered(limits.unreadable, table, register) && !occupied(items, table, register)
    }

    fn any_item() -> impl Strategy<Value = ModbusAddress> {
        (
            prop_oneof![Just(Table::Input), Just(Table::Holding)],
            0u16..40,
            1u16..=3,
        )
            .prop_map(|(table, address, words)| at(table, address, words))
    }

    proptest! {
        #[test]
        fn plans_cover_everything_within_limits_and_are_minimal(
            items in proptest::collection::vec(any_item(), 0..7),
            max in 3u16..10,
            read_gaps in any::<bool>(),
            listed in proptest::collection::vec(any_item(), 0..3),
            write_only in proptest::collection::vec(any_item(), 0..3),
        ) {
            let spans = |items: &[ModbusAddress], scale: u16| -> Vec<RegisterSpan> {
                items.iter().map(|a| RegisterSpan { table: a.table, start: a.address, count: a.words * scale }).collect()
            };
            let (listed, write_only) = (spans(&listed, 2), spans(&write_only, 1));
            let limits = ModbusLimits {
                readable: &listed,
                unreadable: &write_only,
                ..limits(max, read_gaps)
            };
            let plan = plan(&limits, &items).unwrap();
            for item in &items {
                prop_assert!(plan.iter().any(|r| r.offset_of(item).is_some()), "{:?} not covered", item);
            }
            for r in &plan {
                prop_assert!(r.count >= 1 && r.count <= max);
                for register in r.start as usize..r.start as usize + r.count as usize {
                    prop_assert!(!forbidden(&limits, &items, r.table, register), "{:?} reads {}", r, register);
                }
                if !read_gaps {
                    for register in r.start as usize..r.start as usize + r.count as usize {
                        prop_assert!(readable(&limits, &items, r.table, register));
                    }
                }
            }
            prop_assert_eq!(plan.len(), optimum(&limits, &items));
        }
    }
}

/// `read`, or the read block holding its first register where the block covers more pending
/// values than `read` does.
fn block_instead(
    limits: &ModbusLimits,
    read: PlannedRead,
    len: usize,
    item: impl Fn(usize) -> (ModbusAddress, bool),
) -> PlannedRead {
    let pending_within = |table: Table, start: usize, stop: usize| {
        (0..len)
            .map(&item)
            .filter(|(a, done)| {
                !done && a.table == table && a.address as usize >= start && end(a) <= stop
            })
            .count()
    };
    let ordinary = pending_within(read.table, read.start as usize, end_of(&read));
    let block = limits
        .read_blocks
        .iter()
        .filter(|b| {
            b.table == read.table && (b.start as usize..b.end()).contains(&(read.start as usize))
        })
        .map(|b| (pending_within(b.table, b.start as usize, b.end()), b))
        .filter(|(covered, _)| *covered > ordinary)
        .max_by_key(|(covered, _)| *covered);
    block.map_or(read, |(_, b)| PlannedRead {
        table: b.table,
        start: b.start,
        count: b.count,
        whole_value: false,
    })
}

fn end_of(read: &PlannedRead) -> usize {
    read.start as usize + read.count as usize
}

#[cfg(test)]
mod block_tests {
    use super::*;
    use crate::modbus::address::WordOrder;

    /// The Lenze smd: one register per read, no gaps, and the status block at #24.
    /// C99, the software version: 4 words at #89 (PC400).
    const C99: RegisterSpan = RegisterSpan::holding(89, 4);
    const SMD: ModbusLimits = ModbusLimits {
        max_read_registers: 1,
        read_gaps: false,
        read_blocks: &[RegisterSpan::holding(24, 6)],
        whole_values: &[C99],
        ..ModbusLimits::SPEC
    };
    const WITHOUT_BLOCKS: ModbusLimits = ModbusLimits {
        read_blocks: &[],
        ..SMD
    };

    fn holding(address: u16) -> ModbusAddress {
        ModbusAddress {
            table: Table::Holding,
            address,
            words: 1,
            word_order: WordOrder::HighFirst,
        }
    }

    fn read(start: u16, count: u16) -> PlannedRead {
        PlannedRead {
            table: Table::Holding,
            start,
            count,
            whole_value: false,
        }
    }

    #[test]
    fn several_status_registers_take_the_block() {
        let items: std::vec::Vec<_> = (24..=29).map(holding).collect();
        assert_eq!(plan(&SMD, &items).unwrap(), [read(24, 6)]);
        assert_eq!(
            plan(&WITHOUT_BLOCKS, &items).unwrap().len(),
            6,
            "without the block: six"
        );
        let items = [holding(26), holding(29), holding(61)];
        assert_eq!(plan(&SMD, &items).unwrap(), [read(24, 6), read(61, 1)]);
    }

    #[test]
    fn one_status_register_is_read_alone() {
        for address in [24, 27, 29] {
            assert_eq!(plan(&SMD, &[holding(address)]).unwrap(), [read(address, 1)]);
        }
    }

    #[test]
    fn registers_outside_every_block_keep_the_limit() {
        let items = [holding(30), holding(31), holding(23)];
        assert_eq!(
            plan(&SMD, &items).unwrap(),
            [read(23, 1), read(30, 1), read(31, 1)]
        );
    }

    fn wide(address: u16, words: u16) -> ModbusAddress {
        ModbusAddress {
            words,
            ..holding(address)
        }
    }

    #[test]
    fn a_whole_value_wider_than_the_limit_is_read_alone() {
        let items = [holding(88), wide(89, 4), holding(90)];
        assert_eq!(
            plan(&SMD, &items).unwrap(),
            [
                read(88, 1),
                PlannedRead {
                    whole_value: true,
                    ..read(89, 4)
                },
                read(90, 1)
            ]
        );
    }

    #[test]
    fn a_wide_value_the_device_does_not_answer_whole_is_refused() {
        for item in [wide(89, 3), wide(90, 4), wide(24, 6)] {
            assert_eq!(
                plan(&SMD, &[item]),
                Err(BusError::Unsupported(
                    "value wider than the device's read limit"
                )),
                "{item:?}"
            );
        }
    }
}
