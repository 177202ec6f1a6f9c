//! The deliberate safety write against the in-crate SDO server on the in-process bus: the SWD
//! quick start's frames (line 4111) appear in order, the server ends with the configuration, the
//! signature BABDh and 13FEh = A5h; any NMT state but Pre-Operational, and any configuration that
//! cannot be written, is refused before a frame is sent.
#![cfg(feature = "canopen")]

use std::collections::BTreeMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::Duration;

use drivebus::canopen::can::in_process::{InProcessBus, InProcessEndpoint};
use drivebus::canopen::client::BlockingSdo;
use drivebus::canopen::nmt::NmtState;
use drivebus::canopen::pdo::MappedObject;
use drivebus::canopen::sdo::server::SdoServer;
use drivebus::canopen::srdo::{
    check_stored_signature, write_safety_configuration, MappingWrite, SafetyPlan, SafetyWriteError,
    SignatureMismatch, SrdoCommunication, SrdoConfig, SrdoDirection, SrdoError,
    StoredSignatureError, VerifyError,
};
use drivebus::canopen::{CanBus, CanFrame, NodeId, SdoBus};
use drivebus::BusError;

/// The quick start's node (line 4100).
const NODE: NodeId = NodeId(0x10);

const SRDO1_MAPPING: [MappedObject; 2] = [
    MappedObject::from_entry(0x6620_0108),
    MappedObject::from_entry(0x6622_0108),
];

/// SRDO1 on node 10h with the information direction the quick start writes (lines 1736-1746).
fn srdo1(direction: SrdoDirection) -> SrdoConfig<'static> {
    SrdoConfig {
        number: 1,
        communication: SrdoCommunication {
            direction,
            sct_ms: 50,
            srvt_ms: 20,
            transmission_type: 0xFE,
            cob_id_normal: 0x11F,
            cob_id_inverted: 0x120,
        },
        mapping: &SRDO1_MAPPING,
    }
}

type Dictionary = Arc<Mutex<BTreeMap<(u16, u8), Vec<u8>>>>;

/// The SWD's SRDO1 objects with their defaults (lines 1736-1746, 3574, 3588).
fn swd_objects() -> BTreeMap<(u16, u8), Vec<u8>> {
    BTreeMap::from([
        ((0x1301, 1), vec![2]),
        ((0x1301, 2), 50u16.to_le_bytes().to_vec()),
        ((0x1301, 3), 20u16.to_le_bytes().to_vec()),
        ((0x1301, 5), 0x11Fu32.to_le_bytes().to_vec()),
        ((0x1301, 6), 0x120u32.to_le_bytes().to_vec()),
        ((0x13FE, 0), vec![0xA5]),
        ((0x13FF, 1), 0x70ABu16.to_le_bytes().to_vec()),
    ])
}

/// A dictionary shared between the server thread and the test.
struct Shared(Dictionary);

impl drivebus::canopen::sdo::server::ObjectDictionary for Shared {
    fn read(
        &mut self,
        index: u16,
        subindex: u8,
    ) -> Result<Vec<u8>, drivebus::canopen::sdo::AbortCode> {
        self.0.lock().unwrap().read(index, subindex)
    }
    fn write(
        &mut self,
        index: u16,
        subindex: u8,
        data: &[u8],
    ) -> Result<(), drivebus::canopen::sdo::AbortCode> {
        self.0.lock().unwrap().write(index, subindex, data)
    }
}

/// The SDO server of node 10h on its own thread, stopped and joined on drop.
struct Server {
    stop: Arc<AtomicBool>,
    handle: Option<JoinHandle<()>>,
}

impl Server {
    fn spawn(bus: &InProcessBus, dictionary: Dictionary) -> Self {
        let mut server = SdoServer::new(NODE, Shared(dictionary));
        let mut endpoint = bus.endpoint();
        let stop = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&stop);
        let handle = std::thread::spawn(move || {
            while !flag.load(Ordering::Relaxed) {
                if let Ok(Some(frame)) = endpoint.recv(Duration::from_millis(5)) {
                    for response in server.handle(&frame) {
                        endpoint.send(&response).unwrap();
                    }
                }
            }
        });
        Self {
            stop,
            handle: Some(handle),
        }
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(handle) = self.handle.take() {
            let _ = handle.join();
        }
    }
}

fn drain(sniffer: &mut InProcessEndpoint) -> Vec<CanFrame> {
    std::iter::from_fn(|| sniffer.recv(Duration::from_millis(20)).unwrap()).collect()
}

fn frame(id: u16, data: [u8; 8]) -> CanFrame {
    CanFrame::new(id, &data).unwrap()
}

