//! Hostile servers: the Modbus TCP client over a real socket, and the Modbus RTU client on a
//! socat pty pair, against a scripted server that answers slowly, partially, with the wrong
//! transaction id or unit, with an oversized or endless frame, or closes mid-frame. Each
//! misbehaviour ends in a typed error, and the next transaction works.
#![cfg(feature = "modbus")]

use std::io::{Read, Write};
use std::net::TcpListener;
use std::sync::mpsc;
use std::time::Duration;

use drivebus::modbus::client::{ModbusTcpClient, SerialConfig, SerialRtuClient, TcpConfig};
use drivebus::modbus::crc::crc16_modbus;
use drivebus::modbus::retry::RetryPolicy;
use drivebus::modbus::{RegisterBus, Table, UnitId};
use drivebus::BusError;
use peer_support::pty_pair;

const UNIT: UnitId = UnitId(1);
const TIMEOUT: Duration = Duration::from_millis(150);

/// How the server answers one request.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Answer {
    /// Correctly.
    Good,
    /// Correctly, after the client's timeout: twice it on RTU (the line then pauses), one and a
    /// half times it on TCP (see `tcp_server`).
    Slow,
    /// Correctly, after one and a half times the client's timeout: late, and while the client
    /// would already be waiting for its next answer.
    Late,
    /// The first half of the answer, then nothing.
    Partial,
    /// For another transaction (TCP only).
    WrongTransaction,
    /// From another unit.
    WrongUnit,
    /// A header announcing more than any frame holds, then 64 kB of bytes.
    Oversized,
    /// Half of the answer, then the connection closes (TCP) or the line falls silent (RTU).
    CloseMidFrame,
}

/// The value the server holds at `address`: a stale answer to another address shows.
fn value_at(address: u16) -> u16 {
    address.wrapping_mul(3).wrapping_add(1)
}

/// The answer PDU to a read of one holding register at the address in `request_pdu`.
fn read_answer(request_pdu: &[u8]) -> Vec<u8> {
    let address = u16::from_be_bytes([request_pdu[1], request_pdu[2]]);
    let [hi, lo] = value_at(address).to_be_bytes();
    vec![0x03, 2, hi, lo]
}

/// What the scripted server sends for `answer`, given the well-formed answer frame `good`, the
/// frame `other_unit` (the same answer from another unit) and `other_transaction`.
fn bytes_for(
    answer: Answer,
    good: &[u8],
    other_unit: Vec<u8>,
    other_transaction: Vec<u8>,
) -> Vec<u8> {
    match answer {
        Answer::Good | Answer::Slow | Answer::Late => good.to_vec(),
        Answer::Partial | Answer::CloseMidFrame => good[..good.len() / 2].to_vec(),
        Answer::WrongTransaction => other_transaction,
        Answer::WrongUnit => other_unit,
        Answer::Oversized => {
            let mut bytes = good[..2].to_vec();
            bytes.extend([0, 0, 0xFF, 0xFF, 1]);
            bytes.extend(std::iter::repeat_n(0x03, 65_536));
            bytes
        }
    }
}

