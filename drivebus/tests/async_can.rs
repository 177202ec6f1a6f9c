//! The async CAN interfaces over in-memory tokio streams: SLCAN and candump framing, the
//! opening sequence, cancel-safe sends and the end of the stream.

use std::time::Duration;

use drivebus::asynch::TokioTimer;
use drivebus::canopen::can::async_candump::AsyncCandumpBus;
use drivebus::canopen::can::async_slcan::AsyncSlcanBus;
use drivebus::canopen::can::slcan::Bitrate;
use drivebus::canopen::can::tokio_adapters::TokioIo;
use drivebus::canopen::can::{AsyncCanBus, OpenError};
use drivebus::canopen::CanFrame;
use drivebus::error::BusError;
use tokio::io::{duplex, AsyncReadExt, AsyncWriteExt, DuplexStream};

/// `work`'s output, failing the test if it takes more than 5 s (a broken decoder would
/// otherwise wait for ever).
async fn soon<F: std::future::Future>(work: F) -> F::Output {
    tokio::time::timeout(Duration::from_secs(5), work)
        .await
        .expect("no answer within 5 s")
}

fn frame(id: u16, data: &[u8]) -> CanFrame {
    CanFrame::new(id, data).unwrap()
}

/// A bus over one end of an in-memory pipe with `capacity` bytes of buffer; the other end is
/// the adapter's side.
fn slcan(capacity: usize) -> (AsyncSlcanBus<TokioIo<DuplexStream>>, DuplexStream) {
    let (ours, theirs) = duplex(capacity);
    (AsyncSlcanBus::new(TokioIo::new(ours)), theirs)
}

#[tokio::test]
async fn slcan_frames_go_out_as_lines_and_come_back_decoded() {
    let (mut bus, mut adapter) = slcan(256);
    bus.send(&frame(0x605, &[0x40, 0x00, 0x10, 0x00]))
        .await
        .unwrap();
    let mut line = [0u8; 14];
    adapter.read_exact(&mut line).await.unwrap();
    assert_eq!(&line, b"t605440001000\r");
    // An acknowledgement, noise and a status report are skipped by `recv`.
    adapter
        .write_all(b"z\rnoise\rF00\rt58528001\r")
        .await
        .unwrap();
    assert_eq!(soon(bus.recv()).await, Ok(frame(0x585, &[0x80, 0x01])));
}

#[tokio::test]
async fn slcan_start_checks_each_answer_and_keeps_frames_that_come_between() {
    let (mut bus, mut adapter) = slcan(256);
    // C answered with BEL (already closed), S6 and O with CR; a frame arrives before them.
    adapter.write_all(b"\x07t1230\r\r\r").await.unwrap();
    bus.start(Bitrate::K500, &TokioTimer, Duration::from_millis(200))
        .await
        .unwrap();
    assert_eq!(soon(bus.recv()).await, Ok(frame(0x123, &[])));
    let mut sent = [0u8; 7];
    adapter.read_exact(&mut sent).await.unwrap();
    assert_eq!(&sent, b"C\rS6\rO\r");
}

#[tokio::test]
async fn slcan_start_reports_a_silent_or_refusing_adapter() {
    let (mut bus, _adapter) = slcan(256);
    let silent = bus
        .start(Bitrate::K500, &TokioTimer, Duration::from_millis(20))
        .await;
    assert_eq!(silent, Err(OpenError::NoAnswer { command: "S6" }));
    let (mut bus, mut adapter) = slcan(256);
    adapter.write_all(b"\r\x07").await.unwrap();
    let refused = bus
        .start(Bitrate::M1, &TokioTimer, Duration::from_millis(200))
        .await;
    assert_eq!(refused, Err(OpenError::Refused { command: "S8" }));
}

