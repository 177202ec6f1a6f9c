//! The Kinco RS-232 protocol: 10-byte telegrams carrying an SDO-like data protocol.
//!
//! Source: Kinco FD1X3/FD1X4 manual (`003_8cc8f7f4f05b8633.txt`), chapter 9, lines 2160–2370.
//! The drive's RS-485 port speaks this protocol too, out of the box: object 6510h sub 0Ch
//! selects 0 = Modbus, 1 = this protocol, default 1 (line 2390).
//!
//! Layers, from the wire up; the first three are sans-I/O, `no_std` and always built:
//!
//! * [`telegram`] — the transport protocol: station id, 8 data bytes, checksum
//!   (`CHKS = −SUM(byte 0 … byte 8)`, line 2190).
//! * [`data`] — the data protocol in those 8 bytes: upload (read) and download (write) requests
//!   with object index, subindex and width, and the answers: data, "written", or an error cause
//!   (lines 2224–2320).
//! * [`exchange`] — one request and its answer as a pure function of received bytes, in
//!   point-to-point or multi-point loop mode, where the host's own telegram comes back before
//!   the answer (lines 2194–2222); every way it can fail is an [`Rs232Error`].
//! * [`TelegramBus`] / [`Rs232Link`] — the bus trait the client implements and the
//!   [`Link`](crate::Link) generated drive handles use.
//! * `client` (feature `rs232`) — a blocking client over a serial port ([`serialport`](https://docs.rs/serialport)),
//!   with a timeout per answer.
//!
//! The manual's request telegrams (lines 2330–2365) are test vectors in
//! `drivebus/tests/rs232_manual_telegrams.rs`. One of them, line 2359, is printed with 9 bytes
//! (`01 40 41 60 00 00 00 00 1E`): it is the Statusword read of lines 2333 and 2345 with one
//! reserved zero lost in print, since every telegram has 10 bytes (line 2185) and `1E` is the
//! checksum of the 10-byte form.
//!
//! Parameters are addressed as in CANopen, by [`ObjectAddress`] (index, subindex, bytes): one
//! definition of an object address serves both protocols.
//!
//! ```
//! use drivebus::rs232::{exchange::Exchange, data::Request, LoopMode, StationId};
//!
//! // "Read the Statusword" (manual line 2333).
//! let mut exchange = Exchange::new(StationId(1), Request::upload(0x6041, 0), LoopMode::PointToPoint);
//! assert_eq!(exchange.telegram(), &[0x01, 0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0, 0x1E]);
//! // The drive answers 0x4B (16-bit data) 0x0437.
//! let answer = exchange.receive(&[0x01, 0x4B, 0x41, 0x60, 0x00, 0x37, 0x04, 0, 0, 0xD8])?;
//! assert_eq!(answer.unwrap().value(), Some(&[0x37, 0x04][..]));
//! # Ok::<(), drivebus::rs232::Rs232Error>(())
//! ```

#[cfg(feature = "async")]
pub mod async_client;
#[cfg(feature = "rs232")]
pub mod client;
pub mod data;
mod error;
pub mod exchange;
mod link;
pub mod telegram;

pub use crate::canopen::ObjectAddress;
pub use error::Rs232Error;
#[cfg(feature = "async")]
pub use link::AsyncTelegramBus;
pub use link::{Rs232Link, TelegramBus};

pub use drivebus_model::rs232::Rs232;

/// The station id in byte 0 of every telegram: the drive's node id (`ID_Com`, 100Bh, default 1,
/// manual line 2387).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct StationId(pub u8);

/// How the drives are wired (manual lines 2194–2222).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LoopMode {
    /// One host, one drive (`RS232_Loop_Enable` = 0): only the answer comes back.
    #[default]
    PointToPoint,
    /// Several drives in a loop (`RS232_Loop_Enable`, 6510h sub 0Bh, = 1): the host's own
    /// telegram passes the loop and comes back first, then the addressed drive's answer.
    MultiPoint,
}
