//! Hostile clients: the simulator's Modbus TCP, RTU and SDO servers keep serving a well-behaved
//! client while another peer floods them with garbage, half-open connections and oversized
//! frames, and what they buffer stays bounded.

use std::collections::VecDeque;
use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use drivebus::canopen::can::in_process::InProcessBus;
use drivebus::canopen::client::BlockingSdo;
use drivebus::canopen::{CanBus, CanFrame, NodeId, SdoBus};
use drivebus::modbus::client::{ByteStream, ModbusTcpClient, TcpConfig};
use drivebus::modbus::rtu::seal;
use drivebus::modbus::{RegisterBus, Table, UnitId};
use drivebus::BusError;
use drivesim::canopen::{Node, NodeConfig};
use drivesim::modbus::tcp::MAX_CONNECTIONS;
use drivesim::Simulator;

const UNIT: UnitId = UnitId(1);
/// `setpoint` of the fixture: holding register 0x0010 and object 2000h:00, i16 in ±3000.
const SETPOINT: u16 = 0x0010;

fn simulator() -> Simulator {
    Simulator::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/enforcement.toml"
    ))
    .unwrap()
}

/// A thread repeating `attack` until stopped.
struct Attacker {
    stop: Arc<AtomicBool>,
    rounds: Arc<AtomicUsize>,
    thread: JoinHandle<()>,
}

impl Attacker {
    fn start(mut attack: impl FnMut(usize) + Send + 'static) -> Self {
        let stop = Arc::new(AtomicBool::new(false));
        let rounds = Arc::new(AtomicUsize::new(0));
        let (flag, count) = (Arc::clone(&stop), Arc::clone(&rounds));
        let thread = std::thread::spawn(move || {
            while !flag.load(Ordering::Relaxed) {
                attack(count.fetch_add(1, Ordering::Relaxed));
            }
        });
        Self {
            stop,
            rounds,
            thread,
        }
    }

    /// How many rounds it ran so far.
    fn rounds(&self) -> usize {
        self.rounds.load(Ordering::Relaxed)
    }

    /// Stops the attack; how many rounds it ran.
    fn stop(self) -> usize {
        self.stop.store(true, Ordering::Relaxed);
        let rounds = Arc::clone(&self.rounds);
        self.thread.join().unwrap();
        rounds.load(Ordering::Relaxed)
    }
}

/// One round of abuse of a Modbus TCP server; half-open connections are kept in `held`.
fn abuse_tcp(addr: SocketAddr, round: usize, held: &mut VecDeque<TcpStream>) {
    let Ok(mut stream) = TcpStream::connect(addr) else {
        return;
    };
    let _ = match round % 4 {
        // Garbage: a protocol id that is not 0.
        0 => stream.write_all(&[0x55; 1024]),
        // Oversized: an MBAP length of 65535, then more bytes than any ADU.
        1 => stream
            .write_all(&[0, 1, 0, 0, 0xFF, 0xFF, 1])
            .and_then(|()| stream.write_all(&[0x03; 4096])),
        // Half a header, then nothing.
        2 => stream.write_all(&[0, 1, 0]),
        // Nothing at all.
        _ => Ok(()),
    };
    held.push_back(stream);
    if held.len() > 4 * MAX_CONNECTIONS {
        held.pop_front();
    }
}

#[test]
fn the_tcp_server_keeps_serving_while_flooded() {
    let sim = simulator();
    let server = sim.serve_modbus_tcp("127.0.0.1:0", UNIT).unwrap();
    let addr = server.local_addr();
    let mut client = ModbusTcpClient::connect(addr, &TcpConfig::default()).unwrap();
    client.write_register(UNIT, SETPOINT, 1).unwrap();
    let mut held = VecDeque::new();
    let attacker = Attacker::start(move |round| abuse_tcp(addr, round, &mut held));
    let mut most_open = 0;
    let mut i = 0u16;
    while i < 300 || attacker.rounds() < 200 {
        i = i.wrapping_add(1) % 3000;
        client.write_register(UNIT, SETPOINT, i).unwrap();
        let mut value = [0u16];
        client
            .read_registers(UNIT, Table::Holding, SETPOINT, &mut value)
            .unwrap();
        assert_eq!(value[0], i);
        most_open = most_open.max(server.connections());
    }
    attacker.stop();
    assert!(most_open <= MAX_CONNECTIONS, "{most_open} connections open");
}

#[test]
fn half_open_connections_make_room_for_new_clients() {
    let sim = simulator();
    let server = sim.serve_modbus_tcp("127.0.0.1:0", UNIT).unwrap();
    let mut idle: Vec<TcpStream> = (0..MAX_CONNECTIONS)
        .map(|_| TcpStream::connect(server.local_addr()).unwrap())
        .collect();
    let mut client = ModbusTcpClient::connect(server.local_addr(), &TcpConfig::default()).unwrap();
    client.write_register(UNIT, SETPOINT, 7).unwrap();
    assert!(server.connections() <= MAX_CONNECTIONS);
    // The first idle connection made room: the server closed it.
    let first = &mut idle[0];
    first
        .set_read_timeout(Some(Duration::from_secs(5)))
        .unwrap();
    assert_eq!(first.read(&mut [0u8; 1]).unwrap(), 0);
}

