//! Modbus TCP pipelining across handles (`modbus::pipeline::TcpPipeline`) against scripted
//! servers on 127.0.0.1: requests from several tasks are in flight at once on one connection,
//! each answered by its own transaction id whatever the order of the answers; a dropped
//! request's late answer is discarded and the next request gets its own; a connection closed
//! under pending requests gives each of them a typed error, not a hang.

use std::time::Duration;

use drivebus::modbus::async_client::AsyncClientConfig;
use drivebus::modbus::pipeline::TokioPipeline;
use drivebus::modbus::{AsyncRegisterBus, RegisterRead, Table, UnitId};
use drivebus::BusError;
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::{TcpListener, TcpStream};
use tokio::time::timeout;

const UNIT: UnitId = UnitId(1);

async fn listener() -> (TcpListener, String) {
    let listener = TcpListener::bind("127.0.0.1:0").await.unwrap();
    let address = listener.local_addr().unwrap().to_string();
    (listener, address)
}

/// The next connection, without Nagle's delay (answers back to back must not wait).
async fn accept(listener: &TcpListener) -> TcpStream {
    let (stream, _) = listener.accept().await.unwrap();
    stream.set_nodelay(true).unwrap();
    stream
}

/// One MBAP read of one holding register: its transaction id and register address.
async fn request(stream: &mut TcpStream) -> Option<([u8; 2], u16)> {
    let mut adu = [0u8; 12];
    stream.read_exact(&mut adu).await.ok()?;
    Some(([adu[0], adu[1]], u16::from_be_bytes([adu[8], adu[9]])))
}

/// The answer with transaction id `tid`: one register holding `value`.
fn answer(tid: [u8; 2], value: u16) -> Vec<u8> {
    let [hi, lo] = value.to_be_bytes();
    vec![tid[0], tid[1], 0, 0, 0, 5, UNIT.0, 0x03, 2, hi, lo]
}

/// What the scripted servers answer for register `address`.
fn value_of(address: u16) -> u16 {
    address * 10
}

/// Reads `n` requests before answering any (so they were in flight at once; each with its own
/// transaction id), then answers them last first, in one write.
async fn all_then_last_first(stream: &mut TcpStream, n: usize) {
    let mut requests = Vec::new();
    for _ in 0..n {
        requests.push(request(stream).await.unwrap());
    }
    let mut tids: Vec<_> = requests.iter().map(|(tid, _)| *tid).collect();
    tids.sort_unstable();
    tids.dedup();
    assert_eq!(tids.len(), n, "each request has its own transaction id");
    let answers: Vec<u8> = requests
        .iter()
        .rev()
        .flat_map(|&(tid, address)| answer(tid, value_of(address)))
        .collect();
    stream.write_all(&answers).await.unwrap();
}

async fn pipeline(address: &str, timeout: Duration) -> TokioPipeline {
    let config = AsyncClientConfig {
        timeout,
        ..AsyncClientConfig::default()
    };
    TokioPipeline::connect(address, &config).await.unwrap()
}

async fn read(mut bus: TokioPipeline, address: u16) -> Result<u16, BusError> {
    let mut value = [0u16];
    bus.read_registers(UNIT, Table::Holding, address, &mut value)
        .await
        .map(|()| value[0])
}

#[tokio::test]
async fn requests_of_several_tasks_are_in_flight_at_once_and_matched_by_transaction_id() {
    let (listener, address) = listener().await;
    let server = tokio::spawn(async move {
        let mut stream = accept(&listener).await;
        for _round in 0..20 {
            // All four requests are read before any is answered: they are in flight at once.
            all_then_last_first(&mut stream, 4).await;
        }
    });
    let bus = pipeline(&address, Duration::from_secs(5)).await;
    for _round in 0..20 {
        let tasks: Vec<_> = (0..4u16)
            .map(|task| tokio::spawn(read(bus.clone(), 0x10 + task)))
            .collect();
        for (task, handle) in tasks.into_iter().enumerate() {
            let register = 0x10 + task as u16;
            assert_eq!(handle.await.unwrap(), Ok(value_of(register)), "task {task}");
        }
    }
    assert_eq!(bus.in_flight(), 0);
    server.await.unwrap();
}

