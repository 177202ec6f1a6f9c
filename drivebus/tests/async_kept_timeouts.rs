//! Every async client keeps one alarm for its answer timeouts and moves it at each request
//! (issue 30: cheaper than a timer per request): the Modbus TCP pipeline (one per handle), the
//! Kinco RS-232 host, `AsyncSdo` and `AsyncNodeSdo` (the async Modbus client's own tests are
//! `async_modbus_kept_timeout.rs`). Each request still gets its whole timeout from its own
//! start, right after an answered request or long after; a timeout racing an answer gives the
//! answer or the timeout, and the next request its own answer; clones keep their own. On
//! tokio's paused clock over in-memory lines, so the times are exact.
//!
//! Each client's server answers a read of item `n` (a register address, an RS-232 or SDO
//! subindex) after `n` ms with the value `n`, and never answers [`UNANSWERED`].

use std::time::Duration;

use drivebus::asynch::TokioTimer;
use drivebus::canopen::async_client::AsyncSdo;
use drivebus::canopen::can::async_in_process::AsyncInProcessBus;
use drivebus::canopen::can::AsyncCanBus;
use drivebus::canopen::network::AsyncNetwork;
use drivebus::canopen::{AsyncSdoBus, CanFrame, NodeId};
use drivebus::modbus::async_client::tokio::FromTokio;
use drivebus::modbus::pipeline::TcpPipeline;
use drivebus::modbus::{AsyncRegisterBus, Table, UnitId};
use drivebus::rs232::async_client::AsyncRs232Client;
use drivebus::rs232::data::{Answer, Request, Value};
use drivebus::rs232::telegram::{self, Telegram, TELEGRAM_LEN};
use drivebus::rs232::{AsyncTelegramBus, LoopMode, Rs232Error, StationId};
use drivebus::BusError;
use tokio::io::{AsyncReadExt, AsyncWriteExt, DuplexStream, ReadHalf, WriteHalf};
use tokio::sync::mpsc::{self, UnboundedSender};
use tokio::time::{sleep, Instant};

const TIMEOUT: Duration = Duration::from_millis(100);
/// The item no server answers.
const UNANSWERED: u8 = 0xFF;
/// Answered just within the timeout.
const ALMOST: u8 = 90;
const UNIT: UnitId = UnitId(1);
const STATION: StationId = StationId(1);
const NODE: NodeId = NodeId(5);

/// A client under test.
trait Client {
    /// Reads item `n`, which the server answers after `n` ms with `n`.
    async fn read(&mut self, n: u8) -> Result<u8, BusError>;
    /// What a read of `n` that got no answer fails with.
    fn timed_out(n: u8) -> BusError;
}

/// Sends `answer` to `queue` after `delay` ms, beside whatever else is under way.
fn answer_later<A: Send + 'static>(queue: &UnboundedSender<A>, delay: u8, answer: A) {
    let queue = queue.clone();
    tokio::spawn(async move {
        sleep(Duration::from_millis(u64::from(delay))).await;
        let _ = queue.send(answer);
    });
}

// ---- the scenarios, one per test, run on every client ----

/// One read of `n`: its outcome and how long it took.
async fn timed(client: &mut impl Client, n: u8) -> (Result<u8, BusError>, Duration) {
    let start = Instant::now();
    (client.read(n).await, start.elapsed())
}

async fn a_request_right_after_an_answered_one_gets_its_whole_timeout<C: Client>(mut client: C) {
    assert_eq!(client.read(0).await, Ok(0));
    assert_eq!(client.read(20).await, Ok(20));
    // Answered 110 ms after the request before it started: past that one's deadline, in
    // time for its own.
    assert_eq!(client.read(ALMOST).await, Ok(ALMOST));
}

async fn a_request_long_after_another_gets_its_whole_timeout<C: Client>(mut client: C) {
    assert_eq!(client.read(0).await, Ok(0));
    // The kept deadline passes while the client is idle.
    sleep(Duration::from_secs(5)).await;
    assert_eq!(client.read(ALMOST).await, Ok(ALMOST));
    assert_eq!(client.read(ALMOST).await, Ok(ALMOST));
}

