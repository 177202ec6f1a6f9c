//! The async Modbus RTU client on a serial line: `AsyncRtuClient` over `TokioSerialStream`, on a
//! socat pty pair whose other end is the simulated Smartris (drivesim's RTU server, on the
//! blocking `SerialStream`, in a thread). One typed read and one typed write; a request dropped
//! before its answer arrived leaves the line resynchronised: the late answer, already on the
//! line when the next request starts, is drained instead of taken for that request's answer.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use drivebus::asynch::{within, TokioTimer};
use drivebus::modbus::async_client::{AsyncClientConfig, AsyncRtuClient};
use drivebus::modbus::UnitId;
use drivebus::stream::{ByteStream, SerialStream, TokioSerialStream};
use drivebus::units::{Rpm, Volts};
use drivebus::BusError;
use lafert_smartris::Smartris;

const UNIT: UnitId = UnitId(1);
const BAUD: u32 = 19_200;
/// How late the simulated drive answers: longer than the dropped request is given.
const LATE: Duration = Duration::from_millis(100);

/// A byte stream whose every answer goes out `LATE`, counting the answers.
struct Late {
    stream: SerialStream,
    answers: Arc<AtomicUsize>,
}

impl ByteStream for Late {
    fn send(&mut self, bytes: &[u8]) -> Result<(), BusError> {
        std::thread::sleep(LATE);
        // Counted before it goes out: the client cannot hold an answer not yet counted.
        self.answers.fetch_add(1, Ordering::SeqCst);
        self.stream.send(bytes)
    }

    fn receive(&mut self, buf: &mut [u8], deadline: Instant) -> Result<usize, BusError> {
        self.stream.receive(buf, deadline)
    }

    fn discard_input(&mut self) -> Result<(), BusError> {
        self.stream.discard_input()
    }
}

#[tokio::test]
async fn typed_read_and_write_on_a_serial_line_and_a_dropped_request_resynchronises_it() {
    let sim = drivesim::Simulator::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../descriptions/lafert-smartris"
    ))
    .unwrap();
    sim.preset("bus_dc_link", 4950).unwrap();
    sim.preset("full_scale_velocity", 3000).unwrap();
    let pty = peer_support::pty_pair();
    let answers = Arc::new(AtomicUsize::new(0));
    let line = SerialStream::open_8_bits(
        pty.server.to_str().unwrap(),
        BAUD,
        serialport::Parity::None,
        serialport::StopBits::One,
        Duration::from_millis(10),
    )
    .unwrap();
    let mut line = Late {
        stream: line,
        answers: Arc::clone(&answers),
    };
    let served = sim.clone();
    // Ends with an error when the pty pair goes away at the end of the test.
    std::thread::spawn(move || drivesim::modbus::rtu::serve(&served, &mut line, UNIT));

    let port = TokioSerialStream::open_8n1(pty.client.to_str().unwrap(), BAUD).unwrap();
    let config = AsyncClientConfig {
        timeout: Duration::from_millis(500),
        ..AsyncClientConfig::default()
    };
    let mut drive = Smartris::modbus_async(AsyncRtuClient::rtu(port, TokioTimer, config), UNIT);

    // One typed read, one typed write (its bound read first), read back.
    assert_eq!(drive.bus_dc_link().read().await, Ok(Volts(49.5)));
    drive.speed_setpoint().write(Rpm(1500.0)).await.unwrap();
    assert_eq!(drive.speed_setpoint().read().await, Ok(Rpm(1500.0)));
    assert_eq!(drive.modbus_address().read().await, Ok(1));

    // A read of the Modbus address (holding 0x0028, 1) dropped before its answer, which
    // arrives late.
    let before = answers.load(Ordering::SeqCst);
    let dropped = within(&TokioTimer, LATE / 4, drive.modbus_address().read_raw()).await;
    assert!(dropped.is_err(), "the answer came in time: {dropped:?}");
    let waited = tokio::time::timeout(Duration::from_secs(5), async {
        while answers.load(Ordering::SeqCst) == before {
            tokio::time::sleep(Duration::from_millis(5)).await;
        }
    });
    assert!(
        waited.await.is_ok(),
        "the dropped request never reached the drive"
    );
    // A read of the same shape (one holding register, holding 0x0003 = 3000): without
    // resynchronisation the late 1 would pass for its answer.
    assert_eq!(drive.full_scale_velocity().read_raw().await, Ok(3000));
    assert_eq!(drive.modbus_address().read().await, Ok(1));
}
