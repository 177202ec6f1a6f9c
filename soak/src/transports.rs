//! The three ways the soak reaches the simulator, each through the fault-injecting proxy:
//! Modbus TCP, Modbus RTU on pty pairs, and SDO over candump lines.

use std::any::Any;
use std::os::unix::net::UnixStream;
use std::sync::atomic::AtomicU64;
use std::sync::Arc;
use std::time::Duration;

use drivebus::canopen::can::candump::CandumpBus;
use drivebus::canopen::client::BlockingSdo;
use drivebus::canopen::NodeId;
use drivebus::modbus::client::{Client, NetStream, SerialConfig, SerialStream, TcpConfig};
use drivebus::modbus::rtu::RtuFraming;
use drivebus::modbus::tcp::TcpFraming;
use drivesim::canopen::{Node, NodeConfig};
use drivesim::Simulator;

use crate::endpoint::{CountingBus, CountingStream, Endpoint, ModbusEndpoint, SdoEndpoint, UNIT};
use crate::fault::{Fault, FaultCounts, FaultPlan};
use crate::proxy;

/// How long every client waits for an answer.
pub const TIMEOUT: Duration = Duration::from_millis(100);

/// The faults a line without transaction ids can produce. A half-duplex RTU line, and one SDO
/// channel with a single transfer at a time, cannot deliver a frame after a later one, and an
/// answer later than the client's timeout is, by these protocols' design, indistinguishable from
/// the answer to the next request of the same shape: delays stay within the timeout there.
const LINE_FAULTS: &[Fault] = &[
    Fault::Corrupt,
    Fault::Truncate,
    Fault::Duplicate,
    Fault::Delay,
    Fault::Drop,
];

/// The faults of an RTU line on requests: as [`LINE_FAULTS`], but not repeated. A line does not
/// repeat a master's request, and the second answer a repeated request draws would reach the
/// master after it moved on, where nothing tells it from the next answer of the same shape.
const RTU_REQUEST_FAULTS: &[Fault] = &[Fault::Corrupt, Fault::Truncate, Fault::Delay, Fault::Drop];

/// A transport the soak runs over.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Transport {
    /// Modbus TCP (MBAP) over loopback TCP.
    ModbusTcp,
    /// Modbus RTU over two socat pty pairs.
    ModbusRtu,
    /// CANopen SDO over candump text lines.
    SdoCandump,
}

/// What keeps a transport's servers and proxies alive.
pub type Guard = Box<dyn Any>;

/// A client connected through a fault-injecting proxy, and what keeps the rest alive.
pub type Connected = (Box<dyn Endpoint>, Guard);

impl Transport {
    /// Every transport, in run order.
    pub const ALL: [Transport; 3] = [
        Transport::ModbusTcp,
        Transport::ModbusRtu,
        Transport::SdoCandump,
    ];

    /// Its name on the command line and in the report.
    pub fn name(self) -> &'static str {
        match self {
            Transport::ModbusTcp => "modbus-tcp",
            Transport::ModbusRtu => "modbus-rtu",
            Transport::SdoCandump => "sdo-candump",
        }
    }

    /// The faults its proxy injects at `rate`.
    pub fn plan(self, rate: f64) -> FaultPlan {
        match self {
            // Answers name their request: any fault, and delays beyond the timeout.
            Transport::ModbusTcp => FaultPlan {
                rate,
                request_kinds: &Fault::ALL,
                response_kinds: &Fault::ALL,
                max_delay: TIMEOUT * 2,
            },
            Transport::ModbusRtu => FaultPlan {
                rate,
                request_kinds: RTU_REQUEST_FAULTS,
                response_kinds: LINE_FAULTS,
                max_delay: TIMEOUT / 2,
            },
            // CAN can repeat a frame either way (a receiver takes it, the sender sees an error in
            // the last bit of its end of frame and sends it again).
            Transport::SdoCandump => FaultPlan {
                rate,
                request_kinds: LINE_FAULTS,
                response_kinds: LINE_FAULTS,
                max_delay: TIMEOUT / 2,
            },
        }
    }

    /// Starts the simulator's server for `sim`, the proxy, and a client through it.
    pub fn connect(
        self,
        sim: &Simulator,
        plan: FaultPlan,
        seed: u64,
        counts: &'static FaultCounts,
    ) -> Result<Connected, String> {
        match self {
            Transport::ModbusTcp => modbus_tcp(sim, plan, seed, counts),
            Transport::ModbusRtu => modbus_rtu(sim, plan, seed, counts),
            Transport::SdoCandump => sdo_candump(sim, plan, seed, counts),
        }
        .map_err(|e| format!("{}: {e}", self.name()))
    }
}