/// Serves MBAP requests on `listener`, answering the n-th request as `script[n]` (then Good);
/// reports each connection it accepts on `accepted`.
fn tcp_server(listener: TcpListener, script: Vec<Answer>, accepted: mpsc::Sender<()>) {
    let mut answers = script.into_iter();
    for stream in listener.incoming() {
        let Ok(mut stream) = stream else { return };
        let _ = accepted.send(());
        let mut header = [0u8; 7];
        while stream.read_exact(&mut header).is_ok() {
            let mut pdu = vec![0u8; usize::from(u16::from_be_bytes([header[4], header[5]])) - 1];
            if stream.read_exact(&mut pdu).is_err() {
                break;
            }
            let answer = answers.next().unwrap_or(Answer::Good);
            let frame = |transaction: u16, unit: u8| {
                let body = read_answer(&pdu);
                let mut out = transaction.to_be_bytes().to_vec();
                out.extend([0, 0, 0, body.len() as u8 + 1, unit]);
                out.extend(body);
                out
            };
            let transaction = u16::from_be_bytes([header[0], header[1]]);
            let good = frame(transaction, header[6]);
            let bytes = bytes_for(
                answer,
                &good,
                frame(transaction, header[6] + 1),
                frame(transaction.wrapping_add(1), header[6]),
            );
            if answer == Answer::Slow {
                // Late by half a timeout, so that it lands inside the next request's wait, where
                // only its transaction id tells it apart, and the next answer (sent right after
                // it) lands well before that wait ends. After two timeouts, as on RTU, the next
                // answer came out exactly at the next request's deadline: a race a loaded machine
                // lost now and then.
                std::thread::sleep(TIMEOUT * 3 / 2);
            }
            if stream.write_all(&bytes).is_err() || answer == Answer::CloseMidFrame {
                break;
            }
        }
    }
}

/// Reads holding register `address` once (no retries).
fn read(client: &mut impl RegisterBus, address: u16) -> Result<u16, BusError> {
    let mut value = [0u16];
    client.read_registers(UNIT, Table::Holding, address, &mut value)?;
    Ok(value[0])
}

/// The typed error each misbehaviour must end in.
fn expected_error(answer: Answer, error: &BusError) -> bool {
    match answer {
        Answer::CloseMidFrame => matches!(error, BusError::Io(_)),
        Answer::Oversized => matches!(error, BusError::Frame(_)),
        _ => matches!(error, BusError::Timeout | BusError::Frame(_)),
    }
}

const MISBEHAVIOURS: [Answer; 6] = [
    Answer::Slow,
    Answer::Partial,
    Answer::WrongTransaction,
    Answer::WrongUnit,
    Answer::Oversized,
    Answer::CloseMidFrame,
];

#[test]
fn the_tcp_client_survives_each_misbehaving_answer() {
    for answer in MISBEHAVIOURS {
        let listener = TcpListener::bind("127.0.0.1:0").unwrap();
        let addr = listener.local_addr().unwrap();
        let (accepted_tx, accepted) = mpsc::channel();
        std::thread::spawn(move || tcp_server(listener, vec![answer], accepted_tx));
        let config = TcpConfig {
            timeout: TIMEOUT,
            retry: RetryPolicy::reads(0),
            ..TcpConfig::default()
        };
        let mut client = ModbusTcpClient::connect(addr, &config).unwrap();
        let error = read(&mut client, 10).unwrap_err();
        assert!(expected_error(answer, &error), "{answer:?}: {error:?}");
        for address in 11..14 {
            assert_eq!(
                read(&mut client, address),
                Ok(value_at(address)),
                "after {answer:?}"
            );
        }
        let connections = accepted.try_iter().count();
        let expected = if answer == Answer::CloseMidFrame {
            2
        } else {
            1
        };
        assert_eq!(connections, expected, "{answer:?}: connections opened");
    }
}

/// A frame's bytes followed by their CRC.
fn with_crc(mut frame: Vec<u8>) -> Vec<u8> {
    let crc = crc16_modbus(&frame);
    frame.extend(crc.to_le_bytes());
    frame
}

/// Serves RTU read requests (8 bytes each) on the pty end `path`, answering the n-th as
/// `script[n]` (then Good).
fn rtu_server(path: &str, script: Vec<Answer>) {
    let mut line = std::fs::OpenOptions::new()
        .read(true)
        .write(true)
        .open(path)
        .unwrap();
    let mut answers = script.into_iter();
    let mut request = [0u8; 8];
    while line.read_exact(&mut request).is_ok() {
        let answer = answers.next().unwrap_or(Answer::Good);
        let frame = |unit: u8| {
            let mut body = vec![unit];
            body.extend(read_answer(&request[1..6]));
            with_crc(body)
        };
        let good = frame(request[0]);
        let mut oversized = vec![request[0], 0x03, 0xFF];
        oversized.extend(std::iter::repeat_n(0x55, 65_536));
        let bytes = match answer {
            // A length byte of 255: more than an ADU holds.
            Answer::Oversized => oversized,
            _ => bytes_for(answer, &good, frame(request[0] + 1), good.clone()),
        };
        match answer {
            Answer::Slow => std::thread::sleep(TIMEOUT * 2),
            Answer::Late => std::thread::sleep(TIMEOUT * 3 / 2),
            _ => {}
        }
        if line.write_all(&bytes).is_err() {
            return;
        }
    }
}