/// A serial line: scripted input (noise and requests, with no silence between them), and the
/// answers the server sent.
struct Line {
    input: VecDeque<u8>,
    answers: Vec<Vec<u8>>,
    /// Whether the line has fallen silent after the script.
    silent: bool,
    /// Answers sent while the noise still ran.
    answered_in_noise: usize,
}

impl ByteStream for Line {
    fn send(&mut self, bytes: &[u8]) -> Result<(), BusError> {
        self.answered_in_noise += usize::from(!self.silent);
        self.answers.push(bytes.to_vec());
        Ok(())
    }
    fn receive(&mut self, buf: &mut [u8], _: Instant) -> Result<usize, BusError> {
        if self.input.is_empty() {
            // The script is over: the line falls silent once, then ends the server's loop.
            return match std::mem::take(&mut self.silent) {
                true => Err(BusError::Io(std::io::ErrorKind::UnexpectedEof)),
                false => {
                    self.silent = true;
                    Ok(0)
                }
            };
        }
        let n = buf.len().min(self.input.len()).min(64);
        for (slot, byte) in buf.iter_mut().zip(self.input.drain(..n)) {
            *slot = byte;
        }
        Ok(n)
    }
    fn discard_input(&mut self) -> Result<(), BusError> {
        Ok(())
    }
}

fn sealed(frame: &[u8]) -> Vec<u8> {
    let mut out = frame.to_vec();
    out.extend([0, 0]);
    seal(&mut out, frame.len()).unwrap();
    out
}

#[test]
fn the_rtu_server_answers_requests_between_floods_of_noise() {
    let sim = simulator();
    let read = sealed(&[1, 0x03, 0x00, 0x10, 0x00, 0x01]);
    // An oversized frame: a write of 255 bytes, longer than any ADU.
    let mut oversized = vec![1, 0x10, 0x00, 0x10, 0x00, 0x7F, 0xFF];
    oversized.resize(300, 0xAA);
    let mut input = VecDeque::new();
    for round in 0..20 {
        // 10 kB of a function code no length rule knows, never falling silent.
        input.extend([1u8, 0x2B]);
        input.extend(std::iter::repeat_n(0x55u8, 10_000));
        if round % 2 == 0 {
            input.extend(&oversized);
        }
        input.extend(&read);
    }
    let mut line = Line {
        input,
        answers: Vec::new(),
        silent: false,
        answered_in_noise: 0,
    };
    let end = drivesim::modbus::rtu::serve(&sim, &mut line, UNIT);
    assert_eq!(end, Err(BusError::Io(std::io::ErrorKind::UnexpectedEof)));
    let answer = sealed(&[1, 0x03, 0x02, 0x00, 100]);
    assert_eq!(
        line.answers,
        vec![answer; 20],
        "every read answered, nothing else"
    );
    // Noise that never falls silent holds back no more than an ADU: each read but the last
    // (which follows the last burst's tail) is answered before the line is quiet.
    assert_eq!(line.answered_in_noise, 19);
}

#[test]
fn the_sdo_server_keeps_serving_through_foreign_short_and_remote_frames() {
    let sim = simulator();
    let node = NodeId(5);
    let bus = InProcessBus::new();
    let (mut node_end, mut noise_end) = (bus.endpoint(), bus.endpoint());
    let mut sdo = BlockingSdo::new(bus.endpoint()).with_timeout(Duration::from_millis(500));
    let mut simulated = Node::new(
        sim.clone(),
        NodeConfig {
            node,
            heartbeat: None,
        },
        sim.variant(),
    );
    let stop = Arc::new(AtomicBool::new(false));
    let running = Arc::clone(&stop);
    let node_thread = std::thread::spawn(move || {
        simulated.run_while(&mut node_end, || !running.load(Ordering::Relaxed))
    });
    let attacker = Attacker::start(move |round| {
        let byte = round as u8;
        let frame = match round % 3 {
            0 => CanFrame::new(0x605, &[0x2B, 0x00, 0x20, 0x00, byte]).unwrap(),
            1 => CanFrame::remote(0x605, 8).unwrap(),
            _ => CanFrame::new(0x600 + u16::from(byte % 0x7F) + 6, &[byte; 8]).unwrap(),
        };
        let _ = noise_end.send(&frame);
        while let Ok(Some(_)) = noise_end.recv(Duration::ZERO) {}
        std::thread::sleep(Duration::from_micros(200));
    });
    let mut value = 0i16;
    while value < 200 || attacker.rounds() < 300 {
        value = (value + 1) % 3000;
        sdo.download(node, 0x2000, 0, &value.to_le_bytes()).unwrap();
        let mut out = [0u8; 2];
        assert_eq!(sdo.upload(node, 0x2000, 0, &mut out).unwrap(), 2);
        assert_eq!(i16::from_le_bytes(out), value);
        while let Ok(Some(_)) = sdo.recv(Duration::ZERO) {}
    }
    attacker.stop();
    stop.store(true, Ordering::Relaxed);
    node_thread.join().unwrap().unwrap();
}
