//! The blocking SDO client over the in-process bus against the in-crate SDO server, with faults
//! injected between them: lost frames, wrong toggle bits, unexpected commands, silence in the
//! middle of a transfer, and foreign traffic interleaved.
#![cfg(feature = "canopen")]

use std::collections::BTreeMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::Duration;

use drivebus::canopen::can::in_process::{InProcessBus, InProcessEndpoint};
use drivebus::canopen::client::BlockingSdo;
use drivebus::canopen::pdo::{MappedObject, PdoConfig, PdoKind};
use drivebus::canopen::sdo::server::SdoServer;
use drivebus::canopen::sdo::AbortCode;
use drivebus::canopen::{CanBus, CanFrame, CanOpenLink, NodeId, ObjectAddress, SdoBus};
use drivebus::link::Link;
use drivebus::BusError;

const NODE: NodeId = NodeId(5);
type Fault = Box<dyn FnMut(CanFrame) -> Vec<CanFrame> + Send>;

/// A thread running until dropped (then stopped and joined).
struct Background {
    stop: Arc<AtomicBool>,
    handle: Option<JoinHandle<()>>,
}

impl Background {
    fn spawn(mut step: impl FnMut() + Send + 'static) -> Self {
        let stop = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&stop);
        let handle = std::thread::spawn(move || {
            while !flag.load(Ordering::Relaxed) {
                step();
            }
        });
        Self {
            stop,
            handle: Some(handle),
        }
    }
}

impl Drop for Background {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(handle) = self.handle.take() {
            let _ = handle.join();
        }
    }
}

/// Serves `objects` for node 5, passing every response through `fault`.
fn server(bus: &InProcessBus, objects: &[((u16, u8), &[u8])], mut fault: Fault) -> Background {
    let dictionary: BTreeMap<(u16, u8), Vec<u8>> =
        objects.iter().map(|(k, v)| (*k, v.to_vec())).collect();
    let mut server = SdoServer::new(NODE, dictionary).with_block_size(8);
    let mut endpoint = bus.endpoint();
    Background::spawn(move || {
        if let Ok(Some(frame)) = endpoint.recv(Duration::from_millis(5)) {
            for response in server.handle(&frame) {
                for faulty in fault(response) {
                    endpoint.send(&faulty).unwrap();
                }
            }
        }
    })
}

fn clean() -> Fault {
    Box::new(|frame| vec![frame])
}

/// Foreign traffic: TPDOs and heartbeats of this node, SDO answers of another node, remote
/// frames on this node's SDO response id.
fn noise(bus: &InProcessBus) -> Background {
    let mut endpoint = bus.endpoint();
    let frames = [
        CanFrame::new(0x185, &[0x37, 0x02, 0x10, 0x27]).unwrap(),
        CanFrame::new(0x705, &[0x05]).unwrap(),
        CanFrame::new(0x586, &[0x43, 0x00, 0x22, 0x01, 9, 9, 9, 9]).unwrap(),
        CanFrame::new(0x586, &[0x00, 1, 2, 3, 4, 5, 6, 7]).unwrap(),
        CanFrame::remote(0x585, 8).unwrap(),
    ];
    let mut i = 0;
    Background::spawn(move || {
        endpoint.send(&frames[i % frames.len()]).unwrap();
        i += 1;
        std::thread::sleep(Duration::from_micros(200));
    })
}

fn client(bus: &InProcessBus) -> BlockingSdo<InProcessEndpoint> {
    BlockingSdo::new(bus.endpoint()).with_timeout(Duration::from_millis(500))
}

/// Every frame a bystander saw, for checking what the client put on the bus.
fn drain(sniffer: &mut InProcessEndpoint) -> Vec<CanFrame> {
    std::iter::from_fn(|| sniffer.recv(Duration::from_millis(20)).unwrap()).collect()
}

fn abort_frame(index: u16, subindex: u8, code: AbortCode) -> CanFrame {
    let [lo, hi] = index.to_le_bytes();
    let [a, b, c, d] = code.code().to_le_bytes();
    CanFrame::new(0x605, &[0x80, lo, hi, subindex, a, b, c, d]).unwrap()
}

#[test]
fn transfers_of_every_kind_survive_interleaved_foreign_frames() {
    let bus = InProcessBus::new();
    let _server = server(&bus, &[((0x2000, 0), &[]), ((0x2001, 0), &[])], clean());
    let _noise = noise(&bus);
    let value: Vec<u8> = (0..500u32).map(|i| (i * 7) as u8).collect();
    let mut buf = vec![0u8; 600];

    let mut plain = client(&bus);
    plain.download(NODE, 0x2000, 0, &value).unwrap();
    assert_eq!(plain.upload(NODE, 0x2000, 0, &mut buf), Ok(500));
    assert_eq!(buf[..500], value[..]);
    plain.download(NODE, 0x2001, 0, &[1, 2, 3]).unwrap();
    assert_eq!(plain.upload(NODE, 0x2001, 0, &mut buf), Ok(3));

    let mut block = client(&bus).with_block_transfers(1, 8);
    block.download(NODE, 0x2000, 0, &value[..333]).unwrap();
    assert_eq!(block.upload(NODE, 0x2000, 0, &mut buf), Ok(333));
    assert_eq!(buf[..333], value[..333]);

    // The foreign frames were kept for the application, not misread as SDO answers.
    let kept = std::iter::from_fn(|| plain.recv(Duration::ZERO).unwrap()).count();
    assert!(kept > 0);
}

