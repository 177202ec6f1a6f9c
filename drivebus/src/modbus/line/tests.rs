use super::*;
use crate::testing::{MemoryBus, Request};
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::thread;
use std::time::Duration;
use std::vec::Vec;

#[test]
fn clones_talk_over_one_bus_request_by_request() {
    let mut memory = MemoryBus::new();
    memory
        .set_register(Table::Holding, 1, 0)
        .set_register(Table::Holding, 2, 0);
    let line = ModbusLine::new(memory);
    let threads: Vec<_> = (0..4u16)
        .map(|n| {
            let mut bus = line.clone();
            thread::spawn(move || {
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
    let writes = line
        .lock()
        .unwrap()
        .log()
        .iter()
        .filter(|r| matches!(r, Request::Write { .. }))
        .count();
    assert_eq!(writes, 200, "every clone's writes reached the one bus");
}

/// A line where every request takes a while, and which counts the requests of each unit.
#[derive(Debug, Default)]
struct SlowLine {
    served: BTreeMap<u8, usize>,
    order: Vec<u8>,
}

impl RegisterBus for SlowLine {
    fn read_registers(
        &mut self,
        unit: UnitId,
        _table: Table,
        _start: u16,
        out: &mut [u16],
    ) -> Result<(), BusError> {
        // Long enough for every other handle to queue up behind this one.
        thread::sleep(Duration::from_micros(300));
        *self.served.entry(unit.0).or_default() += 1;
        self.order.push(unit.0);
        out.fill(u16::from(unit.0));
        Ok(())
    }
    fn write_register(&mut self, _: UnitId, _: u16, _: u16) -> Result<(), BusError> {
        Ok(())
    }
    fn write_registers(&mut self, _: UnitId, _: u16, _: &[u16]) -> Result<(), BusError> {
        Ok(())
    }
}

#[test]
fn units_polling_in_tight_loops_are_served_in_turn() {
    let line = ModbusLine::new(SlowLine::default());
    let stop = std::sync::Arc::new(AtomicBool::new(false));
    let start = std::sync::Arc::new(std::sync::Barrier::new(4));
    let threads: Vec<_> = (1..=4u8)
        .map(|unit| {
            let (mut line, stop) = (line.clone(), std::sync::Arc::clone(&stop));
            let start = std::sync::Arc::clone(&start);
            thread::spawn(move || {
                let mut out = [0u16; 1];
                start.wait();
                while !stop.load(Ordering::Relaxed) {
                    line.read_registers(UnitId(unit), Table::Input, 0, &mut out)
                        .unwrap();
                    assert_eq!(out[0], u16::from(unit), "its own unit's answer");
                }
            })
        })
        .collect();
    thread::sleep(Duration::from_millis(300));
    stop.store(true, Ordering::Relaxed);
    for thread in threads {
        thread.join().unwrap();
    }
    let served = line.lock().unwrap().served.clone();
    assert_eq!(served.len(), 4, "{served:?}");
    assert!(served.values().all(|&n| n >= 10), "{served:?}");
    // First come, first served: each unit waits behind the three others every time, so the
    // counts stay close (a barging lock lets the releasing thread take it again, and the
    // others starve). Not exact: a thread the scheduler leaves asleep loses its turns.
    let most = served.values().max().copied().unwrap_or(0);
    assert!(
        served.values().all(|&n| 4 * n >= 3 * most),
        "unfair: {served:?}"
    );
}

#[test]
fn threads_are_served_in_the_order_they_asked() {
    let line = ModbusLine::new(SlowLine::default());
    let held = line.lock().unwrap();
    thread::scope(|scope| {
        for (queued, unit) in [3u8, 1, 4, 2].into_iter().enumerate() {
            let mut handle = line.clone();
            scope.spawn(move || {
                handle
                    .read_registers(UnitId(unit), Table::Input, 0, &mut [0])
                    .unwrap();
            });
            // The next thread asks only once this one waits.
            while line.shared.turns.waiting() <= queued {
                thread::yield_now();
            }
        }
        drop(held);
    });
    assert_eq!(line.lock().unwrap().order, [3, 1, 4, 2]);
}

#[test]
fn closing_the_line_sends_every_waiting_thread_away() {
    let line = ModbusLine::new(SlowLine::default());
    let held = line.lock().unwrap();
    let waiting = AtomicUsize::new(0);
    thread::scope(|scope| {
        let threads: Vec<_> = (1..=3u8)
            .map(|unit| {
                let (mut line, waiting) = (line.clone(), &waiting);
                scope.spawn(move || {
                    waiting.fetch_add(1, Ordering::SeqCst);
                    line.read_registers(UnitId(unit), Table::Input, 0, &mut [0])
                })
            })
            .collect();
        while waiting.load(Ordering::SeqCst) < 3 {
            thread::yield_now();
        }
        thread::sleep(Duration::from_millis(20));
        line.close();
        for thread in threads {
            assert_eq!(thread.join().unwrap(), Err(BusError::Closed));
        }
    });
    drop(held);
    assert!(line.is_closed());
    let mut late = line.clone();
    assert_eq!(
        late.read_registers(UnitId(1), Table::Input, 0, &mut [0]),
        Err(BusError::Closed),
        "a later request is refused too"
    );
}

/// A bus whose connection has ended.
struct Ended;

impl RegisterBus for Ended {
    fn read_registers(
        &mut self,
        _: UnitId,
        _: Table,
        _: u16,
        _: &mut [u16],
    ) -> Result<(), BusError> {
        Err(BusError::Closed)
    }
    fn write_register(&mut self, _: UnitId, _: u16, _: u16) -> Result<(), BusError> {
        Err(BusError::Timeout)
    }
    fn write_registers(&mut self, _: UnitId, _: u16, _: &[u16]) -> Result<(), BusError> {
        Err(BusError::Timeout)
    }
}

#[test]
fn a_bus_that_reports_its_connection_ended_closes_the_line() {
    let mut line = ModbusLine::new(Ended);
    assert_eq!(line.write_register(UnitId(1), 0, 0), Err(BusError::Timeout));
    assert!(
        !line.is_closed(),
        "a timeout is one unit's silence, not the line's end"
    );
    assert_eq!(
        line.read_registers(UnitId(1), Table::Input, 0, &mut [0]),
        Err(BusError::Closed)
    );
    assert!(line.is_closed());
}

#[test]
fn a_handle_that_panicked_holding_the_line_leaves_it_usable() {
    let line = ModbusLine::new(SlowLine::default());
    let panicking = line.clone();
    let outcome = thread::spawn(move || {
        let _held = panicking.lock().unwrap();
        panic!("a handle's bug");
    })
    .join();
    assert!(outcome.is_err());
    let mut line2 = line.clone();
    assert_eq!(
        line2.read_registers(UnitId(2), Table::Input, 0, &mut [0]),
        Ok(())
    );
}

#[cfg(feature = "tokio")]
mod asynch {
    use super::*;
    use crate::modbus::AsyncRegisterBus;

    /// An async line where each request awaits a few times, counting each unit's requests.
    #[derive(Debug, Default)]
    struct YieldingLine {
        served: BTreeMap<u8, usize>,
    }

    impl AsyncRegisterBus for YieldingLine {
        async fn read_registers(
            &mut self,
            unit: UnitId,
            _table: Table,
            _start: u16,
            out: &mut [u16],
        ) -> Result<(), BusError> {
            // Every other task gets polled, and queues, while this one holds the line.
            for _ in 0..4 {
                tokio::task::yield_now().await;
            }
            *self.served.entry(unit.0).or_default() += 1;
            out.fill(u16::from(unit.0));
            Ok(())
        }
        async fn write_register(&mut self, _: UnitId, _: u16, _: u16) -> Result<(), BusError> {
            tokio::time::sleep(Duration::from_millis(50)).await;
            Ok(())
        }
        async fn write_registers(&mut self, _: UnitId, _: u16, _: &[u16]) -> Result<(), BusError> {
            Ok(())
        }
    }

    /// The spread between the most and the least served unit.
    fn spread(served: &BTreeMap<u8, usize>) -> usize {
        let most = served.values().max().copied().unwrap_or(0);
        let least = served.values().min().copied().unwrap_or(0);
        most - least
    }

    fn assert_send<T: Send>(value: T) -> T {
        value
    }

    #[tokio::test]
    async fn tasks_polling_in_tight_loops_are_served_in_turn() {
        let line = ModbusLine::new(YieldingLine::default());
        let total = std::sync::Arc::new(AtomicUsize::new(0));
        let tasks: Vec<_> = (1..=5u8)
            .map(|unit| {
                let (mut line, total) = (line.clone(), std::sync::Arc::clone(&total));
                tokio::spawn(assert_send(async move {
                    let mut out = [0u16; 1];
                    while total.fetch_add(1, Ordering::SeqCst) < 500 {
                        line.read_registers(UnitId(unit), Table::Input, 0, &mut out)
                            .await
                            .unwrap();
                        assert_eq!(out[0], u16::from(unit));
                    }
                }))
            })
            .collect();
        for task in tasks {
            task.await.unwrap();
        }
        let served = line.lock_async().await.unwrap().served.clone();
        assert_eq!(served.values().sum::<usize>(), 500, "{served:?}");
        assert!(spread(&served) <= 1, "unfair: {served:?}");
    }

    #[tokio::test]
    async fn closing_the_line_sends_every_waiting_task_away() {
        let line = ModbusLine::new(YieldingLine::default());
        let mut holder = line.clone();
        let holding = tokio::spawn(async move { holder.write_register(UnitId(1), 0, 0).await });
        tokio::task::yield_now().await;
        let waiters: Vec<_> = (2..=4u8)
            .map(|unit| {
                let mut line = line.clone();
                tokio::spawn(async move {
                    line.read_registers(UnitId(unit), Table::Input, 0, &mut [0])
                        .await
                })
            })
            .collect();
        tokio::time::sleep(Duration::from_millis(10)).await;
        line.close();
        for waiter in waiters {
            let outcome = tokio::time::timeout(Duration::from_millis(20), waiter)
                .await
                .expect("no waiter hangs on a closed line");
            assert_eq!(outcome.unwrap(), Err(BusError::Closed));
        }
        assert_eq!(
            holding.await.unwrap(),
            Ok(()),
            "the request on the wire finishes"
        );
    }

    #[tokio::test]
    async fn a_task_dropped_while_waiting_leaves_the_queue() {
        let line = ModbusLine::new(YieldingLine::default());
        let mut holder = line.clone();
        let holding = tokio::spawn(async move { holder.write_register(UnitId(1), 0, 0).await });
        tokio::task::yield_now().await;
        let mut impatient = line.clone();
        let gave_up = tokio::time::timeout(
            Duration::from_millis(5),
            impatient.read_registers(UnitId(2), Table::Input, 0, &mut [0]),
        )
        .await;
        assert!(gave_up.is_err(), "still waiting behind the holder");
        assert_eq!(holding.await.unwrap(), Ok(()));
        let mut next = line.clone();
        let mut out = [0u16];
        tokio::time::timeout(
            Duration::from_millis(100),
            next.read_registers(UnitId(3), Table::Input, 0, &mut out),
        )
        .await
        .expect("the abandoned place does not block the line")
        .unwrap();
        assert_eq!(out, [3]);
    }
}
