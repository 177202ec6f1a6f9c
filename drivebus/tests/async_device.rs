//! The typed async API (`Device<Async<L>>`, its accessors, `read_many`) against the blocking
//! one: every operation, run on two devices in the same state, one blocking and one async, gives
//! the same outcome and sends the same requests (range, bounds read first, stops never refused,
//! refusals, run-time scales, sub-index runs, batch reads).
#![cfg(all(feature = "modbus", feature = "canopen", feature = "async"))]

use std::fmt::Debug;

use drivebus::asynch::Async;
use drivebus::canopen::{CanOpenLink, NodeId};
use drivebus::indexed::{Indexed, Run};
use drivebus::modbus::{ModbusLimits, ModbusLink, Table, UnitId};
use drivebus::testing::{now, Immediate, MemoryBus, Request};
use drivebus::units::Rpm;
use drivebus::{Device, Error, Link, Ratio, Scale, VariantId, WriteRefusal};

/// The full scale, an unsigned bound of a signed setpoint and the input of a run-time scale.
pub struct FullScale;
drivebus::parameter!(FullScale = "full_scale": u16 => Rpm, InUnit; read modbus (holding 0x0003));

/// Within ± the full scale, range-checked.
pub struct Setpoint;
drivebus::parameter!(Setpoint = "setpoint": i16 => Rpm, InUnit, range(-5000, 5000);
    read modbus (input 0x0042);
    write modbus (holding 0x0042) [bounds: magnitude = FullScale]);

/// Any value but 0 stops nothing; 0 stops the drive.
pub struct Frequency;
drivebus::parameter!(Frequency = "frequency": u16 => u16, Plain, stops(0xFFFF => 0x0000);
    read modbus (holding 0x0012); write modbus (holding 0x0012));

/// Per mille of the full scale: a run-time scale that reads `full_scale`.
pub struct Load;
drivebus::parameter!(Load = "load": u16 => Rpm, InUnit;
    read modbus (input 0x0050) runtime; write modbus (holding 0x0050) runtime);

impl Load {
    fn runtime_scale<L: Link>(device: &mut Device<L>) -> Result<Scale, Error>
    where
        FullScale: drivebus::Readable<L::Protocol>,
    {
        let full_scale = device.read_raw::<FullScale>()?;
        let bad = Error::Value(drivebus::ValueError::BadScale { parameter: "load" });
        Ok(Scale::factor(
            Ratio::new(full_scale.into(), 1000).ok_or(bad)?,
        ))
    }
}

/// Sub-indices 1..=3 of 2000h.
pub struct Limit;
drivebus::parameter!(Limit = "limit": u16 => u16, Plain, range(0, 1000);
    read canopen (0x2000 sub 1, 2 bytes); write canopen (0x2000 sub 1, 2 bytes));
impl Run for Limit {
    const FIRST: u8 = 1;
    const LAST: u8 = 3;
}

type Blocking = Device<ModbusLink<MemoryBus>>;
type Awaited = Device<Async<Immediate<ModbusLink<MemoryBus>>>>;

fn bus() -> MemoryBus {
    let mut bus = MemoryBus::new();
    // Every register between the values reads 0: a batch spans them.
    for address in 0..=0x52 {
        bus.set_register(Table::Holding, address, 0);
        bus.set_register(Table::Input, address, 0);
    }
    for (table, address, value) in [
        (Table::Holding, 0x03, 3000),
        (Table::Input, 0x42, (-1200i16) as u16),
        (Table::Holding, 0x42, 0),
        (Table::Holding, 0x12, 100),
        (Table::Input, 0x50, 500),
    ] {
        bus.set_register(table, address, value);
    }
    bus
}

fn pair() -> (Blocking, Awaited) {
    let link = || ModbusLink::new(bus(), UnitId(1), ModbusLimits::SPEC);
    (
        Device::new(link(), VariantId(0)),
        Device::new(Async(Immediate(link())), VariantId(0)),
    )
}

/// Runs `blocking` and `awaited` on the two devices; both give the same outcome and leave the
/// same request log.
fn same<T: PartialEq + Debug>(
    devices: &mut (Blocking, Awaited),
    blocking: impl FnOnce(&mut Blocking) -> T,
    awaited: impl AsyncFnOnce(&mut Awaited) -> T,
) -> T {
    let expected = blocking(&mut devices.0);
    let got = now(awaited(&mut devices.1)).expect("the immediate link never waits");
    assert_eq!(got, expected);
    let async_log = devices.1.link_mut().get_mut().0.bus_mut().log().to_vec();
    assert_eq!(async_log, devices.0.link_mut().bus_mut().log());
    got
}