#[test]
fn quick_start_safety_write_in_pre_operational() {
    let bus = InProcessBus::new();
    let dictionary: Dictionary = Arc::new(Mutex::new(swd_objects()));
    let _server = Server::spawn(&bus, Arc::clone(&dictionary));
    let mut sniffer = bus.endpoint();
    let mut sdo = BlockingSdo::new(bus.endpoint()).with_timeout(Duration::from_millis(500));

    let written = write_safety_configuration(
        &mut sdo,
        NODE,
        NmtState::PreOperational,
        srdo1(SrdoDirection::Invalid),
        MappingWrite::Keep,
    );
    assert_eq!(written, Ok(0xBABD));

    // Line 4111: the three requests of the quick start, in this order, on 610h.
    let quick_start = [
        frame(0x610, [0x2F, 0x01, 0x13, 0x01, 0x00, 0x00, 0x00, 0x00]),
        frame(0x610, [0x2B, 0xFF, 0x13, 0x01, 0xBD, 0xBA, 0x00, 0x00]),
        frame(0x610, [0x2F, 0xFE, 0x13, 0x00, 0xA5, 0x00, 0x00, 0x00]),
    ];
    let requests: Vec<CanFrame> = drain(&mut sniffer)
        .into_iter()
        .filter(|f| f.id() == 0x610)
        .collect();
    let positions: Vec<usize> = quick_start
        .iter()
        .map(|q| {
            requests
                .iter()
                .position(|r| r == q)
                .expect("quick-start frame sent")
        })
        .collect();
    assert!(positions.windows(2).all(|w| w[0] < w[1]), "{positions:?}");
    assert_eq!(
        requests.last(),
        quick_start.last(),
        "validity is written last"
    );

    let objects = dictionary.lock().unwrap();
    assert_eq!(objects[&(0x1301, 1)], [0]);
    assert_eq!(objects[&(0x13FF, 1)], [0xBD, 0xBA]);
    assert_eq!(objects[&(0x13FE, 0)], [0xA5]);
}

/// An SDO bus that records what it is asked to send.
#[derive(Default)]
struct Recorder {
    downloads: Vec<(u16, u8, Vec<u8>)>,
    refuse: Option<(u16, u8)>,
}

impl SdoBus for Recorder {
    fn upload(&mut self, _: NodeId, _: u16, _: u8, _: &mut [u8]) -> Result<usize, BusError> {
        Err(BusError::Unsupported("the recorder does not upload"))
    }
    fn download(
        &mut self,
        _: NodeId,
        index: u16,
        subindex: u8,
        data: &[u8],
    ) -> Result<(), BusError> {
        if self.refuse == Some((index, subindex)) {
            return Err(BusError::SdoAbort {
                index,
                subindex,
                code: drivebus::canopen::sdo::AbortCode::from_u32(0x0601_0002),
            });
        }
        self.downloads.push((index, subindex, data.to_vec()));
        Ok(())
    }
}

#[test]
fn other_nmt_states_are_refused_before_any_frame() {
    for state in [
        NmtState::Operational,
        NmtState::Stopped,
        NmtState::Initializing,
    ] {
        let mut bus = Recorder::default();
        let result = write_safety_configuration(
            &mut bus,
            NODE,
            state,
            srdo1(SrdoDirection::Receive),
            MappingWrite::Keep,
        );
        assert_eq!(result, Err(SafetyWriteError::NotPreOperational { state }));
        assert!(bus.downloads.is_empty());
    }
}

#[test]
fn unwritable_configurations_are_refused_before_any_frame() {
    let mut late = srdo1(SrdoDirection::Receive);
    late.communication.srvt_ms = 50; // SRVT must be below SCT (line 1681)
    let mut unsigned = srdo1(SrdoDirection::Invalid);
    unsigned.communication.srvt_ms = 300;
    unsigned.communication.sct_ms = 1000;
    let mut unpaired = srdo1(SrdoDirection::Receive);
    unpaired.mapping = &SRDO1_MAPPING[..1];
    for config in [late, unsigned, unpaired] {
        let mut bus = Recorder::default();
        let result = write_safety_configuration(
            &mut bus,
            NODE,
            NmtState::PreOperational,
            config,
            MappingWrite::Keep,
        );
        assert!(matches!(
            result,
            Err(SafetyWriteError::Config(SrdoError::BadConfiguration(_)))
        ));
        assert!(bus.downloads.is_empty());
    }
}