#[tokio::test]
async fn a_dropped_requests_late_answer_is_discarded_and_the_next_gets_its_own() {
    let (listener, address) = listener().await;
    let server = tokio::spawn(async move {
        let mut stream = accept(&listener).await;
        let (dropped, _) = request(&mut stream).await.unwrap();
        // Held back until the next request is in: then the dropped one's answer comes first.
        let (next, register) = request(&mut stream).await.unwrap();
        assert_ne!(dropped, next, "the next request has its own transaction id");
        stream.write_all(&answer(dropped, 111)).await.unwrap();
        stream
            .write_all(&answer(next, value_of(register)))
            .await
            .unwrap();
        stream
    });
    let bus = pipeline(&address, Duration::from_secs(2)).await;
    let dropped = timeout(Duration::from_millis(50), read(bus.clone(), 0x10)).await;
    assert!(dropped.is_err(), "the first request is dropped unanswered");
    assert_eq!(bus.in_flight(), 0, "a dropped request gives up its slot");
    assert_eq!(read(bus.clone(), 0x20).await, Ok(value_of(0x20)));
    drop(server.await.unwrap());
}

#[tokio::test]
async fn a_request_dropped_while_another_task_waits_leaves_that_task_its_answer() {
    let (listener, address) = listener().await;
    let server = tokio::spawn(async move {
        let mut stream = accept(&listener).await;
        let (first, _) = request(&mut stream).await.unwrap();
        let (second, register) = request(&mut stream).await.unwrap();
        // The first task gave up meanwhile (it may have been the one reading).
        tokio::time::sleep(Duration::from_millis(100)).await;
        stream.write_all(&answer(first, 1)).await.unwrap();
        stream
            .write_all(&answer(second, value_of(register)))
            .await
            .unwrap();
        stream
    });
    let bus = pipeline(&address, Duration::from_secs(2)).await;
    let gives_up = tokio::spawn(timeout(Duration::from_millis(50), read(bus.clone(), 0x10)));
    // Sent after the first: the server reads them in this order.
    tokio::time::sleep(Duration::from_millis(10)).await;
    let waits = tokio::spawn(read(bus.clone(), 0x30));
    assert!(gives_up.await.unwrap().is_err());
    assert_eq!(waits.await.unwrap(), Ok(value_of(0x30)));
    drop(server.await.unwrap());
}

#[tokio::test]
async fn a_connection_closed_under_pending_requests_fails_each_of_them() {
    let (listener, address) = listener().await;
    let server = tokio::spawn(async move {
        let mut stream = accept(&listener).await;
        for _ in 0..3 {
            request(&mut stream).await.unwrap();
        }
        // Closed without an answer.
    });
    let bus = pipeline(&address, Duration::from_secs(5)).await;
    let tasks: Vec<_> = (0..3u16)
        .map(|task| tokio::spawn(read(bus.clone(), task)))
        .collect();
    for task in tasks {
        let outcome = timeout(Duration::from_secs(1), task).await;
        assert_eq!(
            outcome.map(Result::unwrap),
            Ok(Err(BusError::Closed)),
            "well before the 5 s timeout"
        );
    }
    // And every later request.
    assert_eq!(read(bus.clone(), 0).await, Err(BusError::Closed));
    server.await.unwrap();
}

#[tokio::test]
async fn one_handles_batch_is_in_flight_at_once_and_matched_by_transaction_id() {
    let (listener, address) = listener().await;
    let server = tokio::spawn(async move {
        let mut stream = accept(&listener).await;
        // The batch's three reads all arrive before any answer.
        all_then_last_first(&mut stream, 3).await;
        stream
    });
    let mut bus = pipeline(&address, Duration::from_secs(5)).await;
    let (mut a, mut b, mut c) = ([0u16], [0u16], [0u16]);
    let mut reads = [
        RegisterRead::new(Table::Holding, 0x10, &mut a),
        RegisterRead::new(Table::Holding, 0x11, &mut b),
        RegisterRead::new(Table::Holding, 0x12, &mut c),
    ];
    bus.read_register_batch(UNIT, &mut reads).await.unwrap();
    assert!(reads.iter().all(|read| read.done));
    assert_eq!(
        (a, b, c),
        ([value_of(0x10)], [value_of(0x11)], [value_of(0x12)])
    );
    assert_eq!(bus.in_flight(), 0);
    drop(server.await.unwrap());
}
