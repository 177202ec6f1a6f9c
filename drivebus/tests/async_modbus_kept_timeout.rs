//! The async Modbus client's answer timeout is one alarm kept from request to request and moved
//! at each (issue 30: cheaper than a timer per request). Each request still gets its whole
//! timeout from its own start, whether the last request was a moment ago, long ago (the kept
//! deadline has passed meanwhile) or had a longer timeout. On tokio's paused clock over an
//! in-memory stream, so the times are exact.

use std::time::Duration;

use drivebus::asynch::TokioTimer;
use drivebus::modbus::async_client::tokio::FromTokio;
use drivebus::modbus::async_client::{AsyncClientConfig, AsyncTcpClient};
use drivebus::modbus::{AsyncRegisterBus, Table, UnitId};
use drivebus::BusError;
use tokio::io::{AsyncReadExt, AsyncWriteExt, DuplexStream};
use tokio::sync::mpsc;
use tokio::time::{sleep, Instant};

const UNIT: UnitId = UnitId(1);
const TIMEOUT: Duration = Duration::from_millis(100);

type Client = AsyncTcpClient<FromTokio<DuplexStream>, TokioTimer>;

/// A client, and the channel telling its server how long to wait before each answer (`None`:
/// no answer).
fn client() -> (Client, mpsc::UnboundedSender<Option<Duration>>) {
    let (near, mut far) = tokio::io::duplex(256);
    let (delays, mut delay) = mpsc::unbounded_channel::<Option<Duration>>();
    tokio::spawn(async move {
        let mut adu = [0u8; 12];
        while far.read_exact(&mut adu).await.is_ok() {
            let Some(Some(wait)) = delay.recv().await else {
                continue;
            };
            sleep(wait).await;
            let answer = [adu[0], adu[1], 0, 0, 0, 5, UNIT.0, 0x03, 2, 0x12, 0x34];
            if far.write_all(&answer).await.is_err() {
                break;
            }
        }
    });
    let config = AsyncClientConfig {
        timeout: TIMEOUT,
        retry: drivebus::modbus::retry::RetryPolicy::reads(0),
        ..AsyncClientConfig::default()
    };
    (
        AsyncTcpClient::tcp(FromTokio::new(near), TokioTimer, config),
        delays,
    )
}

/// One read answered after `delay` (`None`: unanswered): its outcome and how long it took.
async fn read(
    client: &mut Client,
    delays: &mpsc::UnboundedSender<Option<Duration>>,
    delay: Option<Duration>,
) -> (Result<u16, BusError>, Duration) {
    delays.send(delay).unwrap();
    let start = Instant::now();
    let mut value = [0u16];
    let outcome = client
        .read_registers(UNIT, Table::Holding, 0x10, &mut value)
        .await;
    (outcome.map(|()| value[0]), start.elapsed())
}

const ALMOST: Option<Duration> = Some(Duration::from_millis(90));

#[tokio::test(start_paused = true)]
async fn a_request_soon_after_another_gets_its_whole_timeout() {
    let (mut client, delays) = client();
    assert_eq!(
        read(&mut client, &delays, Some(Duration::ZERO)).await.0,
        Ok(0x1234)
    );
    sleep(Duration::from_millis(60)).await;
    // Answered 150 ms after the first request started: past the first deadline, in time for
    // its own.
    assert_eq!(read(&mut client, &delays, ALMOST).await.0, Ok(0x1234));
}

#[tokio::test(start_paused = true)]
async fn a_request_long_after_another_gets_its_whole_timeout() {
    let (mut client, delays) = client();
    assert_eq!(
        read(&mut client, &delays, Some(Duration::ZERO)).await.0,
        Ok(0x1234)
    );
    // The kept deadline passes while the client is idle.
    sleep(Duration::from_secs(5)).await;
    assert_eq!(read(&mut client, &delays, ALMOST).await.0, Ok(0x1234));
    assert_eq!(read(&mut client, &delays, ALMOST).await.0, Ok(0x1234));
}

#[tokio::test(start_paused = true)]
async fn an_unanswered_request_times_out_after_its_own_timeout() {
    let (mut client, delays) = client();
    for _ in 0..3 {
        assert_eq!(read(&mut client, &delays, ALMOST).await.0, Ok(0x1234));
    }
    let (outcome, took) = read(&mut client, &delays, None).await;
    assert_eq!(outcome, Err(BusError::Timeout));
    assert!(
        took >= TIMEOUT && took < TIMEOUT + Duration::from_millis(5),
        "{took:?}"
    );
}

#[tokio::test(start_paused = true)]
async fn a_shorter_timeout_moves_the_kept_deadline_earlier() {
    let (mut client, delays) = client();
    let soon = Some(Duration::from_millis(20));
    assert_eq!(read(&mut client, &delays, soon).await.0, Ok(0x1234));
    let shorter = Duration::from_millis(10);
    client.config_mut().timeout = shorter;
    let (outcome, took) = read(&mut client, &delays, None).await;
    assert_eq!(outcome, Err(BusError::Timeout));
    assert!(
        took >= shorter && took < shorter + Duration::from_millis(5),
        "{took:?}"
    );
}