async fn an_unanswered_request_times_out_after_its_own_timeout<C: Client>(mut client: C) {
    for _ in 0..3 {
        assert_eq!(client.read(ALMOST).await, Ok(ALMOST));
    }
    let (outcome, took) = timed(&mut client, UNANSWERED).await;
    assert_eq!(outcome, Err(C::timed_out(UNANSWERED)));
    // The network's transfers take their deadlines from its own (real) clock: a little of
    // the timeout may pass in real time before the alarm is set.
    let tolerance = Duration::from_millis(5);
    assert!(
        took + tolerance >= TIMEOUT && took < TIMEOUT + tolerance,
        "{took:?}"
    );
    assert_eq!(client.read(1).await, Ok(1), "the client is usable after");
}

async fn a_timeout_racing_an_answer_gives_either_and_the_next_request_its_own<C: Client>(
    mut client: C,
) {
    let at_the_timeout = TIMEOUT.as_millis() as u8;
    for _ in 0..5 {
        match client.read(at_the_timeout).await {
            Ok(value) => assert_eq!(value, at_the_timeout, "the raced answer is the request's"),
            Err(error) => assert_eq!(error, C::timed_out(at_the_timeout)),
        }
        assert_eq!(client.read(3).await, Ok(3));
    }
}

/// Two clones, the second starting 50 ms after the first and answered 40 ms after the first's
/// deadline (or, one transfer per node, waiting for the first to end, then timed from there).
async fn clones_keep_their_own_timeouts<C: Client + Clone>(mut first: C) {
    let mut second = first.clone();
    let late = async {
        sleep(Duration::from_millis(50)).await;
        second.read(ALMOST).await
    };
    let (early, late) = tokio::join!(first.read(ALMOST), late);
    assert_eq!((early, late), (Ok(ALMOST), Ok(ALMOST)));
}

macro_rules! kept_timeout_tests {
    ($client:ident: $make:expr) => {
        mod $client {
            kept_timeout_tests!(@each $make;
                a_request_right_after_an_answered_one_gets_its_whole_timeout,
                a_request_long_after_another_gets_its_whole_timeout,
                an_unanswered_request_times_out_after_its_own_timeout,
                a_timeout_racing_an_answer_gives_either_and_the_next_request_its_own);
        }
    };
    (@each $make:expr; $($scenario:ident),*) => {$(
        #[tokio::test(start_paused = true)]
        async fn $scenario() {
            super::$scenario({
                use super::*;
                $make
            })
            .await;
        }
    )*};
}

kept_timeout_tests!(pipeline: pipeline());
kept_timeout_tests!(rs232: rs232_host());
kept_timeout_tests!(async_sdo: Sdo(own_bus_sdo()));
kept_timeout_tests!(node_sdo: Sdo(node_sdo()));

#[tokio::test(start_paused = true)]
async fn pipeline_clones_keep_their_own_timeouts() {
    clones_keep_their_own_timeouts(pipeline()).await;
}

#[tokio::test(start_paused = true)]
async fn node_handles_keep_their_own_timeouts() {
    clones_keep_their_own_timeouts(Sdo(node_sdo())).await;
}

// ---- the Modbus TCP pipeline ----

type Pipeline =
    TcpPipeline<FromTokio<ReadHalf<DuplexStream>>, FromTokio<WriteHalf<DuplexStream>>, TokioTimer>;

/// A pipeline to a server that answers each request on its own (several may wait at once).
fn pipeline() -> Pipeline {
    let (near, far) = tokio::io::duplex(1024);
    let (mut requests, mut answers) = tokio::io::split(far);
    let (queue, mut queued) = mpsc::unbounded_channel::<[u8; 11]>();
    tokio::spawn(async move {
        while let Some(answer) = queued.recv().await {
            if answers.write_all(&answer).await.is_err() {
                break;
            }
        }
    });
    tokio::spawn(async move {
        let mut adu = [0u8; 12];
        while requests.read_exact(&mut adu).await.is_ok() {
            let n = adu[9];
            if n != UNANSWERED {
                let answer = [adu[0], adu[1], 0, 0, 0, 5, UNIT.0, 0x03, 2, 0, n];
                answer_later(&queue, n, answer);
            }
        }
    });
    let (reader, writer) = tokio::io::split(near);
    let (reader, writer) = (FromTokio::new(reader), FromTokio::new(writer));
    TcpPipeline::new(reader, writer, TokioTimer, TIMEOUT)
}

