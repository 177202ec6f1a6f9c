//! Cancellation and bad transports under the async Modbus clients, against scripted servers on
//! 127.0.0.1: a dropped Modbus TCP request's late answer never answers the next request (its
//! transaction id is not the next one's), a dropped RTU request does not desynchronise the line
//! (its late answer is drained before the next request), a timeout racing an answer gives
//! either the answer or a timeout and leaves the next request answered right, and a connection
//! closed under a pending request gives `BusError::Closed`, not a hang.

use std::time::Duration;

use drivebus::asynch::TokioTimer;
use drivebus::modbus::async_client::tokio::connect;
use drivebus::modbus::async_client::{AsyncClient, AsyncClientConfig};
use drivebus::modbus::{rtu, AsyncRegisterBus, Table, UnitId};
use drivebus::BusError;
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::{TcpListener, TcpStream};
use tokio::time::{sleep, timeout};

const UNIT: UnitId = UnitId(1);

fn config(timeout: Duration) -> AsyncClientConfig {
    AsyncClientConfig {
        timeout,
        retry: drivebus::modbus::retry::RetryPolicy::reads(0),
        ..AsyncClientConfig::default()
    }
}

/// The next connection, without Nagle's delay: two small answers back to back must not wait
/// for the client's delayed acknowledgement (40 ms, longer than some tests' timeouts).
async fn accept(listener: &TcpListener) -> TcpStream {
    let (stream, _) = listener.accept().await.unwrap();
    stream.set_nodelay(true).unwrap();
    stream
}

async fn listener() -> (TcpListener, String) {
    let listener = TcpListener::bind("127.0.0.1:0").await.unwrap();
    let address = listener.local_addr().unwrap().to_string();
    (listener, address)
}

/// Reads one MBAP request (a read of holding registers): its transaction id.
async fn mbap_request(stream: &mut TcpStream) -> Option<[u8; 2]> {
    let mut adu = [0u8; 12];
    stream.read_exact(&mut adu).await.ok()?;
    Some([adu[0], adu[1]])
}

/// The MBAP answer with transaction id `tid` to a read of one register: `value`.
fn mbap_answer(tid: [u8; 2], value: u16) -> Vec<u8> {
    let [hi, lo] = value.to_be_bytes();
    vec![tid[0], tid[1], 0, 0, 0, 5, UNIT.0, 0x03, 2, hi, lo]
}

/// The RTU answer to a read of one register: `value`.
fn rtu_answer(value: u16) -> Vec<u8> {
    let [hi, lo] = value.to_be_bytes();
    let mut frame = vec![UNIT.0, 0x03, 2, hi, lo, 0, 0];
    let len = rtu::seal(&mut frame, 5).unwrap();
    frame.truncate(len);
    frame
}

async fn read_one<B: AsyncRegisterBus>(bus: &mut B) -> Result<u16, BusError> {
    let mut value = [0u16];
    bus.read_registers(UNIT, Table::Holding, 0x10, &mut value)
        .await
        .map(|()| value[0])
}

#[tokio::test]
async fn a_dropped_tcp_requests_late_answer_does_not_answer_the_next_request() {
    let (listener, address) = listener().await;
    let server = tokio::spawn(async move {
        let mut stream = accept(&listener).await;
        let first = mbap_request(&mut stream).await.unwrap();
        // Held back until the next request is in: then the stale answer comes first.
        let second = mbap_request(&mut stream).await.unwrap();
        assert_ne!(first, second, "each request has its own transaction id");
        stream.write_all(&mbap_answer(first, 111)).await.unwrap();
        stream.write_all(&mbap_answer(second, 222)).await.unwrap();
        stream
    });
    let cfg = config(Duration::from_secs(2));
    let mut client = AsyncClient::tcp(connect(&address, &cfg).await.unwrap(), TokioTimer, cfg);
    let dropped = timeout(Duration::from_millis(50), read_one(&mut client)).await;
    assert!(dropped.is_err(), "the first request is dropped unanswered");
    assert_eq!(read_one(&mut client).await, Ok(222));
    drop(server.await.unwrap());
}

