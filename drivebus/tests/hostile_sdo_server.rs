//! A hostile SDO server behind a candump text stream: answers that come late, cut short, from
//! another node, for another object, as garbage text, or a stream that ends mid-line. Each ends
//! in a typed error, and (while the stream lasts) the next transfer works.
#![cfg(feature = "canopen")]

use std::io::{BufRead, BufReader, Write};
use std::os::unix::net::UnixStream;
use std::time::Duration;

use drivebus::canopen::can::candump::{parse_line, CandumpBus};
use drivebus::canopen::client::BlockingSdo;
use drivebus::canopen::{NodeId, SdoBus};
use drivebus::BusError;

const NODE: NodeId = NodeId(5);
const TIMEOUT: Duration = Duration::from_millis(150);

/// How the server answers one upload request.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Answer {
    Good,
    /// After twice the client's timeout.
    Slow,
    /// The first five bytes of the frame only.
    Short,
    /// From node 6.
    OtherNode,
    /// For object 2101h instead.
    OtherObject,
    /// A line that is no frame.
    Garbage,
    /// Half a line, then the stream ends.
    CloseMidLine,
}

/// The value of object `index`: a stale answer for another object shows.
fn value_of(index: u16) -> u16 {
    index ^ 0x5A5A
}

fn upload_answer(node: u8, index: u16) -> String {
    let [lo, hi] = index.to_le_bytes();
    let [v0, v1] = value_of(index).to_le_bytes();
    format!(
        "{:03X}#4B{lo:02X}{hi:02X}00{v0:02X}{v1:02X}0000\n",
        0x580 + u16::from(node)
    )
}

/// Answers upload requests on `stream` as `script` says (then Good).
fn server(stream: UnixStream, script: Vec<Answer>) {
    let mut writer = stream.try_clone().unwrap();
    let mut answers = script.into_iter();
    for line in BufReader::new(stream).lines() {
        let Ok(line) = line else { return };
        let Ok(Some(record)) = parse_line(line.as_bytes()) else {
            continue;
        };
        let data = record.frame.data();
        if record.frame.id() != 0x605 || data[0] != 0x40 {
            continue; // Aborts the client sends after a failure.
        }
        let index = u16::from_le_bytes([data[1], data[2]]);
        let good = upload_answer(5, index);
        let text = match answers.next().unwrap_or(Answer::Good) {
            Answer::Good => good,
            Answer::Slow => {
                std::thread::sleep(TIMEOUT * 2);
                good
            }
            Answer::Short => format!("{}\n", &good[..14]),
            Answer::OtherNode => upload_answer(6, index),
            Answer::OtherObject => upload_answer(5, index + 1),
            Answer::Garbage => "585#4B0021ZZ\n".to_string(),
            Answer::CloseMidLine => {
                let _ = writer.write_all(&good.as_bytes()[..9]);
                return;
            }
        };
        if writer.write_all(text.as_bytes()).is_err() {
            return;
        }
    }
}

fn client_and_server(answer: Answer) -> BlockingSdo<CandumpBus<UnixStream>> {
    let (client_end, server_end) = UnixStream::pair().unwrap();
    std::thread::spawn(move || server(server_end, vec![answer]));
    let bus = CandumpBus::new(client_end.try_clone().unwrap(), client_end);
    BlockingSdo::new(bus).with_timeout(TIMEOUT)
}

fn upload(sdo: &mut BlockingSdo<CandumpBus<UnixStream>>, index: u16) -> Result<u16, BusError> {
    let mut out = [0u8; 2];
    sdo.upload(NODE, index, 0, &mut out)?;
    Ok(u16::from_le_bytes(out))
}

#[test]
fn the_sdo_client_survives_each_misbehaving_answer() {
    for answer in [
        Answer::Slow,
        Answer::Short,
        Answer::OtherNode,
        Answer::OtherObject,
        Answer::Garbage,
    ] {
        let mut sdo = client_and_server(answer);
        assert_eq!(
            upload(&mut sdo, 0x2100),
            Err(BusError::Timeout),
            "{answer:?}"
        );
        if answer == Answer::Slow {
            // The late answer arrives while the client waits for nothing: it is dropped
            // before the next transfer starts.
            std::thread::sleep(TIMEOUT * 2);
        }
        for index in 0x2102..0x2105 {
            assert_eq!(
                upload(&mut sdo, index),
                Ok(value_of(index)),
                "after {answer:?}"
            );
        }
    }
}

#[test]
fn a_stream_ending_mid_line_is_an_io_error() {
    let mut sdo = client_and_server(Answer::CloseMidLine);
    assert!(
        matches!(upload(&mut sdo, 0x2100), Err(BusError::Io(_))),
        "the end of the stream is reported"
    );
}