fn modbus_tcp(
    sim: &Simulator,
    plan: FaultPlan,
    seed: u64,
    counts: &'static FaultCounts,
) -> Result<Connected, Box<dyn std::error::Error>> {
    let server = sim.serve_modbus_tcp("127.0.0.1:0", UNIT)?;
    let proxy = proxy::mbap::start(server.local_addr(), plan, seed, counts)?;
    let config = TcpConfig {
        timeout: TIMEOUT,
        ..TcpConfig::default()
    };
    let writes = Arc::new(AtomicU64::new(0));
    let stream = CountingStream::new(
        NetStream::connect(proxy, config.connect_timeout)?,
        7,
        Arc::clone(&writes),
    );
    let client = Client::new(stream, TcpFraming::default(), config.client_config());
    Ok((
        Box::new(ModbusEndpoint { client, writes }),
        Box::new(server),
    ))
}

fn modbus_rtu(
    sim: &Simulator,
    plan: FaultPlan,
    seed: u64,
    counts: &'static FaultCounts,
) -> Result<Connected, Box<dyn std::error::Error>> {
    let config = SerialConfig {
        timeout: TIMEOUT,
        ..SerialConfig::new(115_200)
    };
    let (client_line, server_line) = (peer_support::pty_pair(), peer_support::pty_pair());
    let mut server_end = SerialStream::open(path(&server_line.server)?, &config)?;
    let served = sim.clone();
    std::thread::spawn(move || drivesim::modbus::rtu::serve(&served, &mut server_end, UNIT));
    proxy::rtu::start(&client_line.server, &server_line.client, plan, seed, counts)?;
    let writes = Arc::new(AtomicU64::new(0));
    let stream = CountingStream::new(
        SerialStream::open(path(&client_line.client)?, &config)?,
        1,
        Arc::clone(&writes),
    );
    let client = Client::new(stream, RtuFraming, config.client_config());
    Ok((
        Box::new(ModbusEndpoint { client, writes }),
        Box::new((client_line, server_line)),
    ))
}

fn path(path: &std::path::Path) -> Result<&str, &'static str> {
    path.to_str().ok_or("pty path is not UTF-8")
}

fn sdo_candump(
    sim: &Simulator,
    plan: FaultPlan,
    seed: u64,
    counts: &'static FaultCounts,
) -> Result<Connected, Box<dyn std::error::Error>> {
    let node = NodeId::new(5).ok_or("node id")?;
    let (client_end, proxy_client_end) = UnixStream::pair()?;
    let (proxy_node_end, node_end) = UnixStream::pair()?;
    let mut node_bus = CandumpBus::new(node_end.try_clone()?, node_end);
    let mut simulated = Node::new(
        sim.clone(),
        NodeConfig {
            node,
            heartbeat: None,
        },
        sim.variant(),
    );
    std::thread::spawn(move || simulated.run(&mut node_bus));
    proxy::candump::start(proxy_client_end, proxy_node_end, plan, seed, counts)?;
    let writes = Arc::new(AtomicU64::new(0));
    let bus = CountingBus::new(
        CandumpBus::new(client_end.try_clone()?, client_end),
        Arc::clone(&writes),
    );
    let sdo = BlockingSdo::new(bus).with_timeout(TIMEOUT);
    Ok((Box::new(SdoEndpoint { sdo, node, writes }), Box::new(())))
}