#[tokio::test]
async fn a_dropped_rtu_request_does_not_desynchronise_the_line() {
    let (listener, address) = listener().await;
    let server = tokio::spawn(async move {
        let mut stream = accept(&listener).await;
        let mut request = [0u8; 8];
        stream.read_exact(&mut request).await.unwrap();
        // The slow device answers after the client gave up on it.
        sleep(Duration::from_millis(60)).await;
        stream.write_all(&rtu_answer(111)).await.unwrap();
        stream.read_exact(&mut request).await.unwrap();
        stream.write_all(&rtu_answer(222)).await.unwrap();
        stream
    });
    let cfg = config(Duration::from_millis(150));
    let mut client = AsyncClient::rtu(connect(&address, &cfg).await.unwrap(), TokioTimer, cfg);
    let dropped = timeout(Duration::from_millis(20), read_one(&mut client)).await;
    assert!(dropped.is_err(), "the first request is dropped unanswered");
    // Same unit, same shape: without resynchronisation the late 111 would pass for its answer.
    assert_eq!(read_one(&mut client).await, Ok(222));
    drop(server.await.unwrap());
}

#[tokio::test]
async fn a_timeout_racing_an_answer_gives_the_answer_or_timeout_and_the_next_request_its_own() {
    let limit = Duration::from_millis(30);
    let (listener, address) = listener().await;
    let server = tokio::spawn(async move {
        let mut stream = accept(&listener).await;
        let mut value = 0u16;
        while let Some(tid) = mbap_request(&mut stream).await {
            value += 1;
            // Every other answer comes right at the client's timeout.
            if value % 2 == 1 {
                sleep(limit).await;
            }
            if stream.write_all(&mbap_answer(tid, value)).await.is_err() {
                break;
            }
        }
    });
    let cfg = config(limit);
    let mut client = AsyncClient::tcp(connect(&address, &cfg).await.unwrap(), TokioTimer, cfg);
    for round in 0..10u16 {
        match read_one(&mut client).await {
            Ok(value) => assert_eq!(value, 2 * round + 1, "the raced answer is the request's"),
            // A timeout; reported as the stale frame seen meanwhile (an earlier raced answer,
            // skipped by its transaction id) when there was one, as the blocking client does.
            Err(error) => assert!(
                error == BusError::Timeout
                    || error == BusError::Frame("transaction id does not match the request"),
                "{error:?}"
            ),
        }
        assert_eq!(read_one(&mut client).await, Ok(2 * round + 2));
    }
    drop(client);
    server.await.unwrap();
}

#[tokio::test]
async fn a_connection_closed_under_a_pending_request_is_a_typed_error_not_a_hang() {
    let (listener, address) = listener().await;
    let server = tokio::spawn(async move {
        let mut stream = accept(&listener).await;
        mbap_request(&mut stream).await.unwrap();
        // Closed without an answer.
    });
    let cfg = config(Duration::from_secs(5));
    let mut client = AsyncClient::tcp(connect(&address, &cfg).await.unwrap(), TokioTimer, cfg);
    let outcome = timeout(Duration::from_secs(1), read_one(&mut client)).await;
    assert_eq!(
        outcome,
        Ok(Err(BusError::Closed)),
        "well before the 5 s timeout"
    );
    server.await.unwrap();
}

#[tokio::test]
async fn a_batch_is_in_flight_at_once_and_answers_are_matched_by_transaction_id() {
    let (listener, address) = listener().await;
    let server = tokio::spawn(async move {
        let mut stream = accept(&listener).await;
        // Both requests must be in before either is answered: a client waiting for the first
        // answer would time out here.
        let first = mbap_request(&mut stream).await.unwrap();
        let second = mbap_request(&mut stream).await.unwrap();
        stream.write_all(&mbap_answer(second, 222)).await.unwrap();
        stream.write_all(&mbap_answer(first, 111)).await.unwrap();
        stream
    });
    let cfg = AsyncClientConfig {
        max_in_flight: 2,
        ..config(Duration::from_secs(2))
    };
    let mut client = AsyncClient::tcp(connect(&address, &cfg).await.unwrap(), TokioTimer, cfg);
    let (mut a, mut b) = ([0u16], [0u16]);
    let mut reads = [
        drivebus::modbus::RegisterRead::new(Table::Holding, 0x10, &mut a),
        drivebus::modbus::RegisterRead::new(Table::Holding, 0x20, &mut b),
    ];
    let outcome = timeout(
        Duration::from_secs(1),
        client.read_register_batch(UNIT, &mut reads),
    )
    .await;
    assert_eq!(outcome, Ok(Ok(())), "well before the 2 s timeout");
    assert!(reads.iter().all(|read| read.done));
    assert_eq!(
        (a, b),
        ([111], [222]),
        "answers in reverse order, each to its request"
    );
    drop(server.await.unwrap());
}
