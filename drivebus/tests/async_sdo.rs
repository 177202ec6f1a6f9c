//! The async SDO client on the async in-process bus against a scripted server: cancellation
//! (a dropped transfer is aborted), a closed bus, and timeouts racing answers.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::task::{Context, Poll, Waker};
use std::time::Duration;

use drivebus::asynch::{Alarm, AsyncLink, Timer, TokioTimer};
use drivebus::canopen::async_client::AsyncSdo;
use drivebus::canopen::can::async_in_process::{AsyncInProcessBus, AsyncInProcessEndpoint};
use drivebus::canopen::can::AsyncCanBus;
use drivebus::canopen::sdo::AbortCode;
use drivebus::canopen::{AsyncSdoBus, CanFrame, CanOpenLink, NodeId, ObjectAddress};
use drivebus::error::BusError;

const NODE: NodeId = NodeId(5);

/// What the scripted server received, in order.
type Seen = Arc<Mutex<Vec<CanFrame>>>;

/// The answer of the scripted server to a request, if any: 2000h:00 reads `value`, 2001h:00
/// never answers, downloads are confirmed.
fn answer(request: &CanFrame, value: u32) -> Option<CanFrame> {
    let data = request.padded();
    let mux = [data[1], data[2], data[3]];
    if request.id() != 0x605 || mux == [0x01, 0x20, 0x00] {
        return None;
    }
    let mut reply = [0u8; 8];
    reply[1..4].copy_from_slice(&mux);
    match data[0] >> 5 {
        2 => {
            reply[0] = 0x43;
            reply[4..].copy_from_slice(&value.to_le_bytes());
        }
        1 => reply[0] = 0x60,
        _ => return None,
    }
    Some(CanFrame::new(0x585, &reply).unwrap())
}

/// Runs the scripted server on `endpoint` until the bus closes; `value` is what 2000h:00 reads.
fn serve(mut endpoint: AsyncInProcessEndpoint, value: Arc<Mutex<u32>>) -> Seen {
    let seen = Seen::default();
    let record = Arc::clone(&seen);
    tokio::spawn(async move {
        while let Ok(request) = endpoint.recv().await {
            record.lock().unwrap().push(request);
            let value = *value.lock().unwrap();
            if let Some(reply) = answer(&request, value) {
                if endpoint.send(&reply).await.is_err() {
                    return;
                }
            }
        }
    });
    seen
}

fn object(index: u16) -> ObjectAddress {
    ObjectAddress {
        index,
        subindex: 0,
        bytes: 4,
    }
}

fn abort_of(index: u16, code: AbortCode) -> CanFrame {
    let [lo, hi] = index.to_le_bytes();
    let [a, b, c, d] = code.code().to_le_bytes();
    CanFrame::new(0x605, &[0x80, lo, hi, 0, a, b, c, d]).unwrap()
}

fn timeout() -> Duration {
    Duration::from_millis(300)
}

#[tokio::test]
async fn reads_and_writes_through_an_async_canopen_link() {
    let bus = AsyncInProcessBus::new();
    let seen = serve(bus.endpoint(), Arc::new(Mutex::new(1500)));
    let sdo = AsyncSdo::new(bus.endpoint(), TokioTimer).with_timeout(timeout());
    let mut link = CanOpenLink::new(sdo, NODE);
    let mut out = [0u8; 4];
    assert_eq!(link.read(&object(0x2000), &mut out).await, Ok(4));
    assert_eq!(u32::from_le_bytes(out), 1500);
    link.write(&object(0x2002), &[1, 2]).await.unwrap();
    assert_eq!(seen.lock().unwrap().len(), 2);
}

#[tokio::test]
async fn a_dropped_upload_is_aborted_at_once_and_the_next_request_succeeds() {
    let bus = AsyncInProcessBus::new();
    let seen = serve(bus.endpoint(), Arc::new(Mutex::new(7)));
    let mut sdo = AsyncSdo::new(bus.endpoint(), TokioTimer).with_timeout(timeout());
    let mut out = [0u8; 4];
    let dropped = tokio::time::timeout(
        Duration::from_millis(30),
        sdo.upload(NODE, 0x2001, 0, &mut out),
    );
    assert!(dropped.await.is_err(), "2001h is never answered");
    assert!(
        !sdo.abort_pending(),
        "the in-process bus sends without waiting"
    );
    tokio::task::yield_now().await;
    assert_eq!(
        seen.lock().unwrap().last(),
        Some(&abort_of(0x2001, AbortCode::GeneralError))
    );
    assert_eq!(sdo.upload(NODE, 0x2000, 0, &mut out).await, Ok(4));
    assert_eq!(out, 7u32.to_le_bytes());
}

/// A bus that can never send without waiting (as a byte stream cannot).
struct AwaitOnly(AsyncInProcessEndpoint);

impl AsyncCanBus for AwaitOnly {
    async fn send(&mut self, frame: &CanFrame) -> Result<(), BusError> {
        self.0.send(frame).await
    }
    async fn recv(&mut self) -> Result<CanFrame, BusError> {
        self.0.recv().await
    }
}