#[test]
fn a_lost_segment_response_times_out_and_the_client_aborts_on_the_bus() {
    let bus = InProcessBus::new();
    let mut segments = 0;
    let _server = server(
        &bus,
        &[((0x2002, 0), &[7; 40])],
        Box::new(move |frame| {
            // The second upload segment is lost.
            if frame.data()[0] & 0xE0 == 0x00 {
                segments += 1;
                if segments == 2 {
                    return vec![];
                }
            }
            vec![frame]
        }),
    );
    let mut sniffer = bus.endpoint();
    let mut buf = [0u8; 64];
    assert_eq!(
        client(&bus).upload(NODE, 0x2002, 0, &mut buf),
        Err(BusError::Timeout)
    );
    assert_eq!(
        drain(&mut sniffer).last(),
        Some(&abort_frame(0x2002, 0, AbortCode::ProtocolTimedOut))
    );
}

#[test]
fn a_wrong_toggle_bit_is_detected_and_aborted() {
    let bus = InProcessBus::new();
    let _server = server(
        &bus,
        &[((0x2003, 0), b"a value of more than seven bytes")],
        Box::new(|frame| {
            let mut data = frame.padded();
            if data[0] & 0xE0 == 0x00 && frame.id() == 0x585 {
                data[0] ^= 0x10;
            }
            vec![CanFrame::new(frame.id(), &data[..frame.dlc() as usize]).unwrap()]
        }),
    );
    let mut sniffer = bus.endpoint();
    let mut buf = [0u8; 64];
    let code = AbortCode::ToggleBitNotAlternated;
    assert_eq!(
        client(&bus).upload(NODE, 0x2003, 0, &mut buf),
        Err(BusError::SdoClientAbort {
            index: 0x2003,
            subindex: 0,
            code
        })
    );
    assert!(drain(&mut sniffer).contains(&abort_frame(0x2003, 0, code)));
}

#[test]
fn an_unexpected_server_command_is_detected_and_aborted() {
    let bus = InProcessBus::new();
    let _server = server(
        &bus,
        &[((0x2004, 0), &[0; 4])],
        Box::new(|frame| {
            // Download segment acknowledgements come back as upload segments.
            let mut data = frame.padded();
            if data[0] & 0xE0 == 0x20 {
                data[0] &= 0x1F;
            }
            vec![CanFrame::new(frame.id(), &data).unwrap()]
        }),
    );
    let mut sniffer = bus.endpoint();
    let code = AbortCode::InvalidCommandSpecifier;
    assert_eq!(
        client(&bus).download(NODE, 0x2004, 0, &[9; 20]),
        Err(BusError::SdoClientAbort {
            index: 0x2004,
            subindex: 0,
            code
        })
    );
    assert!(drain(&mut sniffer).contains(&abort_frame(0x2004, 0, code)));
}

#[test]
fn a_lost_block_segment_is_repeated() {
    let bus = InProcessBus::new();
    let value: Vec<u8> = (0..200).collect();
    let mut dropped = false;
    let _server = server(
        &bus,
        &[((0x2005, 0), &value)],
        Box::new(move |frame| {
            if frame.data()[0] == 3 && !dropped {
                dropped = true;
                return vec![];
            }
            vec![frame]
        }),
    );
    let mut buf = [0u8; 256];
    let mut sdo = client(&bus).with_block_transfers(0, 8);
    assert_eq!(sdo.upload(NODE, 0x2005, 0, &mut buf), Ok(200));
    assert_eq!(buf[..200], value[..]);
}

#[test]
fn pdo_configuration_and_links_run_over_any_backend() {
    let bus = InProcessBus::new();
    let _server = server(
        &bus,
        &[
            ((0x1800, 1), &[0; 4]),
            ((0x1800, 2), &[0]),
            ((0x1A00, 0), &[0]),
            ((0x1A00, 1), &[0; 4]),
            ((0x1A00, 2), &[0; 4]),
            ((0x6041, 0), &[0x37, 0x02]),
        ],
        clean(),
    );
    let mut sdo = client(&bus);
    let entries = [
        MappedObject::new(0x6041, 0, 16),
        MappedObject::new(0x6064, 0, 32),
    ];
    let config = PdoConfig {
        kind: PdoKind::Transmit,
        number: 1,
        cob_id: 0x185,
        transmission_type: Some(1),
        inhibit_time: None,
        event_timer: None,
        entries: &entries,
    };
    config.apply(&mut sdo, NODE).unwrap();
    let mut buf = [0u8; 4];
    assert_eq!(sdo.upload(NODE, 0x1A00, 0, &mut buf), Ok(1));
    assert_eq!(buf[0], 2);
    assert_eq!(sdo.upload(NODE, 0x1800, 1, &mut buf), Ok(4));
    assert_eq!(u32::from_le_bytes(buf), 0x185);

    let mut link = CanOpenLink::new(sdo, NODE);
    let statusword = ObjectAddress {
        index: 0x6041,
        subindex: 0,
        bytes: 2,
    };
    let mut out = [0u8; 2];
    assert_eq!(link.read(&statusword, &mut out), Ok(2));
    assert_eq!(u16::from_le_bytes(out), 0x0237);
}
