//! Our CANopen master against python-canopen 2.4.1's LocalNode, relayed over candump stdio.
#![cfg(feature = "canopen")]

mod support;

use std::process::{Child, ChildStdin};
use std::time::{Duration, Instant};

use drivebus::canopen::can::candump::CandumpBus;
use drivebus::canopen::client::BlockingSdo;
use drivebus::canopen::emcy::{Emcy, ErrorRegister};
use drivebus::canopen::heartbeat::{HeartbeatConsumer, HeartbeatEvent};
use drivebus::canopen::nmt::{NmtCommand, NmtState, NodeEvent};
use drivebus::canopen::sdo::AbortCode;
use drivebus::canopen::{CanBus, CanOpenLink, NodeId, ObjectAddress, SdoBus};
use drivebus::link::Link;
use drivebus::BusError;
use support::{expect_frame, is_boot_up, spawn_peer, stop, NODE, STARTUP};

const NODE_ID: NodeId = NodeId(NODE);

/// A LocalNode in a python relay process; killed (by PID) when dropped.
struct Peer {
    child: Child,
    sdo: BlockingSdo<CandumpBus<ChildStdin>>,
}

impl Peer {
    fn start() -> Self {
        Self::start_with(|sdo| sdo)
    }

    /// Starts the peer; `configure` adjusts the SDO client.
    fn start_with(
        configure: impl FnOnce(
            BlockingSdo<CandumpBus<ChildStdin>>,
        ) -> BlockingSdo<CandumpBus<ChildStdin>>,
    ) -> Self {
        let eds = support::peers_dir().join("canopen_peer.eds");
        let mut child = spawn_peer(
            "canopen_relay.py",
            &[eds.display().to_string(), NODE.to_string()],
        );
        let bus = CandumpBus::from_child(&mut child).expect("piped stdio");
        let mut peer = Self {
            child,
            sdo: configure(BlockingSdo::new(bus).with_timeout(Duration::from_secs(2))),
        };
        if let Err(why) = expect_frame(&mut peer.sdo, STARTUP, "boot-up from the peer", is_boot_up)
        {
            let stderr = stop(&mut peer.child);
            panic!("python canopen relay did not start ({why}); run tests/peers/setup-canopen.sh\n{stderr}");
        }
        peer
    }

    /// The bus, including frames that arrived during SDO transfers.
    fn bus(&mut self) -> &mut BlockingSdo<CandumpBus<ChildStdin>> {
        &mut self.sdo
    }

    fn read(&mut self, index: u16, subindex: u8) -> Result<Vec<u8>, BusError> {
        let mut buf = [0u8; 256];
        let len = self.sdo.upload(NODE_ID, index, subindex, &mut buf)?;
        Ok(buf[..len].to_vec())
    }

    fn write(&mut self, index: u16, subindex: u8, data: &[u8]) -> Result<(), BusError> {
        self.sdo.download(NODE_ID, index, subindex, data)
    }
}

impl Drop for Peer {
    fn drop(&mut self) {
        stop(&mut self.child);
    }
}

fn abort(index: u16, subindex: u8, code: AbortCode) -> BusError {
    BusError::SdoAbort {
        index,
        subindex,
        code,
    }
}

#[test]
fn expedited_upload_of_each_integer_type() {
    let mut peer = Peer::start();
    assert_eq!(peer.read(0x2001, 0).unwrap(), [0x12]);
    assert_eq!(peer.read(0x2002, 0).unwrap(), 0x1234u16.to_le_bytes());
    assert_eq!(peer.read(0x2003, 0).unwrap(), 0x1234_5678u32.to_le_bytes());
    assert_eq!(peer.read(0x2004, 0).unwrap(), (-123_456i32).to_le_bytes());
    assert_eq!(peer.read(0x1018, 1).unwrap(), 0x0DD0u32.to_le_bytes());
}

