//! Every request telegram of the Kinco FD manual (section 9.4, lines 2330–2365; the list is
//! `fixtures/kinco-rs232/manual-telegrams.txt`) comes out of the generated API byte for byte:
//! each line's action is called on the fixture's drive handle over the blocking RS-232 host,
//! and the last telegram it sent is compared with the manual's. The 150 rpm target speed
//! (line 2364) is written in rpm: the handle reads the encoder resolution first (10000 here).

use std::collections::VecDeque;
use std::time::Instant;

use drivebus::rs232::client::{Rs232Client, Rs232Config};
use drivebus::rs232::data::{Answer, Request, Value};
use drivebus::rs232::telegram::{self, Telegram};
use drivebus::rs232::{Rs232Link, StationId};
use drivebus::stream::ByteStream;
use drivebus::units::Rpm;
use drivebus::{BusError, Error};
use drivegen_tests::kinco_rs232::KincoRs232;
use peer_support::kinco_telegrams::printed;

/// A drive on a wire that records every telegram sent and answers it at once: downloads with
/// "written", uploads of the encoder resolution with 10000, other uploads with 0x0437.
#[derive(Debug, Default)]
struct Wire {
    sent: Vec<Vec<u8>>,
    answers: VecDeque<u8>,
}

impl ByteStream for Wire {
    fn send(&mut self, bytes: &[u8]) -> Result<(), BusError> {
        self.sent.push(bytes.to_vec());
        let telegram: Telegram = bytes.try_into().expect("one telegram per send");
        let (station, data) = telegram::decode(&telegram).expect("a good checksum");
        let answer = match Request::decode(data).expect("a request") {
            Request::Upload(object) if object.index == 0x6410 => {
                Answer::Uploaded(object, Value::new(&10_000u32.to_le_bytes()).unwrap())
            }
            Request::Upload(object) => Answer::Uploaded(object, Value::new(&[0x37, 0x04]).unwrap()),
            Request::Download(object, _) => Answer::Downloaded(object),
        };
        self.answers
            .extend(telegram::encode(station, &answer.encode()));
        Ok(())
    }

    fn receive(&mut self, buf: &mut [u8], _deadline: Instant) -> Result<usize, BusError> {
        let n = buf.len().min(self.answers.len());
        for (slot, byte) in buf.iter_mut().zip(self.answers.drain(..n)) {
            *slot = byte;
        }
        Ok(n)
    }

    fn discard_input(&mut self) -> Result<(), BusError> {
        self.answers.clear();
        Ok(())
    }
}

type Drive = KincoRs232<Rs232Link<Rs232Client<Wire>>>;

/// What the manual does at `line`, through the generated API.
fn act(drive: &mut Drive, line: u32) -> Result<(), Error> {
    match line {
        2330 | 2355 => drive.controlword().write(0x2Fu16),
        2339 | 2348 | 2365 => drive.controlword().write(0x0Fu16),
        2344 => drive.controlword().write(0x1Fu16),
        2356 => drive.controlword().write(0x3Fu16),
        2357 => drive.controlword().write(0x4Fu16),
        2358 => drive.controlword().write(0x5Fu16),
        2331 | 2340 => drive.operation_mode().write(6i8),
        2349 => drive.operation_mode().write(1i8),
        2363 => drive.operation_mode().write(3i8),
        2332 | 2350 => drive.target_position().write(50_000i32),
        2333 | 2345 | 2359 => drive.statusword().read().map(drop),
        2341 => drive.homing_method().write(33i8),
        2342 => drive.homing_speed_switch().write(0x08_5555u32),
        2343 => drive.homing_speed_zero().write(0x06_4000u32),
        2351 => drive.profile_speed().write(0x08_5555u32),
        2364 => drive.target_speed().write(Rpm(150.0)),
        other => panic!("no action for line {other}"),
    }
}

#[test]
fn the_generated_api_sends_every_telegram_of_the_manual() {
    let bus = Rs232Client::new(Wire::default(), Rs232Config::default());
    let mut drive = KincoRs232::rs232(bus, StationId(1));
    let vectors = printed();
    assert_eq!(vectors.len(), 23);
    for (line, manual) in vectors {
        act(&mut drive, line).unwrap_or_else(|e| panic!("line {line}: {e}"));
        let wire = drive.device().link_mut().bus_mut().stream_mut();
        assert_eq!(wire.sent.last(), Some(&manual), "line {line}");
    }
}

#[test]
fn the_statusword_read_returns_the_answers_value() {
    let bus = Rs232Client::new(Wire::default(), Rs232Config::default());
    let mut drive = KincoRs232::rs232(bus, StationId(1));
    assert_eq!(drive.statusword().read().unwrap(), 0x0437);
}
