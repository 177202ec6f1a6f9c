//! Fault injection: a simulated device behind a [`ByteStream`] that corrupts, truncates, delays,
//! duplicates, drops and re-orders its answers. Every case must end in the correct value or a
//! typed error — never a panic, never a wrong value — and the next clean exchange must succeed.
#![cfg(feature = "modbus")]

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use drivebus::modbus::pdu::{
    decode_request, encode_exception, encode_registers_response, encode_write_response,
    ServerRequest, MAX_PDU,
};
use drivebus::modbus::retry::{Idempotency, RetryPolicy};
use drivebus::modbus::rtu::{self, RtuFraming};
use drivebus::modbus::tcp::{self as mbap, Header, TcpFraming};
use drivebus::modbus::transport::{ByteStream, Client, ClientConfig};
use drivebus::modbus::{RegisterBus, Table, UnitId};
use drivebus::BusError;
use proptest::prelude::*;

const UNIT: UnitId = UnitId(1);
const TIMEOUT: Duration = Duration::from_millis(40);

/// What happens to the answer of one request.
#[derive(Debug, Clone, PartialEq)]
enum Fault {
    /// Delivered intact.
    None,
    /// Byte `at` (modulo the length) XOR `mask` (non-zero).
    Corrupt { at: usize, mask: u8 },
    /// Only the first `keep` bytes arrive.
    Truncate { keep: usize },
    /// Arrives after `by`.
    Delay { by: Duration },
    /// Arrives twice, back to back.
    Duplicate,
    /// Never arrives.
    Drop,
    /// Line noise arrives first.
    Garbage(Vec<u8>),
    /// The answer to the previous request arrives (again) first.
    StaleFirst,
    /// Arrives one byte at a time.
    Trickle,
    /// Comes from another unit.
    OtherUnit,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    Rtu,
    Tcp,
}

/// A device with 256 holding and input registers that answers through a fault plan.
struct FaultyDevice {
    kind: Kind,
    holding: [u16; 256],
    input: [u16; 256],
    faults: VecDeque<Fault>,
    /// Bytes in flight: when they arrive, and what they are.
    inbound: VecDeque<(Instant, Vec<u8>)>,
    previous_answer: Vec<u8>,
    writes_executed: usize,
    flushes: usize,
}

impl FaultyDevice {
    fn new(kind: Kind) -> Self {
        Self {
            kind,
            holding: core::array::from_fn(|a| 0x4000 + a as u16),
            input: core::array::from_fn(|a| 0x3000 + a as u16),
            faults: VecDeque::new(),
            inbound: VecDeque::new(),
            previous_answer: Vec::new(),
            writes_executed: 0,
            flushes: 0,
        }
    }

    /// Executes a request PDU and returns the answer PDU.
    fn serve(&mut self, pdu: &[u8]) -> Vec<u8> {
        let mut out = [0u8; MAX_PDU];
        let function = pdu.first().copied().unwrap_or(0);
        let len = match decode_request(pdu) {
            Ok(ServerRequest::Read {
                function: f @ (3 | 4),
                start,
                count,
            }) => {
                let table = if f == 3 { &self.holding } else { &self.input };
                match table.get(start as usize..start as usize + count as usize) {
                    Some(values) => encode_registers_response(f, values, &mut out),
                    None => encode_exception(f, 2, &mut out),
                }
            }
            Ok(ServerRequest::WriteSingleRegister { address, value }) => {
                match self.holding.get_mut(address as usize) {
                    Some(slot) => {
                        *slot = value;
                        self.writes_executed += 1;
                        encode_write_response(pdu, &mut out)
                    }
                    None => encode_exception(function, 2, &mut out),
                }
            }
            _ => encode_exception(function, 1, &mut out),
        }
        .unwrap();
        out[..len].to_vec()
    }