#[test]
fn a_refused_write_leaves_the_configuration_unmarked() {
    let mut bus = Recorder {
        refuse: Some((0x13FF, 1)),
        ..Recorder::default()
    };
    let result = write_safety_configuration(
        &mut bus,
        NODE,
        NmtState::PreOperational,
        srdo1(SrdoDirection::Receive),
        MappingWrite::Keep,
    );
    assert!(matches!(
        result,
        Err(SafetyWriteError::Bus {
            index: 0x13FF,
            subindex: 1,
            ..
        })
    ));
    assert!(bus.downloads.iter().all(|(index, ..)| *index != 0x13FE));
}

#[test]
fn the_mapping_is_written_between_the_communication_object_and_the_signature() {
    let plan = SafetyPlan::new(srdo1(SrdoDirection::Receive), MappingWrite::Write).unwrap();
    assert_eq!(plan.signature(), 0x70AB);
    let order: Vec<(u16, u8, Vec<u8>)> = plan
        .map(|w| (w.index, w.subindex, w.data().to_vec()))
        .collect();
    assert_eq!(
        order,
        [
            (0x1301, 1, vec![2]),
            (0x1301, 2, vec![50, 0]),
            (0x1301, 3, vec![20, 0]),
            (0x1301, 5, vec![0x1F, 0x01, 0, 0]),
            (0x1301, 6, vec![0x20, 0x01, 0, 0]),
            (0x1381, 0, vec![0]),
            (0x1381, 1, vec![0x08, 0x01, 0x20, 0x66]),
            (0x1381, 2, vec![0x08, 0x01, 0x22, 0x66]),
            (0x1381, 0, vec![2]),
            (0x13FF, 1, vec![0xAB, 0x70]),
            (0x13FE, 0, vec![0xA5]),
        ]
    );
}

#[test]
fn a_stored_signature_mismatch_reports_both_values() {
    let bus = InProcessBus::new();
    let dictionary: Dictionary = Arc::new(Mutex::new(swd_objects()));
    let _server = Server::spawn(&bus, Arc::clone(&dictionary));
    let mut sdo = BlockingSdo::new(bus.endpoint()).with_timeout(Duration::from_millis(500));
    // The drive holds the default 70ABh (line 3588): right for SRDO1 as it is, wrong once
    // disabled (BABDh, line 4111).
    assert_eq!(
        check_stored_signature(&mut sdo, NODE, &srdo1(SrdoDirection::Receive)),
        Ok(())
    );
    assert_eq!(
        check_stored_signature(&mut sdo, NODE, &srdo1(SrdoDirection::Invalid)),
        Err(StoredSignatureError::Verify(VerifyError::Mismatch(
            SignatureMismatch {
                srdo: 1,
                computed: 0xBABD,
                stored: 0x70AB
            }
        )))
    );
}

/// The SWD's SRDO1 objects in memory, for the writes to land on.
#[cfg(feature = "async")]
fn swd_memory() -> drivebus::testing::MemoryBus {
    let mut memory = drivebus::testing::MemoryBus::new();
    for ((index, subindex), value) in swd_objects() {
        memory.set_object(index, subindex, &value);
    }
    for entry in 0..=2 {
        memory.set_object(0x1381, entry, &[0; 4]);
    }
    memory
}

#[cfg(feature = "async")]
#[test]
fn the_async_safety_write_checks_and_sends_what_the_blocking_one_does() {
    use drivebus::canopen::srdo::write_safety_configuration_async;
    use drivebus::testing::{now, Immediate};
    let config = srdo1(SrdoDirection::Receive);
    let mut blocking = swd_memory();
    let signature = write_safety_configuration(
        &mut blocking,
        NODE,
        NmtState::PreOperational,
        config,
        MappingWrite::Write,
    );
    let mut awaited = Immediate(swd_memory());
    let outcome = now(write_safety_configuration_async(
        &mut awaited,
        NODE,
        NmtState::PreOperational,
        config,
        MappingWrite::Write,
    ));
    assert_eq!(outcome, Some(signature));
    assert!(matches!(outcome, Some(Ok(_))), "{outcome:?}");
    assert_eq!(awaited.0.log(), blocking.log());
    // Refused before anything is sent outside Pre-Operational, as the blocking write is.
    let mut idle = Immediate(swd_memory());
    let refused = now(write_safety_configuration_async(
        &mut idle,
        NODE,
        NmtState::Operational,
        config,
        MappingWrite::Write,
    ));
    assert_eq!(
        refused,
        Some(Err(SafetyWriteError::NotPreOperational {
            state: NmtState::Operational
        }))
    );
    assert!(idle.0.log().is_empty());
}
