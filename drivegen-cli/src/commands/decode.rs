//! `drivegen decode`: a candump capture as named, typed values.

use std::fs::File;
use std::io::BufReader;
use std::path::PathBuf;

use drivebus::canopen::can::candump::CandumpReader;
use drivebus::canopen::message::Message;
use drivebus::canopen::sdo::AbortCode;
use drivegen::ir::Device;

use crate::error::CliError;
use crate::pdo_mappings::PdoMappings;
use crate::table;

/// Arguments of `decode`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Description file, or a folder with a device.toml.
    description: PathBuf,
    /// candump log (`(1700000000.123456) can0 605#...`) or compact lines (`605#...`); none
    /// with --can.
    #[arg(required_unless_present = "can")]
    capture: Option<PathBuf>,
    /// Decode live from a CAN interface instead of a capture, printing each frame as it arrives
    /// with its receive time (the kernel's on `socketcan:IFACE`, the adapter's milliseconds on
    /// `slcan:` in `Z1` mode): `socketcan:IFACE`, `slcan:/dev/PATH` or `slcan:HOST:PORT`.
    #[arg(long, value_name = "BACKEND", conflicts_with = "capture")]
    can: Option<String>,
    /// --can: stop after this many frames (default: run until interrupted).
    #[arg(long, requires = "can")]
    count: Option<usize>,
    /// --can: stop after this long without a frame, in milliseconds.
    #[arg(long, requires = "can")]
    idle_ms: Option<u64>,
    /// --can slcan:...: the CAN bit rate, 10k to 1M (default: the description's documented
    /// default, else 500k).
    #[arg(long, value_name = "BITS", requires = "can", value_parser = crate::can::parse_bitrate)]
    bitrate: Option<u32>,
    /// Print one JSON object per frame.
    #[arg(long)]
    json: bool,
}

/// One decoded frame.
struct Line {
    time: String,
    node: String,
    kind: &'static str,
    what: String,
    value: String,
}

/// Decodes every frame of the capture, or live from --can.
pub fn run(args: Args) -> Result<(), CliError> {
    let device = super::load(&args.description)?;
    if let Some(backend) = &args.can {
        return live(&args, &device, backend);
    }
    let capture = args.capture.clone().unwrap_or_default();
    let file = File::open(&capture)
        .map_err(|e| CliError::Io(format!("cannot open {}: {e}", capture.display())))?;
    let mut lines = Vec::new();
    let mut mappings = PdoMappings::default();
    for record in CandumpReader::new(BufReader::new(file)) {
        let record = record.map_err(|e| CliError::Io(format!("{}: {e}", capture.display())))?;
        let time = record.timestamp_us.map_or(String::new(), |us| {
            format!("{}.{:06}", us / 1_000_000, us % 1_000_000)
        });
        let message = Message::classify(&record.frame);
        if let Message::SdoRequest { node, data } = message {
            if let Some((index, subindex, value)) = expedited_download(&data) {
                mappings.learn(node.0, index, subindex, value);
            }
        }
        lines.push(decode(&device, &mappings, message, time));
    }
    if args.json {
        for l in &lines {
            println!(
                "{}",
                serde_json::json!({"time": l.time, "node": l.node, "kind": l.kind, "object": l.what, "value": l.value})
            );
        }
    } else {
        let mut rows = vec![vec![
            "time".to_string(),
            "node".into(),
            "kind".into(),
            "object".into(),
            "value".into(),
        ]];
        rows.extend(
            lines
                .into_iter()
                .map(|l| vec![l.time, l.node, l.kind.to_string(), l.what, l.value]),
        );
        print!("{}", table::render(&rows));
    }
    Ok(())
}