    fn frame(&self, unit: u8, transaction: u16, pdu: &[u8]) -> Vec<u8> {
        let mut out = [0u8; 300];
        match self.kind {
            Kind::Rtu => {
                out[0] = unit;
                out[1..=pdu.len()].copy_from_slice(pdu);
                let len = rtu::seal(&mut out, 1 + pdu.len()).unwrap();
                out[..len].to_vec()
            }
            Kind::Tcp => {
                let header = Header {
                    transaction,
                    unit: UnitId(unit),
                    pdu_len: pdu.len(),
                };
                header.write(&mut out).unwrap();
                out[mbap::HEADER_LEN..][..pdu.len()].copy_from_slice(pdu);
                out[..mbap::HEADER_LEN + pdu.len()].to_vec()
            }
        }
    }

    fn deliver(&mut self, bytes: Vec<u8>, delay: Duration) {
        self.inbound.push_back((Instant::now() + delay, bytes));
    }
}

impl ByteStream for FaultyDevice {
    fn send(&mut self, bytes: &[u8]) -> Result<(), BusError> {
        let (unit, transaction, pdu) = match self.kind {
            Kind::Rtu => (
                bytes[0],
                0,
                rtu::open_frame(UnitId(bytes[0]), bytes).unwrap().to_vec(),
            ),
            Kind::Tcp => {
                let header = Header::parse(bytes).unwrap();
                (
                    header.unit.0,
                    header.transaction,
                    bytes[mbap::HEADER_LEN..].to_vec(),
                )
            }
        };
        let answer_pdu = self.serve(&pdu);
        let answer = self.frame(unit, transaction, &answer_pdu);
        let fault = self.faults.pop_front().unwrap_or(Fault::None);
        let now = Duration::ZERO;
        match fault {
            Fault::None => self.deliver(answer.clone(), now),
            Fault::Corrupt { at, mask } => {
                let mut bad = answer.clone();
                let at = at % bad.len();
                bad[at] ^= mask;
                self.deliver(bad, now);
            }
            Fault::Truncate { keep } => self.deliver(answer[..keep % answer.len()].to_vec(), now),
            Fault::Delay { by } => self.deliver(answer.clone(), by),
            Fault::Duplicate => {
                self.deliver(answer.clone(), now);
                self.deliver(answer.clone(), now);
            }
            Fault::Drop => {}
            Fault::Garbage(noise) => {
                self.deliver(noise, now);
                self.deliver(answer.clone(), now);
            }
            Fault::StaleFirst => {
                self.deliver(self.previous_answer.clone(), now);
                self.deliver(answer.clone(), now);
            }
            Fault::Trickle => {
                for byte in &answer {
                    self.deliver(vec![*byte], now);
                }
            }
            Fault::OtherUnit => {
                let other = self.frame(unit.wrapping_add(1), transaction, &answer_pdu);
                self.deliver(other, now);
            }
        }
        self.previous_answer = answer;
        Ok(())
    }

    fn receive(&mut self, buf: &mut [u8], deadline: Instant) -> Result<usize, BusError> {
        loop {
            let now = Instant::now();
            match self.inbound.front_mut() {
                Some((at, bytes)) if *at <= now => {
                    let n = bytes.len().min(buf.len());
                    buf[..n].copy_from_slice(&bytes[..n]);
                    bytes.drain(..n);
                    if bytes.is_empty() {
                        self.inbound.pop_front();
                    }
                    return Ok(n);
                }
                Some((at, _)) if *at < deadline => std::thread::sleep(*at - now),
                _ if now >= deadline => return Ok(0),
                _ => std::thread::sleep(deadline - now),
            }
        }
    }

    fn discard_input(&mut self) -> Result<(), BusError> {
        self.flushes += 1;
        // What has arrived is dropped; what is still in flight arrives later, as on a real line.
        let now = Instant::now();
        self.inbound.retain(|(at, _)| *at > now);
        Ok(())
    }
}

fn config(retries: u8) -> ClientConfig {
    ClientConfig {
        timeout: TIMEOUT,
        retry: RetryPolicy::reads(retries),
        idle_gap: Duration::ZERO,
    }
}