#[test]
fn expedited_download_is_read_back() {
    let mut peer = Peer::start();
    peer.write(0x2003, 0, &0xDEAD_BEEFu32.to_le_bytes())
        .unwrap();
    peer.write(0x2001, 0, &[0xA5]).unwrap();
    peer.write(0x2004, 0, &(-7i32).to_le_bytes()).unwrap();
    assert_eq!(peer.read(0x2003, 0).unwrap(), 0xDEAD_BEEFu32.to_le_bytes());
    assert_eq!(peer.read(0x2001, 0).unwrap(), [0xA5]);
    assert_eq!(peer.read(0x2004, 0).unwrap(), (-7i32).to_le_bytes());
}

#[test]
fn segmented_upload_and_download_of_a_visible_string() {
    let mut peer = Peer::start();
    assert_eq!(
        peer.read(0x2005, 0).unwrap(),
        b"drivegen segmented transfer peer"
    );
    for len in [5usize, 7, 8, 14, 15, 100] {
        let text: Vec<u8> = (0..len).map(|i| b'a' + (i % 26) as u8).collect();
        peer.write(0x2005, 0, &text).unwrap();
        assert_eq!(peer.read(0x2005, 0).unwrap(), text, "{len} bytes");
    }
}

#[test]
fn block_upload_follows_the_peer_into_segmented_mode() {
    // LocalNode has no block upload and answers with a normal upload, as CiA 301 allows.
    let mut peer = Peer::start_with(|sdo| sdo.with_block_transfers(0, 16));
    assert_eq!(
        peer.read(0x2005, 0).unwrap(),
        b"drivegen segmented transfer peer"
    );
}

#[test]
fn abort_codes_arrive_typed() {
    let mut peer = Peer::start();
    assert_eq!(
        peer.read(0x3000, 0),
        Err(abort(0x3000, 0, AbortCode::ObjectDoesNotExist))
    );
    assert_eq!(
        peer.read(0x1018, 9),
        Err(abort(0x1018, 9, AbortCode::SubindexDoesNotExist))
    );
    assert_eq!(
        peer.write(0x2006, 0, &[0; 4]),
        Err(abort(0x2006, 0, AbortCode::ReadOnly))
    );
    assert_eq!(
        peer.read(0x2007, 0),
        Err(abort(0x2007, 0, AbortCode::WriteOnly))
    );
    assert_eq!(
        peer.write(0x2002, 0, &[0; 4]),
        Err(abort(0x2002, 0, AbortCode::LengthMismatch))
    );
    // The value written before a refusal is untouched, and the channel still works.
    assert_eq!(peer.read(0x2006, 0).unwrap(), 0xCAFE_F00Du32.to_le_bytes());
    peer.write(0x2007, 0, &[1, 2, 3, 4]).unwrap();
}

/// Feeds frames to `consumer` until it reports an event matching `want`.
fn wait_for(
    peer: &mut Peer,
    consumer: &mut HeartbeatConsumer,
    epoch: Instant,
    what: &str,
    want: impl Fn(&HeartbeatEvent) -> bool,
) {
    let deadline = Instant::now() + Duration::from_secs(10);
    while Instant::now() < deadline {
        let frame = peer.bus().recv(Duration::from_millis(20)).unwrap();
        let now = epoch.elapsed();
        let mut events = Vec::new();
        if let Some(frame) = frame {
            events.extend(consumer.handle(&frame, now));
        }
        while let Some(event) = consumer.poll(now) {
            events.push(event);
        }
        if events.iter().any(&want) {
            return;
        }
    }
    panic!("no {what} from the peer");
}