#[test]
fn the_rtu_client_survives_each_misbehaving_answer() {
    for answer in MISBEHAVIOURS {
        if answer == Answer::WrongTransaction {
            continue; // RTU has no transaction ids.
        }
        let pty = pty_pair();
        let server_end = pty.server.to_str().unwrap().to_owned();
        std::thread::spawn(move || rtu_server(&server_end, vec![answer]));
        let config = SerialConfig {
            timeout: TIMEOUT,
            retry: RetryPolicy::reads(0),
            ..SerialConfig::new(115_200)
        };
        let mut client = SerialRtuClient::open(pty.client.to_str().unwrap(), &config).unwrap();
        let error = read(&mut client, 10).unwrap_err();
        let typed = match answer {
            // The line cannot close: a frame cut short is silence.
            Answer::CloseMidFrame => matches!(error, BusError::Timeout | BusError::Frame(_)),
            _ => expected_error(answer, &error),
        };
        assert!(typed, "{answer:?}: {error:?}");
        // A late answer arrives in the next exchange's idle gap or wait; give the line a pause
        // as a master does after a timeout.
        std::thread::sleep(TIMEOUT * 2);
        for address in 11..14 {
            assert_eq!(
                read(&mut client, address),
                Ok(value_at(address)),
                "after {answer:?}"
            );
        }
    }
}

#[test]
fn a_server_that_never_stops_sending_ends_in_a_typed_error() {
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let addr = listener.local_addr().unwrap();
    std::thread::spawn(move || {
        let (mut stream, _) = listener.accept().unwrap();
        // Garbage without end, from before the first request, until the client hangs up.
        while stream.write_all(&[0x55; 4096]).is_ok() {}
    });
    let config = TcpConfig {
        timeout: TIMEOUT,
        retry: RetryPolicy::reads(0),
        ..TcpConfig::default()
    };
    let mut client = ModbusTcpClient::connect(addr, &config).unwrap();
    std::thread::sleep(Duration::from_millis(50));
    let started = std::time::Instant::now();
    for address in 0..3 {
        let error = read(&mut client, address).unwrap_err();
        assert!(
            matches!(error, BusError::Timeout | BusError::Frame(_)),
            "{error:?}"
        );
    }
    // A hang guard, not a speed claim: before the flush was bounded (at most 64 KiB per
    // request), a writer faster than the reader could hold the client in it indefinitely.
    assert!(started.elapsed() < TIMEOUT * 60, "{:?}", started.elapsed());
}

#[test]
fn a_late_rtu_answer_is_not_taken_for_the_next_one() {
    // RTU answers carry no transaction id: the late answer to the read of 10 has the shape of
    // the answer to the read of 11 sent right after the timeout. The client lets it pass first.
    let pty = pty_pair();
    let server_end = pty.server.to_str().unwrap().to_owned();
    std::thread::spawn(move || rtu_server(&server_end, vec![Answer::Late]));
    let config = SerialConfig {
        timeout: TIMEOUT,
        retry: RetryPolicy::reads(0),
        ..SerialConfig::new(115_200)
    };
    let mut client = SerialRtuClient::open(pty.client.to_str().unwrap(), &config).unwrap();
    assert_eq!(read(&mut client, 10), Err(BusError::Timeout));
    assert_eq!(read(&mut client, 11), Ok(value_at(11)));
    assert_eq!(read(&mut client, 12), Ok(value_at(12)));
}
