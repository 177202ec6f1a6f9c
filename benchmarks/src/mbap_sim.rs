//! Simulated Modbus TCP drives for the async benchmarks: one listener per drive on 127.0.0.1,
//! every connection answered by a task on one current-thread tokio runtime. A read of
//! holding or input registers gets `0x1000 + address`; anything else closes the connection.
//!
//! It runs in its own process (`src/bin/mbap-sim.rs`), so that the client's process CPU time
//! and resident memory are the client's alone.

use std::io;

use drivebus::modbus::pdu::{decode_request, encode_registers_response, Request};
use drivebus::modbus::tcp::{self as mbap, Header};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::{TcpListener, TcpStream};

/// Binds `drives` listeners on 127.0.0.1 (ephemeral ports).
pub fn bind(drives: usize) -> io::Result<Vec<std::net::TcpListener>> {
    (0..drives)
        .map(|_| {
            let listener = std::net::TcpListener::bind("127.0.0.1:0")?;
            listener.set_nonblocking(true)?;
            Ok(listener)
        })
        .collect()
}

/// Serves every listener until the runtime is dropped.
pub async fn serve(listeners: Vec<std::net::TcpListener>) -> io::Result<()> {
    for listener in listeners {
        let listener = TcpListener::from_std(listener)?;
        tokio::spawn(accept(listener));
    }
    std::future::pending().await
}

async fn accept(listener: TcpListener) {
    while let Ok((stream, _)) = listener.accept().await {
        // Answers are single small writes: without this Nagle's delay would hold them.
        let _ = stream.set_nodelay(true);
        tokio::spawn(answer(stream));
    }
}

/// Answers request after request, so pipelined requests are answered in turn.
async fn answer(mut stream: TcpStream) {
    let (mut rx, mut tx) = ([0u8; 260], [0u8; 260]);
    let mut values = [0u16; 125];
    while stream.read_exact(&mut rx[..mbap::HEADER_LEN]).await.is_ok() {
        let Ok(header) = Header::parse(&rx) else {
            return;
        };
        let pdu = &mut rx[mbap::HEADER_LEN..][..header.pdu_len];
        if stream.read_exact(pdu).await.is_err() {
            return;
        }
        let (function, start, count) = match decode_request(pdu) {
            Ok(Request::ReadHoldingRegisters { start, count }) => (3, start, count),
            Ok(Request::ReadInputRegisters { start, count }) => (4, start, count),
            _ => return,
        };
        let values = &mut values[..usize::from(count).min(125)];
        for (i, value) in values.iter_mut().enumerate() {
            *value = 0x1000u16.wrapping_add(start).wrapping_add(i as u16);
        }
        let Ok(len) = encode_registers_response(function, values, &mut tx[mbap::HEADER_LEN..])
        else {
            return;
        };
        let reply = Header {
            pdu_len: len,
            ..header
        };
        if reply.write(&mut tx).is_err()
            || stream
                .write_all(&tx[..mbap::HEADER_LEN + len])
                .await
                .is_err()
        {
            return;
        }
    }
}