/// A client of `kind` over a faulty device, as a boxed RegisterBus plus access to the device.
enum AnyClient {
    Rtu(Client<FaultyDevice, RtuFraming>),
    Tcp(Client<FaultyDevice, TcpFraming>),
}

impl AnyClient {
    fn new(kind: Kind, retries: u8) -> Self {
        let device = FaultyDevice::new(kind);
        match kind {
            Kind::Rtu => Self::Rtu(Client::new(device, RtuFraming, config(retries))),
            Kind::Tcp => Self::Tcp(Client::new(device, TcpFraming::default(), config(retries))),
        }
    }
    fn device(&mut self) -> &mut FaultyDevice {
        match self {
            Self::Rtu(c) => c.stream_mut(),
            Self::Tcp(c) => c.stream_mut(),
        }
    }
    fn bus(&mut self) -> &mut dyn RegisterBus {
        match self {
            Self::Rtu(c) => c,
            Self::Tcp(c) => c,
        }
    }
    fn read(&mut self, table: Table, start: u16, count: usize) -> Result<Vec<u16>, BusError> {
        let mut out = vec![0u16; count];
        self.bus().read_registers(UNIT, table, start, &mut out)?;
        Ok(out)
    }
}

fn expected(table: Table, start: u16, count: usize) -> Vec<u16> {
    let base = if table == Table::Holding {
        0x4000
    } else {
        0x3000
    };
    (0..count).map(|i| base + start + i as u16).collect()
}

fn typed(error: &BusError) -> bool {
    matches!(
        error,
        BusError::Timeout | BusError::Frame(_) | BusError::ModbusException { .. }
    )
}

fn any_fault(kind: Kind) -> impl Strategy<Value = Fault> {
    // MBAP carries no checksum (TCP has its own), so corrupting a TCP answer's data bytes cannot
    // be detected by any Modbus client; TCP corruption is limited to the header and PDU head.
    let corrupt_span: usize = if kind == Kind::Tcp { 9 } else { 300 };
    prop_oneof![
        Just(Fault::None),
        (0..corrupt_span, 1u8..=255).prop_map(|(at, mask)| Fault::Corrupt { at, mask }),
        (0usize..300).prop_map(|keep| Fault::Truncate { keep }),
        (0u64..80).prop_map(|ms| Fault::Delay {
            by: Duration::from_millis(ms)
        }),
        Just(Fault::Duplicate),
        Just(Fault::Drop),
        proptest::collection::vec(any::<u8>(), 1..40).prop_map(Fault::Garbage),
        Just(Fault::StaleFirst),
        Just(Fault::Trickle),
        Just(Fault::OtherUnit),
    ]
}

fn faulty_read_then_clean_read(
    kind: Kind,
    fault: Fault,
    start: u16,
    count: usize,
) -> Result<(), TestCaseError> {
    let mut client = AnyClient::new(kind, 0);
    // A different-shaped request first, so a stale answer is one to another request.
    prop_assert_eq!(
        client.read(Table::Input, 0, 1).unwrap(),
        expected(Table::Input, 0, 1)
    );
    client.device().faults.push_back(fault);
    match client.read(Table::Holding, start, count) {
        Ok(values) => prop_assert_eq!(values, expected(Table::Holding, start, count)),
        Err(error) => prop_assert!(typed(&error), "untyped error {:?}", error),
    }
    // Whatever happened, the next exchange is back in step.
    std::thread::sleep(Duration::from_millis(90));
    prop_assert_eq!(
        client.read(Table::Holding, start, count).unwrap(),
        expected(Table::Holding, start, count)
    );
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn rtu_faults_end_in_the_value_or_a_typed_error(fault in any_fault(Kind::Rtu), start in 0u16..200, count in 2usize..40) {
        faulty_read_then_clean_read(Kind::Rtu, fault, start, count)?;
    }

    #[test]
    fn tcp_faults_end_in_the_value_or_a_typed_error(fault in any_fault(Kind::Tcp), start in 0u16..200, count in 2usize..40) {
        faulty_read_then_clean_read(Kind::Tcp, fault, start, count)?;
    }
}