/// Decodes frames from a live interface as they arrive, one line (or JSON object) each; error
/// frames and bus states are lines of kind `error`.
fn live(args: &Args, device: &Device, backend: &str) -> Result<(), CliError> {
    use drivebus::canopen::can::{CanEvent, Timestamp};
    use std::io::Write;
    use std::time::{Duration, UNIX_EPOCH};
    let forms = "socketcan:IFACE, slcan:/dev/PATH or slcan:HOST:PORT";
    let spec = crate::can::CanSpec::parse(backend, forms)?;
    if matches!(
        spec,
        crate::can::CanSpec::CandumpExec(_) | crate::can::CanSpec::CandumpStdio
    ) {
        return Err(CliError::Usage(format!(
            "--can {backend}: expected {forms}"
        )));
    }
    let settings = crate::can::CanSettings {
        bitrate: crate::can::bitrate(args.bitrate, &[device]),
        baud: crate::can::DEFAULT_SLCAN_BAUD,
    };
    let (mut bus, _) = crate::can::open(backend, &spec, settings)?;
    let mut mappings = PdoMappings::default();
    let mut frames = 0;
    let idle = args
        .idle_ms
        .map_or(Duration::from_secs(3600), Duration::from_millis);
    let mut out = std::io::stdout().lock();
    while args.count.is_none_or(|count| frames < count) {
        let event = bus
            .recv_event(idle)
            .map_err(|e| CliError::Io(format!("{backend}: {e}")))?;
        let time = |timestamp: Option<Timestamp>| match timestamp {
            Some(Timestamp::Kernel(at)) => {
                at.duration_since(UNIX_EPOCH).map_or(String::new(), |d| {
                    format!("{}.{:06}", d.as_secs(), d.subsec_micros())
                })
            }
            Some(Timestamp::AdapterMillis(ms)) => format!("{ms}ms"),
            None => String::new(),
        };
        let line = match event {
            None if args.idle_ms.is_some() => break,
            None => continue,
            Some(CanEvent::Frame { frame, timestamp }) => {
                frames += 1;
                let message = Message::classify(&frame);
                if let Message::SdoRequest { node, data } = message {
                    if let Some((index, subindex, value)) = expedited_download(&data) {
                        mappings.learn(node.0, index, subindex, value);
                    }
                }
                decode(device, &mappings, message, time(timestamp))
            }
            Some(CanEvent::Error { report, timestamp }) => Line {
                time: time(timestamp),
                node: String::new(),
                kind: "error",
                what: format!("{:?}", report.classes),
                value: report.state.map_or(String::new(), |s| s.to_string()),
            },
            Some(_) => continue,
        };
        let printed = if args.json {
            writeln!(
                out,
                "{}",
                serde_json::json!({"time": line.time, "node": line.node, "kind": line.kind, "object": line.what, "value": line.value})
            )
        } else {
            writeln!(
                out,
                "{}  {}  {}  {}  {}",
                line.time, line.node, line.kind, line.what, line.value
            )
        };
        if printed.and_then(|()| out.flush()).is_err() {
            // The reader went away (a closed pipe): stop quietly.
            return Ok(());
        }
    }
    Ok(())
}

/// The object and value of an expedited download request.
fn expedited_download(data: &[u8; 8]) -> Option<(u16, u8, &[u8])> {
    if data[0] >> 5 != 1 || data[0] & 0b10 == 0 {
        return None;
    }
    let (index, subindex) = mux(data);
    let len = if data[0] & 1 != 0 {
        4 - ((data[0] >> 2) & 3) as usize
    } else {
        4
    };
    Some((index, subindex, &data[4..4 + len]))
}

