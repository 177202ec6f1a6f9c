//! The async SDO client against python-canopen 2.4.1's LocalNode, relayed over candump stdio
//! (the async candump bus on tokio's pipes): the transfers of `canopen_peer.rs`, and dropped
//! transfers that end with an abort the peer reports back.

mod support;

use std::time::Duration;

use drivebus::asynch::{within, AsyncLink, TokioTimer};
use drivebus::canopen::async_client::AsyncSdo;
use drivebus::canopen::can::async_candump::AsyncCandumpBus;
use drivebus::canopen::can::tokio_adapters::TokioIo;
use drivebus::canopen::can::AsyncCanBus;
use drivebus::canopen::sdo::AbortCode;
use drivebus::canopen::{AsyncSdoBus, CanFrame, CanOpenLink, NodeId, ObjectAddress};
use drivebus::BusError;
use support::{is_boot_up, spawn_peer, stop, NODE, STARTUP};
use tokio::process::{ChildStdin, ChildStdout};

const NODE_ID: NodeId = NodeId(NODE);
/// Where the abort relay reports the aborts its node received.
const ABORT_SEEN: u16 = 0x7E0;

type Candump = AsyncCandumpBus<TokioIo<ChildStdout>, TokioIo<ChildStdin>>;

/// A bus whose receiving stops (waits for ever) once `hold_after` frames were sent, until
/// released: a transfer held there is dropped at a known step.
struct Gate<B> {
    inner: B,
    sent: usize,
    hold_after: Option<usize>,
}

impl<B> Gate<B> {
    fn hold_after(&mut self, frames: usize) {
        self.sent = 0;
        self.hold_after = Some(frames);
    }

    fn release(&mut self) {
        self.hold_after = None;
    }
}

impl<B: AsyncCanBus> AsyncCanBus for Gate<B> {
    async fn send(&mut self, frame: &CanFrame) -> Result<(), BusError> {
        self.sent += 1;
        self.inner.send(frame).await
    }

    async fn recv(&mut self) -> Result<CanFrame, BusError> {
        if self.hold_after.is_some_and(|after| self.sent >= after) {
            std::future::pending::<()>().await;
        }
        self.inner.recv().await
    }
}

/// A LocalNode in a python relay process; killed (by PID) when dropped.
struct Peer {
    child: KillOnDrop,
    sdo: AsyncSdo<Gate<Candump>, TokioTimer>,
}

impl Peer {
    async fn start(script: &str) -> Self {
        let eds = support::peers_dir().join("canopen_peer.eds");
        let mut child = spawn_peer(script, &[eds.display().to_string(), NODE.to_string()]);
        let stdin = ChildStdin::from_std(child.stdin.take().unwrap()).unwrap();
        let stdout = ChildStdout::from_std(child.stdout.take().unwrap()).unwrap();
        let bus = Gate {
            inner: AsyncCandumpBus::new(TokioIo::new(stdout), TokioIo::new(stdin)),
            sent: 0,
            hold_after: None,
        };
        let mut peer = Self {
            child: KillOnDrop(child),
            sdo: AsyncSdo::new(bus, TokioTimer).with_timeout(Duration::from_secs(2)),
        };
        if let Err(why) = peer.expect(STARTUP, is_boot_up).await {
            let stderr = stop(&mut peer.child.0);
            panic!("python canopen relay did not start ({why}); run tests/peers/setup-canopen.sh\n{stderr}");
        }
        peer
    }

    /// Receives frames until one satisfies `want`.
    async fn expect(
        &mut self,
        limit: Duration,
        want: impl Fn(&CanFrame) -> bool,
    ) -> Result<CanFrame, String> {
        let sdo = &mut self.sdo;
        let wait = async {
            loop {
                match sdo.recv().await {
                    Ok(frame) if want(&frame) => return Ok(frame),
                    Ok(_) => {}
                    Err(e) => return Err(format!("bus failed: {e}")),
                }
            }
        };
        within(&TokioTimer, limit, wait)
            .await
            .unwrap_or_else(|_| Err(format!("nothing within {limit:?}")))
    }

    async fn read(&mut self, index: u16, subindex: u8) -> Result<Vec<u8>, BusError> {
        let mut buf = [0u8; 256];
        let len = self.sdo.upload(NODE_ID, index, subindex, &mut buf).await?;
        Ok(buf[..len].to_vec())
    }

    async fn write(&mut self, index: u16, subindex: u8, data: &[u8]) -> Result<(), BusError> {
        self.sdo.download(NODE_ID, index, subindex, data).await
    }

    /// Waits for the relay's report of the abort it received for `index`:00.
    async fn abort_seen(&mut self, index: u16, code: AbortCode) {
        let [lo, hi] = index.to_le_bytes();
        let [a, b, c, d] = code.code().to_le_bytes();
        let report = self
            .expect(Duration::from_secs(5), |frame| frame.id() == ABORT_SEEN)
            .await
            .expect("the peer reports the abort");
        assert_eq!(report.data(), [0x80, lo, hi, 0, a, b, c, d]);
    }
}