#[test]
fn nmt_commands_heartbeat_states_boot_up_and_timeout() {
    let mut peer = Peer::start();
    let epoch = Instant::now();
    let mut consumer = HeartbeatConsumer::new();
    consumer.monitor(NODE_ID, Duration::from_millis(400));
    peer.write(0x1017, 0, &50u16.to_le_bytes()).unwrap();
    let changed_to = |state: NmtState| move |e: &HeartbeatEvent| matches!(e, HeartbeatEvent::Node(NodeEvent::StateChanged { to, .. }) if *to == state);
    wait_for(
        &mut peer,
        &mut consumer,
        epoch,
        "pre-operational heartbeat",
        changed_to(NmtState::PreOperational),
    );

    peer.bus()
        .send(&NmtCommand::Start.frame(Some(NODE_ID)))
        .unwrap();
    wait_for(
        &mut peer,
        &mut consumer,
        epoch,
        "operational heartbeat",
        changed_to(NmtState::Operational),
    );
    peer.bus().send(&NmtCommand::Stop.frame(None)).unwrap();
    wait_for(
        &mut peer,
        &mut consumer,
        epoch,
        "stopped heartbeat",
        changed_to(NmtState::Stopped),
    );
    peer.bus()
        .send(&NmtCommand::ResetNode.frame(Some(NODE_ID)))
        .unwrap();
    wait_for(
        &mut peer,
        &mut consumer,
        epoch,
        "boot-up after reset",
        |e| *e == HeartbeatEvent::Node(NodeEvent::BootUp(NODE_ID)),
    );
    assert_eq!(
        consumer.states().state(NODE_ID),
        Some(NmtState::PreOperational)
    );

    // Heartbeat off: the consumer reports the silence once.
    peer.write(0x1017, 0, &0u16.to_le_bytes()).unwrap();
    wait_for(&mut peer, &mut consumer, epoch, "heartbeat timeout", |e| {
        *e == HeartbeatEvent::Timeout(NODE_ID)
    });
}

#[test]
fn emcy_is_decoded_with_generic_and_drive_tables() {
    let mut peer = Peer::start();
    peer.write(0x2000, 0, &0x8611u16.to_le_bytes()).unwrap();
    let frame = expect_frame(peer.bus(), Duration::from_secs(5), "EMCY", |f| {
        f.id() == 0x80 + u16::from(NODE)
    })
    .unwrap();
    let emcy = Emcy::decode(&frame).expect("an EMCY frame");
    assert_eq!(emcy.node, NODE_ID);
    assert_eq!(emcy.code, 0x8611);
    assert_eq!(emcy.register, ErrorRegister::GENERIC);
    assert_eq!(emcy.manufacturer, [1, 2, 3, 4, 5]);
    assert_eq!(emcy.meaning(&()), "following error");
    static DRIVE: [(u16, &str); 1] = [(0x8611, "following error window exceeded (drive table)")];
    assert_eq!(
        emcy.meaning(&DRIVE),
        "following error window exceeded (drive table)"
    );
}

#[test]
fn a_canopen_link_over_candump_reads_and_writes_like_a_generated_handle() {
    let mut peer = Peer::start();
    let mut link = CanOpenLink::new(&mut peer.sdo, NODE_ID);
    let address = ObjectAddress {
        index: 0x2002,
        subindex: 0,
        bytes: 2,
    };
    link.write(&address, &0xBEEFu16.to_le_bytes()).unwrap();
    let mut buf = [0u8; 2];
    assert_eq!(link.read(&address, &mut buf), Ok(2));
    assert_eq!(u16::from_le_bytes(buf), 0xBEEF);
    assert_eq!(link.wire_bytes(&address), 2);
}

#[test]
fn a_tpdo_configuration_plan_is_applied_to_the_peer() {
    use drivebus::canopen::pdo::{MappedObject, PdoConfig, PdoKind};
    let mut peer = Peer::start();
    assert_eq!(
        peer.read(0x1800, 1).unwrap(),
        0x185u32.to_le_bytes(),
        "EDS default $NODEID+0x180"
    );
    let entries = [
        MappedObject::new(0x2002, 0, 16),
        MappedObject::new(0x2004, 0, 32),
        MappedObject::new(0x2001, 0, 8),
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
    config.apply(&mut peer.sdo, NODE_ID).unwrap();
    assert_eq!(peer.read(0x1A00, 0).unwrap(), [3]);
    assert_eq!(peer.read(0x1A00, 2).unwrap(), 0x2004_0020u32.to_le_bytes());
    assert_eq!(peer.read(0x1800, 2).unwrap(), [1]);
    assert_eq!(peer.read(0x1800, 1).unwrap(), 0x185u32.to_le_bytes());
}