impl Client for Pipeline {
    async fn read(&mut self, n: u8) -> Result<u8, BusError> {
        let mut value = [0u16];
        let address = u16::from(n);
        self.read_registers(UNIT, Table::Holding, address, &mut value)
            .await?;
        Ok(value[0] as u8)
    }

    fn timed_out(_: u8) -> BusError {
        BusError::Timeout
    }
}

// ---- the Kinco RS-232 host ----

type Rs232Host = AsyncRs232Client<FromTokio<DuplexStream>, TokioTimer>;

/// A host on a line to a drive that answers uploads of 2000h:`n`, one exchange at a time.
fn rs232_host() -> Rs232Host {
    let (near, mut far) = tokio::io::duplex(256);
    tokio::spawn(async move {
        let mut request: Telegram = [0; TELEGRAM_LEN];
        while far.read_exact(&mut request).await.is_ok() {
            let Ok((station, data)) = telegram::decode(&request) else {
                continue;
            };
            let Ok(Request::Upload(object)) = Request::decode(data) else {
                continue;
            };
            let n = object.subindex;
            if n == UNANSWERED {
                continue;
            }
            sleep(Duration::from_millis(u64::from(n))).await;
            let value = Value::new(&[n]).unwrap();
            let answer = telegram::encode(station, &Answer::Uploaded(object, value).encode());
            if far.write_all(&answer).await.is_err() {
                break;
            }
        }
    });
    AsyncRs232Client::new(FromTokio::new(near), TokioTimer, LoopMode::PointToPoint)
        .with_timeout(TIMEOUT)
}

impl Client for Rs232Host {
    async fn read(&mut self, n: u8) -> Result<u8, BusError> {
        let answer = self.exchange(STATION, &Request::upload(0x2000, n)).await?;
        Ok(answer.value().map_or(0, |bytes| bytes[0]))
    }

    fn timed_out(n: u8) -> BusError {
        BusError::Rs232Exchange {
            index: 0x2000,
            subindex: n,
            error: Rs232Error::Silence,
        }
    }
}

// ---- the SDO clients ----

/// An SDO client reading 2000h:`n` of [`NODE`].
#[derive(Clone)]
struct Sdo<S>(S);

impl<S: AsyncSdoBus> Client for Sdo<S> {
    async fn read(&mut self, n: u8) -> Result<u8, BusError> {
        let mut out = [0u8; 4];
        self.0.upload(NODE, 0x2000, n, &mut out).await?;
        Ok(out[0])
    }

    fn timed_out(_: u8) -> BusError {
        BusError::Timeout
    }
}

/// A bus with a server for [`NODE`] on it that answers uploads of 2000h:`n`.
fn served_bus() -> AsyncInProcessBus {
    let bus = AsyncInProcessBus::new();
    let (mut requests, mut answers) = (bus.endpoint(), bus.endpoint());
    let (queue, mut queued) = mpsc::unbounded_channel::<CanFrame>();
    tokio::spawn(async move {
        while let Some(answer) = queued.recv().await {
            if answers.send(&answer).await.is_err() {
                break;
            }
        }
    });
    tokio::spawn(async move {
        while let Ok(request) = requests.recv().await {
            let data = request.padded();
            let upload = data[0] >> 5 == 2;
            let n = data[3];
            if request.id() == 0x605 && upload && n != UNANSWERED {
                let reply = [0x43, data[1], data[2], n, n, 0, 0, 0];
                answer_later(&queue, n, CanFrame::new(0x585, &reply).unwrap());
            }
        }
    });
    bus
}

/// An `AsyncSdo` on its own endpoint of a served bus.
fn own_bus_sdo() -> AsyncSdo<impl AsyncCanBus, TokioTimer> {
    AsyncSdo::new(served_bus().endpoint(), TokioTimer).with_timeout(TIMEOUT)
}

/// An `AsyncNodeSdo` on a network over a served bus, its router spawned.
fn node_sdo() -> drivebus::canopen::network::AsyncNodeSdo<TokioTimer> {
    let (network, mut router) = AsyncNetwork::new(served_bus().endpoint(), TokioTimer);
    tokio::spawn(async move { router.run().await });
    network.node(NODE).with_timeout(TIMEOUT)
}
