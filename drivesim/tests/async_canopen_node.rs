//! The CANopen node against drivebus's async SDO client, over SLCAN on a TCP connection (the
//! node on the blocking SLCAN bus, the client on the tokio one): typed aborts, an async link,
//! and a dropped transfer that does not trip the next one.

use std::net::TcpListener;
use std::time::Duration;

use drivebus::asynch::{AsyncLink, TokioTimer};
use drivebus::canopen::async_client::AsyncSdo;
use drivebus::canopen::can::async_slcan::AsyncSlcanBus;
use drivebus::canopen::can::slcan::SlcanBus;
use drivebus::canopen::can::tokio_adapters::TokioIo;
use drivebus::canopen::{AsyncSdoBus, CanOpenLink, NodeId, ObjectAddress};
use drivebus::BusError;
use drivesim::canopen::{Node, NodeConfig};
use drivesim::Simulator;

const FIXTURE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/fixtures/enforcement.toml"
);

type Client = AsyncSdo<AsyncSlcanBus<TokioIo<tokio::net::TcpStream>>, TokioTimer>;

/// A node serving SLCAN on a loopback port, in a thread that ends when the client hangs up;
/// and an async SDO client connected to it.
async fn start(node: u8) -> Client {
    let sim = Simulator::load(FIXTURE).unwrap();
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let address = listener.local_addr().unwrap();
    std::thread::spawn(move || {
        let (stream, _) = listener.accept().unwrap();
        let mut bus = SlcanBus::tcp(stream).unwrap();
        let config = NodeConfig {
            node: NodeId(node),
            heartbeat: None,
        };
        let mut node = Node::new(sim.clone(), config, sim.variant());
        // Ends with an error once the client hung up; that is how a test ends.
        let _ = node.run(&mut bus);
    });
    let bus = AsyncSlcanBus::connect(address).await.unwrap();
    AsyncSdo::new(bus, TokioTimer).with_timeout(Duration::from_millis(300))
}

fn abort_code(result: Result<impl Sized, BusError>) -> u32 {
    match result {
        Err(BusError::SdoAbort { code, .. }) => code.code(),
        Err(other) => panic!("expected an abort, got {other:?}"),
        Ok(_) => panic!("expected an abort, got a value"),
    }
}

#[tokio::test]
async fn sdo_access_is_enforced_with_cia301_abort_codes() {
    let mut sdo = start(5).await;
    let mut buf = [0u8; 8];
    assert_eq!(sdo.upload(NodeId(5), 0x2000, 0, &mut buf).await, Ok(2));
    assert_eq!(buf[..2], 100i16.to_le_bytes());
    assert_eq!(
        abort_code(sdo.download(NodeId(5), 0x2001, 0, &[1, 0]).await),
        0x0601_0002,
        "read-only"
    );
    assert_eq!(
        abort_code(sdo.upload(NodeId(5), 0x2002, 0, &mut buf).await),
        0x0601_0001,
        "write-only"
    );
    assert_eq!(
        abort_code(
            sdo.download(NodeId(5), 0x2000, 0, &3001i16.to_le_bytes())
                .await
        ),
        0x0609_0031,
        "above the maximum"
    );
}

#[tokio::test]
async fn an_async_link_writes_and_reads_back() {
    let sdo = start(5).await;
    let mut link = CanOpenLink::new(sdo, NodeId(5));
    let setpoint = ObjectAddress {
        index: 0x2000,
        subindex: 0,
        bytes: 2,
    };
    link.write(&setpoint, &(-5i16).to_le_bytes()).await.unwrap();
    let mut buf = [0u8; 2];
    assert_eq!(link.read(&setpoint, &mut buf).await, Ok(2));
    assert_eq!(i16::from_le_bytes(buf), -5);
}

#[tokio::test]
async fn a_dropped_upload_does_not_trip_the_next_request() {
    let mut sdo = start(5).await;
    let mut buf = [0u8; 8];
    // Node 6 is not there: the upload is dropped while it waits.
    let dropped = tokio::time::timeout(
        Duration::from_millis(50),
        sdo.upload(NodeId(6), 0x2000, 0, &mut buf),
    )
    .await;
    assert!(dropped.is_err());
    assert!(
        sdo.abort_pending(),
        "a TCP stream cannot send without waiting"
    );
    assert_eq!(sdo.upload(NodeId(5), 0x2000, 0, &mut buf).await, Ok(2));
    assert!(
        !sdo.abort_pending(),
        "the abort went out before the request"
    );
    assert_eq!(buf[..2], 100i16.to_le_bytes());
}
