//! Our SLCAN backend against python-can's `slcan` interface over TCP, with a python-canopen
//! LocalNode behind it: python connects to our listener and speaks Lawicel ASCII.
#![cfg(feature = "canopen")]

mod support;

use std::net::{TcpListener, TcpStream};
use std::process::Child;
use std::time::{Duration, Instant};

use drivebus::canopen::can::slcan::{Bitrate, SlcanBus};
use drivebus::canopen::client::BlockingSdo;
use drivebus::canopen::sdo::AbortCode;
use drivebus::canopen::{NodeId, SdoBus};
use drivebus::BusError;
use support::{expect_frame, is_boot_up, spawn_peer, stop, NODE, STARTUP};

struct Peer {
    child: Child,
    sdo: BlockingSdo<SlcanBus<TcpStream>>,
}

impl Peer {
    fn start() -> Self {
        let listener = TcpListener::bind("127.0.0.1:0").expect("bind on loopback");
        let port = listener.local_addr().unwrap().port();
        let eds = support::peers_dir().join("canopen_peer.eds");
        let mut child = spawn_peer(
            "slcan_peer.py",
            &[
                eds.display().to_string(),
                NODE.to_string(),
                port.to_string(),
            ],
        );
        let stream = match accept(&listener, &mut child) {
            Ok(stream) => stream,
            Err(why) => {
                let stderr = stop(&mut child);
                panic!("python slcan peer did not connect ({why}); run tests/peers/setup-canopen.sh\n{stderr}");
            }
        };
        let mut bus = SlcanBus::tcp(stream).unwrap();
        bus.open(Bitrate::K500).unwrap();
        let mut sdo = BlockingSdo::new(bus).with_timeout(Duration::from_secs(2));
        if let Err(why) = expect_frame(&mut sdo, STARTUP, "boot-up over SLCAN", is_boot_up) {
            let stderr = stop(&mut child);
            panic!("python slcan peer did not boot ({why})\n{stderr}");
        }
        Self { child, sdo }
    }
}

/// Waits for python to connect, failing early if it exits.
fn accept(listener: &TcpListener, child: &mut Child) -> Result<TcpStream, String> {
    listener.set_nonblocking(true).map_err(|e| e.to_string())?;
    let deadline = Instant::now() + STARTUP;
    while Instant::now() < deadline {
        match listener.accept() {
            Ok((stream, _)) => {
                stream.set_nonblocking(false).map_err(|e| e.to_string())?;
                return Ok(stream);
            }
            Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => {}
            Err(e) => return Err(e.to_string()),
        }
        if let Ok(Some(status)) = child.try_wait() {
            return Err(format!("peer exited with {status}"));
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    Err(format!("no connection within {STARTUP:?}"))
}

impl Drop for Peer {
    fn drop(&mut self) {
        stop(&mut self.child);
    }
}

#[test]
fn sdo_transfers_and_aborts_over_slcan_tcp() {
    let mut peer = Peer::start();
    let node = NodeId(NODE);
    let mut buf = [0u8; 128];
    let len = peer.sdo.upload(node, 0x2003, 0, &mut buf).unwrap();
    assert_eq!(buf[..len], 0x1234_5678u32.to_le_bytes());
    let len = peer.sdo.upload(node, 0x2005, 0, &mut buf).unwrap();
    assert_eq!(&buf[..len], b"drivegen segmented transfer peer");

    peer.sdo
        .download(node, 0x2002, 0, &0x4321u16.to_le_bytes())
        .unwrap();
    let text = b"written over SLCAN in seven-byte segments";
    peer.sdo.download(node, 0x2005, 0, text).unwrap();
    let len = peer.sdo.upload(node, 0x2002, 0, &mut buf).unwrap();
    assert_eq!(buf[..len], 0x4321u16.to_le_bytes());
    let len = peer.sdo.upload(node, 0x2005, 0, &mut buf).unwrap();
    assert_eq!(&buf[..len], text);

    assert_eq!(
        peer.sdo.upload(node, 0x3000, 0, &mut buf),
        Err(BusError::SdoAbort {
            index: 0x3000,
            subindex: 0,
            code: AbortCode::ObjectDoesNotExist
        })
    );
}