#[tokio::test]
async fn the_abort_of_a_dropped_transfer_goes_out_before_the_next_request() {
    let bus = AsyncInProcessBus::new();
    let seen = serve(bus.endpoint(), Arc::new(Mutex::new(7)));
    let mut sdo = AsyncSdo::new(AwaitOnly(bus.endpoint()), TokioTimer).with_timeout(timeout());
    let mut out = [0u8; 4];
    let dropped = tokio::time::timeout(
        Duration::from_millis(30),
        sdo.download(NODE, 0x2001, 0, &[1]),
    );
    assert!(dropped.await.is_err());
    assert!(sdo.abort_pending());
    assert_eq!(sdo.upload(NODE, 0x2000, 0, &mut out).await, Ok(4));
    let seen = seen.lock().unwrap();
    assert_eq!(seen.len(), 3, "{seen:?}");
    assert_eq!(seen[1], abort_of(0x2001, AbortCode::GeneralError));
    assert_eq!(seen[2].data()[..4], [0x40, 0x00, 0x20, 0x00]);
}

#[tokio::test]
async fn a_bus_closed_under_a_pending_transfer_fails_it_with_a_typed_error() {
    let bus = AsyncInProcessBus::new();
    let _seen = serve(bus.endpoint(), Arc::new(Mutex::new(7)));
    let mut sdo = AsyncSdo::new(bus.endpoint(), TokioTimer).with_timeout(Duration::from_secs(30));
    let closer = bus.clone();
    tokio::spawn(async move {
        tokio::time::sleep(Duration::from_millis(20)).await;
        closer.close();
    });
    let mut out = [0u8; 4];
    let outcome = tokio::time::timeout(
        Duration::from_secs(5),
        sdo.upload(NODE, 0x2001, 0, &mut out),
    )
    .await;
    assert_eq!(
        outcome,
        Ok(Err(BusError::Io(std::io::ErrorKind::BrokenPipe)))
    );
}

#[tokio::test]
async fn a_timeout_is_an_sdo_timeout_with_the_clients_abort_and_a_late_answer_is_not_taken() {
    let bus = AsyncInProcessBus::new();
    let value = Arc::new(Mutex::new(1));
    let seen = serve(bus.endpoint(), Arc::clone(&value));
    let mut late = bus.endpoint();
    let mut sdo = AsyncSdo::new(bus.endpoint(), TokioTimer).with_timeout(Duration::from_millis(30));
    let mut out = [0u8; 4];
    assert_eq!(
        sdo.upload(NODE, 0x2001, 0, &mut out).await,
        Err(BusError::Timeout)
    );
    tokio::task::yield_now().await;
    assert_eq!(
        seen.lock().unwrap().last(),
        Some(&abort_of(0x2001, AbortCode::ProtocolTimedOut))
    );
    // The answer to an earlier read of 2000h arrives late, before the next read of 2000h.
    late.send(&CanFrame::new(0x585, &[0x43, 0x00, 0x20, 0x00, 9, 9, 9, 9]).unwrap())
        .await
        .unwrap();
    *value.lock().unwrap() = 2;
    assert_eq!(sdo.upload(NODE, 0x2000, 0, &mut out).await, Ok(4));
    assert_eq!(out, 2u32.to_le_bytes(), "the stale answer was dropped");
}

/// A timer whose sleeps end when the test says so: every sleep started before
/// [`Manual::expire`] ends at once after it.
#[derive(Default, Clone)]
struct Manual {
    expired: Arc<AtomicBool>,
    wakers: Arc<Mutex<Vec<Waker>>>,
}

impl Manual {
    fn expire(&self) {
        self.expired.store(true, Ordering::SeqCst);
        for waker in self.wakers.lock().unwrap().drain(..) {
            waker.wake();
        }
    }
}

impl Timer for Manual {
    type Alarm = Manual;

    fn alarm(&self) -> Manual {
        self.clone()
    }

    async fn sleep(&self, _: Duration) {
        let mut alarm = self.clone();
        std::future::poll_fn(|cx| alarm.poll_due(cx)).await;
    }
}

/// The alarm of a manual timer is the timer itself: due once the test expires it.
impl Alarm for Manual {
    fn set(&mut self, _: Duration) {}

    fn poll_due(&mut self, cx: &mut Context<'_>) -> Poll<()> {
        if self.expired.load(Ordering::SeqCst) {
            return Poll::Ready(());
        }
        self.wakers.lock().unwrap().push(cx.waker().clone());
        Poll::Pending
    }
}

#[tokio::test]
async fn an_answer_that_arrives_with_the_timeout_wins() {
    let bus = AsyncInProcessBus::new();
    let mut server = bus.endpoint();
    let timer = Manual::default();
    let expire = timer.clone();
    // The server's answer and the end of the client's timeout come in the same instant.
    tokio::spawn(async move {
        let request = server.recv().await.unwrap();
        expire.expire();
        server.send(&answer(&request, 42).unwrap()).await.unwrap();
    });
    let mut sdo = AsyncSdo::new(bus.endpoint(), timer);
    let mut out = [0u8; 4];
    assert_eq!(sdo.upload(NODE, 0x2000, 0, &mut out).await, Ok(4));
    assert_eq!(out, 42u32.to_le_bytes());
}

#[tokio::test]
async fn a_link_moves_into_a_spawned_task() {
    let bus = AsyncInProcessBus::new();
    let _seen = serve(bus.endpoint(), Arc::new(Mutex::new(3)));
    let sdo = AsyncSdo::new(bus.endpoint(), TokioTimer).with_timeout(timeout());
    let mut link = CanOpenLink::new(sdo, NODE);
    // tokio::spawn needs the futures to be Send: the link's are, over a Send bus and timer.
    let read = tokio::spawn(async move {
        let mut out = [0u8; 4];
        link.read(&object(0x2000), &mut out).await.map(|_| out)
    });
    assert_eq!(read.await.unwrap(), Ok(3u32.to_le_bytes()));
}