#[test]
fn each_fault_has_the_expected_outcome() {
    use BusError::{Frame, Timeout};
    let cases: Vec<(Fault, Result<(), BusError>)> = vec![
        (Fault::None, Ok(())),
        (
            Fault::Corrupt { at: 4, mask: 0x10 },
            Err(Frame("CRC mismatch")),
        ),
        (Fault::Truncate { keep: 5 }, Err(Timeout)),
        (
            Fault::Delay {
                by: Duration::from_millis(10),
            },
            Ok(()),
        ),
        (Fault::Delay { by: TIMEOUT * 3 }, Err(Timeout)),
        (Fault::Duplicate, Ok(())),
        (Fault::Drop, Err(Timeout)),
        (Fault::Garbage(vec![0x01, 0x03, 0xFF, 0x00, 0x01]), Ok(())),
        (Fault::StaleFirst, Ok(())),
        (Fault::Trickle, Ok(())),
        (Fault::OtherUnit, Err(Timeout)),
    ];
    for (fault, outcome) in cases {
        let mut client = AnyClient::new(Kind::Rtu, 0);
        client.read(Table::Input, 0, 1).unwrap();
        client.device().faults.push_back(fault.clone());
        let got = client
            .read(Table::Holding, 0x10, 4)
            .map(|v| assert_eq!(v, expected(Table::Holding, 0x10, 4)));
        assert_eq!(got, outcome, "{fault:?}");
    }
    // TCP: a foreign unit id is rejected explicitly.
    let mut client = AnyClient::new(Kind::Tcp, 0);
    client.device().faults.push_back(Fault::OtherUnit);
    assert_eq!(
        client.read(Table::Holding, 0, 2),
        Err(Frame("unit id does not match the request"))
    );
}

/// A duplicate of an answer must not answer the next, identical request once the value changed.
#[test]
fn duplicates_and_late_answers_are_not_taken_for_the_next_answer() {
    for kind in [Kind::Rtu, Kind::Tcp] {
        let mut client = AnyClient::new(kind, 0);
        client.device().faults.push_back(Fault::Duplicate);
        assert_eq!(client.read(Table::Holding, 5, 1).unwrap(), [0x4005]);
        client.device().holding[5] = 99;
        assert_eq!(client.read(Table::Holding, 5, 1).unwrap(), [99], "{kind:?}");
    }
    // TCP: an answer that arrives after its timeout is recognised as stale by its transaction id.
    let mut client = AnyClient::new(Kind::Tcp, 0);
    client.device().faults.push_back(Fault::Delay {
        by: TIMEOUT + Duration::from_millis(20),
    });
    assert_eq!(client.read(Table::Holding, 5, 1), Err(BusError::Timeout));
    client.device().holding[5] = 77;
    client.device().faults.push_back(Fault::Delay {
        by: Duration::from_millis(30),
    });
    assert_eq!(client.read(Table::Holding, 5, 1).unwrap(), [77]);
}

#[test]
fn stale_input_is_flushed_before_every_request_on_both_framings() {
    for kind in [Kind::Rtu, Kind::Tcp] {
        let mut client = AnyClient::new(kind, 0);
        for _ in 0..3 {
            client.read(Table::Holding, 5, 1).unwrap();
        }
        assert_eq!(client.device().flushes, 3, "{kind:?}");
    }
}

#[test]
fn reads_are_retried_and_writes_are_not_unless_declared_idempotent() {
    for kind in [Kind::Rtu, Kind::Tcp] {
        let mut client = AnyClient::new(kind, 2);
        client
            .device()
            .faults
            .extend([Fault::Drop, Fault::Corrupt { at: 1, mask: 0x80 }]);
        assert_eq!(
            client.read(Table::Input, 7, 3).unwrap(),
            expected(Table::Input, 7, 3)
        );

        client.device().faults.push_back(Fault::Drop);
        assert_eq!(
            client.bus().write_register(UNIT, 0x28, 2),
            Err(BusError::Timeout)
        );
        assert_eq!(
            client.device().writes_executed,
            1,
            "a non-idempotent write is sent once"
        );

        client.device().faults.push_back(Fault::Drop);
        let result = match &mut client {
            AnyClient::Rtu(c) => c.write_register_as(UNIT, 0x42, 1500, Idempotency::Idempotent),
            AnyClient::Tcp(c) => c.write_register_as(UNIT, 0x42, 1500, Idempotency::Idempotent),
        };
        assert_eq!(result, Ok(()));
        assert_eq!(
            client.device().writes_executed,
            3,
            "an idempotent write is repeated"
        );
        assert_eq!(client.device().holding[0x42], 1500);
    }
}