#[tokio::test]
async fn a_dropped_send_is_finished_before_the_next_frame() {
    // Room for 4 bytes: the first line cannot go out whole until the adapter reads.
    let (mut bus, mut adapter) = slcan(4);
    let first = frame(0x181, &[1, 2, 3, 4]);
    let sending = tokio::time::timeout(Duration::from_millis(20), bus.send(&first)).await;
    assert!(sending.is_err(), "the send waited for room and was dropped");
    let reader = tokio::spawn(async move {
        let mut text = vec![0u8; 28];
        adapter.read_exact(&mut text).await.unwrap();
        text
    });
    bus.send(&frame(0x182, &[5, 6, 7, 8])).await.unwrap();
    assert_eq!(
        soon(reader).await.unwrap(),
        b"t181401020304\rt182405060708\r".to_vec()
    );
}

#[tokio::test]
async fn slcan_reports_the_end_of_the_stream() {
    let (mut bus, adapter) = slcan(256);
    drop(adapter);
    assert_eq!(
        soon(bus.recv()).await,
        Err(BusError::Io(std::io::ErrorKind::UnexpectedEof))
    );
}

#[tokio::test]
async fn candump_lines_both_ways_with_malformed_ones_counted() {
    let (ours_in, mut relay_out) = duplex(1024);
    let (ours_out, mut relay_in) = duplex(1024);
    let mut bus = AsyncCandumpBus::new(TokioIo::new(ours_in), TokioIo::new(ours_out));
    bus.send(&frame(0x605, &[0x2B, 0x17, 0x10])).await.unwrap();
    let mut line = [0u8; 11];
    relay_in.read_exact(&mut line).await.unwrap();
    assert_eq!(&line, b"605#2B1710\n");
    let long = [b'x'; 300];
    relay_out
        .write_all(b"# a comment\nnot a frame\n")
        .await
        .unwrap();
    relay_out.write_all(&long).await.unwrap();
    relay_out
        .write_all(b"#tail of the long line\n(1.5) can0 585#4B17100064\n705#05")
        .await
        .unwrap();
    let record = bus.recv_record().await.unwrap();
    assert_eq!(record.frame, frame(0x585, &[0x4B, 0x17, 0x10, 0x00, 0x64]));
    assert_eq!(
        bus.malformed_lines(),
        2,
        "the malformed line and the long one"
    );
    drop(relay_out);
    // The last line has no newline: it still counts, then the end of the stream is reported.
    assert_eq!(soon(bus.recv()).await, Ok(frame(0x705, &[0x05])));
    assert_eq!(
        soon(bus.recv()).await,
        Err(BusError::Io(std::io::ErrorKind::UnexpectedEof))
    );
}

#[cfg(feature = "serial")]
#[tokio::test]
async fn slcan_over_a_serial_port_opens_the_channel_and_receives() {
    use std::io::{Read, Write};
    let pty = peer_support::pty_pair();
    let adapter_path = pty.server.clone();
    // The adapter at the other end of the line: answers C, S6 and O with CR, then sends a frame.
    let adapter = std::thread::spawn(move || {
        let mut line = std::fs::OpenOptions::new()
            .read(true)
            .write(true)
            .open(adapter_path)
            .unwrap();
        let mut commands = Vec::new();
        let mut byte = [0u8; 1];
        while commands.iter().filter(|&&b| b == b'\r').count() < 3 {
            line.read_exact(&mut byte).unwrap();
            commands.push(byte[0]);
            if byte[0] == b'\r' {
                line.write_all(b"\r").unwrap();
            }
        }
        line.write_all(b"t705100\r").unwrap();
        commands
    });
    let mut bus = AsyncSlcanBus::serial(pty.client.to_str().unwrap(), 115_200).unwrap();
    bus.start(Bitrate::K500, &TokioTimer, Duration::from_secs(2))
        .await
        .unwrap();
    assert_eq!(soon(bus.recv()).await, Ok(frame(0x705, &[0])));
    assert_eq!(adapter.join().unwrap(), b"C\rS6\rO\r");
}
