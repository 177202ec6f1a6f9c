//! The watchdog keep-alive polls the status block at a third of n23, records a stretch without
//! answers longer than n23 once, and stops polling when dropped. Time margins are wide: the test
//! asserts orders, not durations.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::sleep;
use std::time::Duration;

use drivebus::modbus::{ModbusLine, ModbusLink, RegisterBus, Table, UnitId};
use drivebus::testing::MemoryBus;
use drivebus::BusError;
use lenze_smd::{KeepAlive, LenzeSmd};

/// A drive map that counts status-block reads and can fall silent.
#[derive(Debug, Clone, Default)]
struct Line {
    silent: Arc<AtomicBool>,
    block_reads: Arc<AtomicUsize>,
}

#[derive(Debug)]
struct FlakyDrive {
    memory: MemoryBus,
    line: Line,
}

impl RegisterBus for FlakyDrive {
    fn read_registers(
        &mut self,
        unit: UnitId,
        table: Table,
        start: u16,
        out: &mut [u16],
    ) -> Result<(), BusError> {
        if self.line.silent.load(Ordering::SeqCst) {
            return Err(BusError::Timeout);
        }
        if (start, out.len()) == (24, 6) {
            self.line.block_reads.fetch_add(1, Ordering::SeqCst);
        }
        self.memory.read_registers(unit, table, start, out)
    }
    fn write_register(&mut self, unit: UnitId, address: u16, value: u16) -> Result<(), BusError> {
        self.memory.write_register(unit, address, value)
    }
    fn write_registers(
        &mut self,
        unit: UnitId,
        start: u16,
        values: &[u16],
    ) -> Result<(), BusError> {
        self.memory.write_registers(unit, start, values)
    }
}

fn drive(line: &Line) -> LenzeSmd<ModbusLink<FlakyDrive>> {
    let mut memory = MemoryBus::new();
    for r in 24..=29 {
        memory.set_register(Table::Holding, r, 0);
    }
    // n22 = 3 (trip FC3), n23 = 300 ms, PC400 registers #114 / #115.
    memory
        .set_register(Table::Holding, 114, 3)
        .set_register(Table::Holding, 115, 300);
    let flaky = FlakyDrive {
        memory,
        line: line.clone(),
    };
    LenzeSmd::modbus(flaky, UnitId(1))
}

#[test]
fn the_timeout_comes_from_n22_and_n23() {
    let line = Line::default();
    let mut d = drive(&line);
    assert_eq!(
        d.watchdog_timeout().unwrap(),
        Some(Duration::from_millis(300))
    );
    d.device()
        .link_mut()
        .bus_mut()
        .memory
        .set_register(Table::Holding, 114, 0);
    assert_eq!(d.watchdog_timeout().unwrap(), None, "n22 = 0: not active");
}

#[test]
fn polls_under_half_the_timeout() {
    let timeout = Duration::from_millis(300);
    assert!(KeepAlive::interval_for(timeout) * 2 < timeout);
}

#[test]
fn keeps_polling_and_reports_a_silence_longer_than_the_timeout() {
    let line = Line::default();
    let drive = Arc::new(Mutex::new(drive(&line)));
    let timeout = Duration::from_millis(90);
    let keep_alive = KeepAlive::spawn(Arc::clone(&drive), timeout);
    sleep(Duration::from_millis(300));
    let before = keep_alive.report();
    assert!(before.polls >= 2, "{before:?}");
    assert!(before.missed.is_empty(), "{before:?}");
    assert!(line.block_reads.load(Ordering::SeqCst) >= 2);

    line.silent.store(true, Ordering::SeqCst);
    sleep(Duration::from_millis(400));
    line.silent.store(false, Ordering::SeqCst);
    sleep(Duration::from_millis(300));
    let after = keep_alive.report();
    assert_eq!(after.missed.len(), 1, "one silence, one miss: {after:?}");
    assert!(after.missed[0].silent_for > timeout);
    assert_eq!(
        after.last_error.as_ref().and_then(|e| e.bus()),
        Some(&BusError::Timeout)
    );
    assert!(after.polls > before.polls, "polling resumed: {after:?}");
}

#[test]
fn dropping_the_keep_alive_stops_polling() {
    let line = Line::default();
    let drive = Arc::new(Mutex::new(drive(&line)));
    let keep_alive = KeepAlive::spawn(Arc::clone(&drive), Duration::from_millis(60));
    sleep(Duration::from_millis(150));
    drop(keep_alive);
    let stopped_at = line.block_reads.load(Ordering::SeqCst);
    assert!(stopped_at > 0);
    sleep(Duration::from_millis(150));
    assert_eq!(line.block_reads.load(Ordering::SeqCst), stopped_at);
    // The drive is free again for the application.
    assert!(drive.lock().unwrap().status().is_ok());
}

