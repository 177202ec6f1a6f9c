//! Where `decode` and `trace` take frames from: a candump log, or a live CAN interface with each
//! frame's receive time.

use std::fs::File;
use std::io::BufReader;
use std::path::Path;
use std::process::Child;
use std::time::{Duration, UNIX_EPOCH};

use drivebus::canopen::can::candump::CandumpReader;
use drivebus::canopen::can::{CanEvent, Timestamp};
use drivebus::canopen::{CanBus, CanFrame};
use drivegen::ir::Device;

use crate::can::{CanSettings, CanSpec};
use crate::error::CliError;

/// The options of a live source.
#[derive(Debug, Clone, clap::Args)]
pub struct LiveArgs {
    /// Decode live from a CAN interface instead of a capture, each frame with its receive time
    /// (the kernel's on `socketcan:IFACE`, the adapter's milliseconds on `slcan:` in `Z1`
    /// mode): `socketcan:IFACE`, `slcan:/dev/PATH` or `slcan:HOST:PORT`.
    #[arg(long, value_name = "BACKEND", conflicts_with = "capture")]
    pub can: Option<String>,
    /// --can: stop after this many frames (default: run until interrupted).
    #[arg(long, requires = "can")]
    pub count: Option<usize>,
    /// --can: stop after this long without a frame, in milliseconds.
    #[arg(long, requires = "can")]
    pub idle_ms: Option<u64>,
    /// --can slcan:...: the CAN bit rate, 10k to 1M (default: the description's documented
    /// default, else 500k).
    #[arg(long, value_name = "BITS", requires = "can", value_parser = crate::can::parse_bitrate)]
    pub bitrate: Option<u32>,
}

/// When a frame was received, printed as `seconds.micros` (a capture's or the kernel's
/// timestamp), `Nms` (an adapter's clock) or nothing: kept as numbers, written only when a
/// frame is printed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Time {
    /// No timestamp.
    None,
    /// Microseconds since the epoch (split into seconds only when printed: a trace drops most
    /// frames unprinted).
    Micros(u64),
    /// An adapter's milliseconds.
    AdapterMillis(u16),
}

impl std::fmt::Display for Time {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::None => Ok(()),
            Self::Micros(us) => write!(f, "{}.{:06}", us / 1_000_000, us % 1_000_000),
            Self::AdapterMillis(ms) => write!(f, "{ms}ms"),
        }
    }
}

/// What a source gives.
#[derive(Debug)]
pub enum Received {
    /// A frame and its time (`seconds.micros`, `Nms` from an adapter, or empty).
    Frame {
        /// When it was received.
        time: Time,
        /// The frame.
        frame: CanFrame,
    },
    /// An error frame or bus state change of a live interface.
    BusError {
        /// When it was reported.
        time: Time,
        /// The error classes.
        classes: String,
        /// The controller state, if reported.
        state: String,
    },
    /// A capture line that is not a frame, with where and why.
    Malformed(String),
}

/// A capture or a live interface.
pub struct FrameSource {
    inner: Inner,
}

enum Inner {
    Capture {
        reader: CandumpReader<BufReader<File>>,
        path: String,
        records: usize,
    },
    Live {
        bus: Box<dyn CanBus + Send>,
        _child: Option<Child>,
        backend: String,
        count: Option<usize>,
        frames: usize,
        idle: Duration,
        stop_when_idle: bool,
    },
}

impl FrameSource {
    /// The frames of a candump log.
    pub fn capture(path: &Path) -> Result<Self, CliError> {
        let file = File::open(path)
            .map_err(|e| CliError::Io(format!("cannot open {}: {e}", path.display())))?;
        Ok(Self {
            inner: Inner::Capture {
                reader: CandumpReader::new(BufReader::new(file)),
                path: path.display().to_string(),
                records: 0,
            },
        })
    }

    /// The frames of the interface `args.can` names (a candump child is not a live interface).
    pub fn live(args: &LiveArgs, device: &Device) -> Result<Self, CliError> {
        let backend = args.can.clone().unwrap_or_default();
        let forms = "socketcan:IFACE, slcan:/dev/PATH or slcan:HOST:PORT";
        let spec = CanSpec::parse(&backend, forms)?;
        if matches!(spec, CanSpec::CandumpExec(_) | CanSpec::CandumpStdio) {
            return Err(CliError::Usage(format!(
                "--can {backend}: expected {forms}"
            )));
        }
        let settings = CanSettings {
            bitrate: crate::can::bitrate(args.bitrate, &[device]),
            baud: crate::can::DEFAULT_SLCAN_BAUD,
        };
        let (bus, child) = crate::can::open(&backend, &spec, settings)?;
        Ok(Self {
            inner: Inner::Live {
                bus,
                _child: child,
                backend,
                count: args.count,
                frames: 0,
                idle: args
                    .idle_ms
                    .map_or(Duration::from_secs(3600), Duration::from_millis),
                stop_when_idle: args.idle_ms.is_some(),
            },
        })
    }
}

impl Iterator for FrameSource {
    type Item = Result<Received, CliError>;

    fn next(&mut self) -> Option<Self::Item> {
        match &mut self.inner {
            Inner::Capture {
                reader,
                path,
                records,
            } => {
                let record = reader.next()?;
                *records += 1;
                Some(Ok(match record {
                    Ok(record) => Received::Frame {
                        time: record.timestamp_us.map_or(Time::None, Time::Micros),
                        frame: record.frame,
                    },
                    Err(e) => Received::Malformed(format!("{path}, record {records}: {e}")),
                }))
            }
            Inner::Live {
                bus,
                backend,
                count,
                frames,
                idle,
                stop_when_idle,
                ..
            } => loop {
                if count.is_some_and(|count| *frames >= count) {
                    return None;
                }
                let event = match bus.recv_event(*idle) {
                    Ok(event) => event,
                    Err(e) => return Some(Err(CliError::Io(format!("{backend}: {e}")))),
                };
                match event {
                    None if *stop_when_idle => return None,
                    Some(CanEvent::Frame { frame, timestamp }) => {
                        *frames += 1;
                        let time = time(timestamp);
                        return Some(Ok(Received::Frame { time, frame }));
                    }
                    Some(CanEvent::Error { report, timestamp }) => {
                        return Some(Ok(Received::BusError {
                            time: time(timestamp),
                            classes: format!("{:?}", report.classes),
                            state: report.state.map_or(String::new(), |s| s.to_string()),
                        }))
                    }
                    _ => continue,
                }
            },
        }
    }
}

fn time(timestamp: Option<Timestamp>) -> Time {
    match timestamp {
        Some(Timestamp::Kernel(at)) => at.duration_since(UNIX_EPOCH).map_or(Time::None, |d| {
            Time::Micros(u64::try_from(d.as_micros()).unwrap_or(u64::MAX))
        }),
        Some(Timestamp::AdapterMillis(ms)) => Time::AdapterMillis(ms),
        None => Time::None,
    }
}