fn decode(device: &Device, mappings: &PdoMappings, message: Message, time: String) -> Line {
    let line = |node: String, kind, what: String, value: String| Line {
        time: time.clone(),
        node,
        kind,
        what,
        value,
    };
    match message {
        Message::SdoRequest { node, data } => {
            let (what, value) = sdo_request(device, &data);
            line(node.0.to_string(), "sdo →", what, value)
        }
        Message::SdoResponse { node, data } => {
            let (what, value) = sdo_response(device, &message, &data);
            line(node.0.to_string(), "sdo ←", what, value)
        }
        Message::Heartbeat { node, state } => line(
            node.0.to_string(),
            "heartbeat",
            String::new(),
            format!("{state:?}"),
        ),
        Message::Emcy(emcy) => line(
            emcy.node.0.to_string(),
            "emcy",
            format!("{:#06X}", emcy.code),
            format!(
                "{} (register {:#04x})",
                emcy_name(device, emcy.code),
                emcy.register.bits()
            ),
        ),
        Message::Nmt { command, target } => line(
            target.map_or("all".into(), |n| n.0.to_string()),
            "nmt",
            String::new(),
            format!("{command:?}"),
        ),
        Message::Sync(counter) => {
            line(String::new(), "sync", String::new(), format!("{counter:?}"))
        }
        Message::Pdo {
            kind,
            number,
            node,
            frame,
        } => line(
            node.0.to_string(),
            "pdo",
            format!("{kind:?}{number}"),
            mappings
                .decode(device, node.0, kind, number, frame.data())
                .unwrap_or_else(|| format!("{:02X?} (mapping not in the capture)", frame.data())),
        ),
        Message::Time(frame) | Message::Other(frame) => line(
            String::new(),
            "other",
            format!("{:03X}", frame.id()),
            format!("{:02X?}", frame.data()),
        ),
    }
}

/// The parameter at `index:subindex`, by name, or the address.
fn object_name(device: &Device, index: u16, subindex: u8) -> String {
    find(device, index, subindex).map_or(format!("{index:04X}:{subindex:02X}"), |p| p.name.clone())
}

fn find(device: &Device, index: u16, subindex: u8) -> Option<&drivegen::ir::Parameter> {
    device.parameters.iter().find(|p| {
        p.canopen
            .iter()
            .any(|a| a.index == index && a.subindex == subindex)
    })
}

fn mux(data: &[u8; 8]) -> (u16, u8) {
    (u16::from_le_bytes([data[1], data[2]]), data[3])
}

fn typed(device: &Device, index: u16, subindex: u8, bytes: &[u8]) -> String {
    match find(device, index, subindex) {
        Some(p) => drivebus::interpret::show(device, p, bytes).text,
        None => format!("{bytes:02X?}"),
    }
}

fn sdo_request(device: &Device, data: &[u8; 8]) -> (String, String) {
    let (index, subindex) = mux(data);
    let name = object_name(device, index, subindex);
    match data[0] >> 5 {
        1 if data[0] & 0b10 != 0 => {
            let len = if data[0] & 1 != 0 {
                4 - ((data[0] >> 2) & 3) as usize
            } else {
                4
            };
            (
                format!("write {name}"),
                typed(device, index, subindex, &data[4..4 + len]),
            )
        }
        1 => (format!("write {name}"), "(segmented)".into()),
        2 => (format!("read {name}"), String::new()),
        4 => (format!("abort {name}"), abort(data)),
        _ => ("segment".into(), format!("{data:02X?}")),
    }
}

fn sdo_response(device: &Device, message: &Message, data: &[u8; 8]) -> (String, String) {
    let (index, subindex) = mux(data);
    if let Some(v) = message.expedited_value() {
        let bytes = &v.bytes[..v.len as usize];
        return (
            object_name(device, v.index, v.subindex),
            typed(device, v.index, v.subindex, bytes),
        );
    }
    let name = object_name(device, index, subindex);
    match data[0] >> 5 {
        3 => (format!("{name} written"), "ok".into()),
        4 => (format!("abort {name}"), abort(data)),
        _ => ("segment".into(), format!("{data:02X?}")),
    }
}

fn abort(data: &[u8; 8]) -> String {
    let code = u32::from_le_bytes([data[4], data[5], data[6], data[7]]);
    format!("{code:#010X} {}", AbortCode::from_u32(code).meaning())
}

/// The name of an EMCY code in the description's error-code enumeration, if it has one.
fn emcy_name(device: &Device, code: u16) -> String {
    device
        .enums
        .iter()
        .filter(|e| e.name.contains("error"))
        .flat_map(|e| e.values.iter())
        .find(|v| v.value == i64::from(code))
        .map_or("unknown code".into(), |v| v.name.clone())
}