#[test]
fn for_drive_follows_n22_and_n23() {
    let line = Line::default();
    let drive = Arc::new(Mutex::new(drive(&line)));
    let keep_alive = KeepAlive::for_drive(Arc::clone(&drive)).unwrap().unwrap();
    assert_eq!(
        keep_alive.interval(),
        Duration::from_millis(100),
        "n23 = 300 ms / 3"
    );
    drop(keep_alive);
    drive
        .lock()
        .unwrap()
        .device()
        .link_mut()
        .bus_mut()
        .memory
        .set_register(Table::Holding, 114, 0);
    assert!(KeepAlive::for_drive(drive).unwrap().is_none(), "n22 = 0");
}

#[test]
fn one_line_carries_an_unlocked_drive_and_its_keep_alive() {
    // On one RS-485 line there is no second connection: the application's handle and the
    // keep-alive's share the line through `ModbusLine`, request by request (line 372: poll at
    // under half of n23 while unlocked).
    let line = Line::default();
    let mut memory = drive(&line).into_link().into_bus();
    // C01 = 10 (serial control, line 411), #48 writable.
    memory
        .memory
        .set_register(Table::Holding, 51, 10)
        .set_register(Table::Holding, 48, 1)
        .set_register(Table::Holding, 1, 0);
    let bus = ModbusLine::new(memory);
    let mut application = LenzeSmd::modbus(bus.clone(), UnitId(1));
    let polling = Arc::new(Mutex::new(LenzeSmd::modbus(bus.clone(), UnitId(1))));
    let keep_alive = KeepAlive::spawn(polling, Duration::from_millis(90));
    let session = application.unlock_controls().unwrap();
    sleep(Duration::from_millis(300));
    let report = keep_alive.report();
    assert!(report.polls >= 2, "polled while unlocked: {report:?}");
    assert!(report.missed.is_empty(), "{report:?}");
    assert!(line.block_reads.load(Ordering::SeqCst) >= 2);
    session.lock().unwrap();
    drop(keep_alive);
    assert_eq!(
        bus.lock().unwrap().memory.register(Table::Holding, 48),
        Some(0),
        "the unlock went over the shared line"
    );
}

/// The flaky drive behind the async handle (its requests complete at once).
fn async_drive(
    line: &Line,
) -> LenzeSmd<drivebus::asynch::Async<drivebus::testing::Immediate<ModbusLink<FlakyDrive>>>> {
    let link = drive(line).into_link();
    LenzeSmd::new(drivebus::asynch::Async(drivebus::testing::Immediate(link)))
}

#[test]
fn the_async_keep_alive_records_what_the_thread_records() {
    use drivebus::testing::now;
    use lenze_smd::AsyncKeepAlive;
    let line = Line::default();
    let mut drive = async_drive(&line);
    let ms = Duration::from_millis;
    let mut keep_alive = AsyncKeepAlive::new(ms(90));
    assert_eq!(keep_alive.interval(), KeepAlive::interval_for(ms(90)));
    for at in [30, 60] {
        now(keep_alive.poll(&mut drive, ms(at))).unwrap();
    }
    assert_eq!(keep_alive.report().polls, 2);
    assert_eq!(
        line.block_reads.load(Ordering::SeqCst),
        2,
        "one block read a poll"
    );
    // Silent from 60 ms: the miss is noticed once, at the first poll past 60 + 90 ms.
    line.silent.store(true, Ordering::SeqCst);
    for at in [90, 120, 150, 180, 210] {
        now(keep_alive.poll(&mut drive, ms(at))).unwrap();
    }
    line.silent.store(false, Ordering::SeqCst);
    now(keep_alive.poll(&mut drive, ms(240))).unwrap();
    let report = keep_alive.report();
    assert_eq!(report.polls, 3, "{report:?}");
    assert_eq!(report.missed.len(), 1, "{report:?}");
    assert_eq!(report.missed[0].silent_for, ms(120));
    assert_eq!(
        report.last_error.as_ref().and_then(|e| e.bus()),
        Some(&BusError::Timeout)
    );
}

#[tokio::test]
async fn the_async_keep_alive_runs_until_dropped() {
    use drivebus::asynch::TokioTimer;
    use lenze_smd::AsyncKeepAlive;
    let line = Line::default();
    let mut drive = async_drive(&line);
    let timeout = drive.watchdog_timeout_async().await.unwrap().unwrap();
    let mut keep_alive = AsyncKeepAlive::new(timeout);
    let ran = tokio::time::timeout(
        Duration::from_millis(350),
        keep_alive.run(&mut drive, &TokioTimer),
    )
    .await;
    assert!(ran.is_err(), "`run` never completes");
    // 300 ms timeout: a poll every 100 ms, three in 350 ms.
    assert!(keep_alive.report().polls >= 2, "{:?}", keep_alive.report());
    let stopped_at = line.block_reads.load(Ordering::SeqCst);
    tokio::time::sleep(Duration::from_millis(150)).await;
    assert_eq!(line.block_reads.load(Ordering::SeqCst), stopped_at);
    // The drive is the application's again.
    assert!(drive.status_async().await.is_ok());
}