fn abort(index: u16, subindex: u8, code: AbortCode) -> BusError {
    BusError::SdoAbort {
        index,
        subindex,
        code,
    }
}

const GREETING: &[u8] = b"drivegen segmented transfer peer";

#[tokio::test]
async fn expedited_and_segmented_transfers_and_typed_aborts() {
    let mut peer = Peer::start("canopen_relay.py").await;
    assert_eq!(peer.read(0x2001, 0).await.unwrap(), [0x12]);
    assert_eq!(
        peer.read(0x2004, 0).await.unwrap(),
        (-123_456i32).to_le_bytes()
    );
    peer.write(0x2003, 0, &0xDEAD_BEEFu32.to_le_bytes())
        .await
        .unwrap();
    assert_eq!(
        peer.read(0x2003, 0).await.unwrap(),
        0xDEAD_BEEFu32.to_le_bytes()
    );
    assert_eq!(peer.read(0x2005, 0).await.unwrap(), GREETING);
    for len in [5usize, 7, 8, 14, 15, 100] {
        let text: Vec<u8> = (0..len).map(|i| b'a' + (i % 26) as u8).collect();
        peer.write(0x2005, 0, &text).await.unwrap();
        assert_eq!(peer.read(0x2005, 0).await.unwrap(), text, "{len} bytes");
    }
    assert_eq!(
        peer.read(0x3000, 0).await,
        Err(abort(0x3000, 0, AbortCode::ObjectDoesNotExist))
    );
    assert_eq!(
        peer.write(0x2006, 0, &[0; 4]).await,
        Err(abort(0x2006, 0, AbortCode::ReadOnly))
    );
}

#[tokio::test]
async fn block_upload_follows_the_peer_into_segmented_mode_through_an_async_link() {
    let peer = Peer::start("canopen_relay.py").await;
    let Peer { child: _child, sdo } = peer;
    let mut link = CanOpenLink::new(sdo.with_block_transfers(0, 16), NODE_ID);
    let mut buf = [0u8; 64];
    let address = ObjectAddress {
        index: 0x2005,
        subindex: 0,
        bytes: 0,
    };
    let len = link.read(&address, &mut buf).await.unwrap();
    assert_eq!(&buf[..len], GREETING);
}

struct KillOnDrop(std::process::Child);

impl Drop for KillOnDrop {
    fn drop(&mut self) {
        stop(&mut self.0);
    }
}

#[tokio::test]
async fn a_dropped_segmented_upload_ends_with_an_abort_the_peer_sees() {
    let mut peer = Peer::start("canopen_abort_relay.py").await;
    // Held after the first segment request: the transfer is in its segmented phase.
    peer.sdo.bus_mut().hold_after(2);
    let mut buf = [0u8; 64];
    let dropped = tokio::time::timeout(
        Duration::from_millis(300),
        peer.sdo.upload(NODE_ID, 0x2005, 0, &mut buf),
    )
    .await;
    assert!(dropped.is_err(), "the held upload cannot end");
    assert!(
        peer.sdo.abort_pending(),
        "a candump pipe cannot send without waiting"
    );
    peer.sdo.bus_mut().release();
    assert_eq!(peer.read(0x2001, 0).await.unwrap(), [0x12]);
    peer.abort_seen(0x2005, AbortCode::GeneralError).await;
    assert_eq!(peer.read(0x2005, 0).await.unwrap(), GREETING);
}

#[tokio::test]
async fn a_dropped_segmented_download_ends_with_an_abort_the_peer_sees() {
    let mut peer = Peer::start("canopen_abort_relay.py").await;
    peer.sdo.bus_mut().hold_after(2);
    let text = [b'x'; 40];
    let dropped = tokio::time::timeout(
        Duration::from_millis(300),
        peer.sdo.download(NODE_ID, 0x2005, 0, &text),
    )
    .await;
    assert!(dropped.is_err(), "the held download cannot end");
    peer.sdo.bus_mut().release();
    assert_eq!(peer.read(0x2001, 0).await.unwrap(), [0x12]);
    peer.abort_seen(0x2005, AbortCode::GeneralError).await;
    assert_eq!(
        peer.read(0x2005, 0).await.unwrap(),
        GREETING,
        "the aborted download wrote nothing"
    );
}

#[tokio::test]
async fn a_relay_that_exits_under_a_pending_transfer_is_a_typed_error() {
    let mut peer = Peer::start("canopen_relay.py").await;
    let pid = peer.child.0.id().to_string();
    // Node 9 is not on the bus: the upload waits for its 2 s timeout, and the relay exits
    // meanwhile.
    std::thread::spawn(move || {
        std::thread::sleep(Duration::from_millis(200));
        let _ = std::process::Command::new("kill").arg(pid).status();
    });
    let mut buf = [0u8; 8];
    let sdo = &mut peer.sdo;
    let outcome = tokio::time::timeout(
        Duration::from_secs(10),
        sdo.upload(NodeId(9), 0x1000, 0, &mut buf),
    )
    .await;
    assert_eq!(
        outcome,
        Ok(Err(BusError::Io(std::io::ErrorKind::UnexpectedEof))),
        "a closed relay is an I/O error, not a hang"
    );
}