#[test]
fn reads_decode_as_the_blocking_ones() {
    let mut d = pair();
    let value = same(
        &mut d,
        |b| b.read::<Setpoint>(),
        async |a| a.read::<Setpoint>().await,
    );
    assert_eq!(value, Ok(Rpm(-1200.0)));
    let raw = same(
        &mut d,
        |b| b.read_raw::<Setpoint>(),
        async |a| a.parameter::<Setpoint>().read_raw().await,
    );
    assert_eq!(raw, Ok(-1200));
    let load = same(
        &mut d,
        |b| b.read::<Load>(),
        async |a| a.parameter::<Load>().read().await,
    );
    assert_eq!(load, Ok(Rpm(1500.0)), "500 per mille of 3000 rpm");
}

#[test]
fn writes_are_checked_bounded_and_scaled_as_the_blocking_ones() {
    let mut d = pair();
    for rpm in [3001.0, -3001.0, 6000.0, -3000.0, 12.0] {
        let _refused_or_sent = same(
            &mut d,
            |b| b.parameter::<Setpoint>().write(Rpm(rpm)),
            async |a| a.parameter::<Setpoint>().write(Rpm(rpm)).await,
        );
    }
    let beyond = same(
        &mut d,
        |b| b.write_raw::<Setpoint>(-3001),
        async |a| a.write_raw::<Setpoint>(-3001).await,
    );
    let written = same(
        &mut d,
        |b| b.parameter::<Load>().write(Rpm(300.0)),
        async |a| a.parameter::<Load>().write(Rpm(300.0)).await,
    );
    assert_eq!(written, Ok(()));
    let modified = same(
        &mut d,
        |b| b.parameter::<Frequency>().modify(|f| f + 1),
        async |a| a.parameter::<Frequency>().modify(|f| f + 1).await,
    );
    assert!(matches!(beyond, Err(Error::OutsideBound(_))));
    assert_eq!(modified, Ok(()));
    let log = d.1.link_mut().get_mut().0.bus_mut().log().to_vec();
    assert!(log.contains(&Request::Write {
        start: 0x50,
        values: vec![100]
    }));
    assert!(log.contains(&Request::Write {
        start: 0x12,
        values: vec![101]
    }));
}

#[test]
fn refused_writes_are_refused_but_a_stop_is_sent() {
    let mut d = pair();
    let reason = WriteRefusal::UnknownVariant {
        selector: "model",
        value: 9,
    };
    d.0.refuse_writes(reason);
    d.1.refuse_writes(reason);
    let refused = same(
        &mut d,
        |b| b.write_raw::<Frequency>(5),
        async |a| a.write_raw::<Frequency>(5).await,
    );
    assert!(matches!(refused, Err(Error::WritesRefused { .. })));
    let stop = same(
        &mut d,
        |b| b.write_raw::<Frequency>(0),
        async |a| a.write_raw::<Frequency>(0).await,
    );
    assert_eq!(stop, Ok(()));
}

#[test]
fn a_batch_is_one_planned_request_set_as_the_blocking_one() {
    let mut d = pair();
    let values = same(
        &mut d,
        |b| b.read_many((Setpoint, FullScale, Load, Frequency)),
        async |a| a.read_many((Setpoint, FullScale, Load, Frequency)).await,
    );
    assert_eq!(values, Ok((Rpm(-1200.0), Rpm(3000.0), Rpm(1500.0), 100)));
}

#[test]
fn a_sub_index_run_is_reached_and_checked_as_the_blocking_one() {
    let mut memory = MemoryBus::new();
    for sub in 1..=3u8 {
        memory.set_object(0x2000, sub, &u16::from(sub * 10).to_le_bytes());
    }
    let mut device = Device::new(
        Async(Immediate(CanOpenLink::new(memory, NodeId(1)))),
        VariantId(0),
    );
    assert_eq!(
        now(Indexed::<_, Limit>::new(&mut device, 2).read()),
        Some(Ok(20))
    );
    assert_eq!(
        now(Indexed::<_, Limit>::new(&mut device, 3).write(7u16)),
        Some(Ok(()))
    );
    assert_eq!(
        now(Indexed::<_, Limit>::new(&mut device, 3).read_raw()),
        Some(Ok(7))
    );
    let outside = now(Indexed::<_, Limit>::new(&mut device, 4).write_raw(1));
    assert!(matches!(outside, Some(Err(Error::Value(_)))));
    let beyond = now(Indexed::<_, Limit>::new(&mut device, 1).write_raw(1001));
    assert!(matches!(beyond, Some(Err(Error::Value(_)))));
}

#[test]
fn a_parameter_behind_an_unlock_is_read_as_the_blocking_one_reads_it() {
    let mut d = pair();
    let value = same(
        &mut d,
        |b| drivebus::LockedAccessor::new(b.parameter::<Setpoint>()).read(),
        async |a| {
            drivebus::LockedAccessor::new(a.parameter::<Setpoint>())
                .read()
                .await
        },
    );
    assert_eq!(value, Ok(Rpm(-1200.0)));
}