#[test]
fn broadcast_writes_do_not_wait_and_broadcast_reads_are_refused() {
    let mut client = Client::new(FaultyDevice::new(Kind::Rtu), RtuFraming, config(0));
    let started = Instant::now();
    assert_eq!(client.write_register(UnitId(0), 5, 9), Ok(()));
    assert!(
        started.elapsed() < TIMEOUT,
        "a broadcast has no answer to wait for"
    );
    assert_eq!(client.stream_mut().holding[5], 9);
    let mut out = [0u16; 1];
    assert!(matches!(
        client.read_registers(UnitId(0), Table::Holding, 5, &mut out),
        Err(BusError::Unsupported(_))
    ));
    // The (non-standard) answer the simulated device gave to the broadcast is not taken as the
    // answer to the next request.
    client.stream_mut().holding[5] = 10;
    client
        .read_registers(UNIT, Table::Holding, 5, &mut out)
        .unwrap();
    assert_eq!(out, [10]);
}

#[test]
fn requests_keep_the_idle_gap() {
    let gap = Duration::from_millis(25);
    let config = ClientConfig {
        idle_gap: gap,
        ..config(0)
    };
    let mut client = Client::new(FaultyDevice::new(Kind::Rtu), RtuFraming, config);
    let mut out = [0u16; 2];
    let started = Instant::now();
    client
        .read_registers(UNIT, Table::Input, 0, &mut out)
        .unwrap();
    client
        .read_registers(UNIT, Table::Input, 0, &mut out)
        .unwrap();
    // The second request waits `gap` after the first answer, which came after `started`.
    assert!(
        started.elapsed() >= gap,
        "t3.5 / turnaround must pass before the next request"
    );
}

/// A stream whose "device" answers every request with the same arbitrary bytes.
struct Noise {
    bytes: Vec<u8>,
    pending: Option<usize>,
}

impl ByteStream for Noise {
    fn send(&mut self, _: &[u8]) -> Result<(), BusError> {
        self.pending = Some(0);
        Ok(())
    }
    fn receive(&mut self, buf: &mut [u8], _deadline: Instant) -> Result<usize, BusError> {
        let Some(at) = self.pending else { return Ok(0) };
        let n = (self.bytes.len() - at).min(buf.len()).min(7);
        buf[..n].copy_from_slice(&self.bytes[at..at + n]);
        self.pending = (at + n < self.bytes.len()).then_some(at + n);
        Ok(n)
    }
    fn discard_input(&mut self) -> Result<(), BusError> {
        self.pending = None;
        Ok(())
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    #[test]
    fn arbitrary_answers_end_in_typed_errors(bytes in proptest::collection::vec(any::<u8>(), 0..700), tcp in any::<bool>()) {
        let stream = Noise { bytes, pending: None };
        let config = ClientConfig { timeout: Duration::ZERO, ..config(1) };
        let mut out = [0u16; 3];
        let result = if tcp {
            Client::new(stream, TcpFraming::default(), config).read_registers(UNIT, Table::Input, 0, &mut out)
        } else {
            Client::new(stream, RtuFraming, config).read_registers(UNIT, Table::Input, 0, &mut out)
        };
        // Noise forming a valid answer (CRC, unit, function, byte count, transaction) is beyond
        // proptest's reach; anything else must be refused with a typed error.
        prop_assert!(matches!(result, Err(ref e) if typed(e)), "{:?}", result);
    }
}
