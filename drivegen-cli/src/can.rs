//! The CAN backends `--can` names, for every command that takes it: SocketCAN interfaces,
//! serial and TCP SLCAN adapters, and candump-line processes; with the bit rate (`--bitrate`)
//! and serial speed (`--baud`) of an SLCAN adapter.

use std::process::{Child, Command, Stdio};

use drivebus::canopen::can::candump::CandumpBus;
use drivebus::canopen::can::slcan::{Bitrate, SlcanBus, ANSWER_TIMEOUT};
use drivebus::canopen::can::OpenError;
use drivebus::canopen::CanBus;
use drivegen::ir::Device;

use crate::error::CliError;

/// The forms `--can` takes on the commands that reach a drive (for messages).
pub const FORMS: &str = "socketcan:IFACE, slcan:/dev/PATH, slcan:HOST:PORT or candump:exec:COMMAND";

/// The bit rate when neither --bitrate nor the description gives one.
pub const DEFAULT_BITRATE: u32 = 500_000;

/// The serial speed of a serial SLCAN adapter when --baud is not given (USB adapters such as a
/// CANable ignore it).
pub const DEFAULT_SLCAN_BAUD: u32 = 115_200;

/// A parsed `--can` value.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum CanSpec {
    /// A Linux kernel CAN interface (`can0`, `vcan0`).
    SocketCan(String),
    /// A serial SLCAN adapter (`/dev/ttyACM0`).
    SlcanSerial(String),
    /// SLCAN over TCP, HOST:PORT.
    SlcanTcp(String),
    /// A process speaking candump lines on its stdio.
    CandumpExec(String),
    /// candump lines on this process's own stdin/stdout (the simulator only).
    CandumpStdio,
}

impl CanSpec {
    /// Parses `--can TEXT`; `forms` names the accepted forms in the error.
    pub fn parse(text: &str, forms: &str) -> Result<Self, CliError> {
        let usage = || CliError::Usage(format!("--can {text}: expected {forms}"));
        if let Some(iface) = text.strip_prefix("socketcan:") {
            let valid = !iface.is_empty()
                && iface.len() < 16
                && iface
                    .bytes()
                    .all(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'-' || b == b'.');
            return valid
                .then(|| Self::SocketCan(iface.into()))
                .ok_or_else(usage);
        }
        if let Some(target) = text.strip_prefix("slcan:") {
            if target.starts_with('/') {
                return Ok(Self::SlcanSerial(target.into()));
            }
            return match target.rsplit_once(':') {
                Some((host, port)) if !host.is_empty() && port.parse::<u16>().is_ok() => {
                    Ok(Self::SlcanTcp(target.into()))
                }
                _ => Err(usage()),
            };
        }
        if let Some(command) = text.strip_prefix("candump:exec:") {
            if command.trim().is_empty() {
                return Err(CliError::Usage("candump:exec: needs a command".into()));
            }
            return Ok(Self::CandumpExec(command.into()));
        }
        if text == "candump:stdio" {
            return Ok(Self::CandumpStdio);
        }
        Err(usage())
    }
}

/// Parses a `--bitrate`: bits per second, or with a `k` / `M` suffix (`500k`, `1M`); one of
/// the SLCAN rates 10k, 20k, 50k, 100k, 125k, 250k, 500k, 800k, 1M.
pub fn parse_bitrate(text: &str) -> Result<u32, String> {
    let lower = text.trim().to_ascii_lowercase();
    let (number, factor) = if let Some(n) = lower.strip_suffix('k') {
        (n, 1_000.0)
    } else if let Some(n) = lower.strip_suffix('m') {
        (n, 1_000_000.0)
    } else {
        (lower.as_str(), 1.0)
    };
    let bits = number
        .parse::<f64>()
        .ok()
        .map(|n| n * factor)
        .filter(|b| b.fract() == 0.0 && *b > 0.0 && *b <= f64::from(u32::MAX))
        .map(|b| b as u32);
    match bits.and_then(Bitrate::from_bits_per_second) {
        Some(rate) => Ok(rate.bits_per_second()),
        None => {
            Err("expected one of 10k, 20k, 50k, 100k, 125k, 250k, 500k, 800k, 1M (bit/s)".into())
        }
    }
}

/// The CAN bit rate a description documents as the drive's default: the default of a CANopen
/// parameter whose enumeration names bit rates (`kbit_1000`, `k500`).
pub fn described_bitrate(device: &Device) -> Option<u32> {
    device.parameters.iter().find_map(|parameter| {
        if parameter.canopen.is_empty() {
            return None;
        }
        let name = parameter.enumeration.as_deref()?;
        let enumeration = device.enums.iter().find(|e| e.name == name)?;
        let rates: Vec<(i64, u32)> = enumeration
            .values
            .iter()
            .map(|v| Some((v.value, kbit(&v.name)? * 1000)))
            .collect::<Option<_>>()?;
        let default = match parameter.default? {
            drivebus::interpret::Number::Int(i) => i,
            drivebus::interpret::Number::Float(_) => return None,
        };
        rates
            .iter()
            .find(|(value, _)| *value == default)
            .map(|(_, bits)| *bits)
    })
}

/// `kbit_1000` / `k500` → 1000 / 500.
fn kbit(name: &str) -> Option<u32> {
    let digits = name
        .strip_prefix("kbit_")
        .or_else(|| name.strip_prefix("kbit"))
        .or_else(|| name.strip_prefix('k'))?;
    digits.parse().ok()
}

/// The bit rate to use: `--bitrate`, else the one the descriptions agree on, else 500 kbit/s.
pub fn bitrate(given: Option<u32>, devices: &[&Device]) -> u32 {
    given.unwrap_or_else(|| {
        let mut described: Vec<u32> = devices
            .iter()
            .filter_map(|d| described_bitrate(d))
            .collect();
        described.sort_unstable();
        described.dedup();
        match described[..] {
            [one] => one,
            _ => DEFAULT_BITRATE,
        }
    })
}

/// Settings of the link to the bus.
#[derive(Debug, Clone, Copy)]
pub struct CanSettings {
    /// CAN bit rate in bit/s (SLCAN sets it; SocketCAN's is the interface's, named in hints).
    pub bitrate: u32,
    /// Serial speed of a serial SLCAN adapter.
    pub baud: u32,
}

/// A typed failure to open `spec`.
fn open_error(spec: &str, settings: CanSettings, error: OpenError) -> CliError {
    CliError::CanOpen {
        spec: spec.into(),
        bitrate: settings.bitrate,
        error,
    }
}

/// Opens the backend `spec` names (not `candump:stdio`); a relay process is returned for the
/// caller to stop.
pub fn open(
    text: &str,
    spec: &CanSpec,
    settings: CanSettings,
) -> Result<(Box<dyn CanBus + Send>, Option<Child>), CliError> {
    let rate = Bitrate::from_bits_per_second(settings.bitrate).ok_or_else(|| {
        CliError::Usage(format!("--bitrate {}: not an SLCAN rate", settings.bitrate))
    })?;
    match spec {
        CanSpec::SocketCan(iface) => open_socketcan(text, iface, settings),
        CanSpec::SlcanSerial(path) => {
            let mut bus =
                SlcanBus::serial(path, settings.baud).map_err(|e| open_error(text, settings, e))?;
            bus.start(rate, ANSWER_TIMEOUT)
                .map_err(|e| open_error(text, settings, e))?;
            Ok((Box::new(bus), None))
        }
        CanSpec::SlcanTcp(addr) => {
            let mut bus = SlcanBus::connect(addr.as_str())
                .map_err(|e| CliError::Io(format!("cannot open {text}: {e}")))?;
            // A TCP gateway may not answer commands: they are sent, not awaited.
            bus.open(rate)
                .map_err(|e| CliError::Io(format!("cannot open {text}: {e}")))?;
            Ok((Box::new(bus), None))
        }
        CanSpec::CandumpExec(command) => {
            let mut words = command.split_whitespace();
            let program = words
                .next()
                .ok_or_else(|| CliError::Usage("candump:exec: needs a command".into()))?;
            let mut command_line = Command::new(program);
            command_line
                .args(words)
                .stdin(Stdio::piped())
                .stdout(Stdio::piped())
                .stderr(Stdio::inherit());
            // Its own process group: a Ctrl-C at the terminal reaches the CLI only, which still
            // needs the relay to restore what it changed on the drive (`watch --pdo`) before it
            // stops the relay.
            #[cfg(unix)]
            std::os::unix::process::CommandExt::process_group(&mut command_line, 0);
            let mut child = command_line
                .spawn()
                .map_err(|e| CliError::Io(format!("cannot start `{command}`: {e}")))?;
            let bus = CandumpBus::from_child(&mut child)
                .map_err(|e| CliError::Io(format!("cannot open {text}: {e}")))?;
            Ok((Box::new(bus), Some(child)))
        }
        CanSpec::CandumpStdio => Err(CliError::Usage(format!(
            "--can candump:stdio is for `drivegen sim`; expected {FORMS}"
        ))),
    }
}

#[cfg(target_os = "linux")]
fn open_socketcan(
    text: &str,
    iface: &str,
    settings: CanSettings,
) -> Result<(Box<dyn CanBus + Send>, Option<Child>), CliError> {
    let bus = drivebus::canopen::can::socketcan::SocketCanBus::open(iface)
        .map_err(|e| open_error(text, settings, e))?;
    Ok((Box::new(bus), None))
}

#[cfg(not(target_os = "linux"))]
fn open_socketcan(
    text: &str,
    _iface: &str,
    _settings: CanSettings,
) -> Result<(Box<dyn CanBus + Send>, Option<Child>), CliError> {
    Err(CliError::Usage(format!(
        "--can {text}: SocketCAN exists on Linux only; use an SLCAN adapter (slcan:PORT)"
    )))
}

/// The message of a failure to open `spec`: the library's, with the bit rate of the command
/// in the `ip link` hint.
pub fn describe(spec: &str, bitrate: u32, error: &OpenError) -> String {
    use drivebus::canopen::can::bring_up;
    match error {
        OpenError::NoInterface { name } => format!(
            "no CAN interface {name}; bring it up with `{}`",
            bring_up(name, bitrate)
        ),
        OpenError::InterfaceDown { name } => format!(
            "CAN interface {name} is down; bring it up with `{}`",
            bring_up(name, bitrate)
        ),
        other => format!("cannot open {spec}: {other}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_form_parses_and_others_are_refused() {
        let forms = FORMS;
        assert_eq!(
            CanSpec::parse("socketcan:can0", forms).unwrap(),
            CanSpec::SocketCan("can0".into())
        );
        assert_eq!(
            CanSpec::parse("slcan:/dev/ttyACM0", forms).unwrap(),
            CanSpec::SlcanSerial("/dev/ttyACM0".into())
        );
        assert_eq!(
            CanSpec::parse("slcan:127.0.0.1:2000", forms).unwrap(),
            CanSpec::SlcanTcp("127.0.0.1:2000".into())
        );
        assert_eq!(
            CanSpec::parse("candump:exec:relay --x", forms).unwrap(),
            CanSpec::CandumpExec("relay --x".into())
        );
        for bad in [
            "socketcan:",
            "socketcan:a/b",
            "socketcan:waytoolonginterface0",
            "slcan:ttyACM0",
            "slcan:host:port",
            "pcan:usb1",
            "candump:exec: ",
        ] {
            assert!(
                matches!(CanSpec::parse(bad, forms), Err(CliError::Usage(_))),
                "{bad}"
            );
        }
    }

    #[test]
    fn the_default_bit_rate_is_the_one_the_descriptions_document() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../descriptions");
        let load = |name: &str| crate::commands::load(&root.join(name)).unwrap();
        let (swd, kinco, lafert) = (
            load("ezwheel-swd"),
            load("kinco-fd"),
            load("lafert-smartris"),
        );
        // SWD 2100h: default 0 = kbit_1000; Kinco 2F81h: default 50 = k500.
        assert_eq!(described_bitrate(&swd), Some(1_000_000));
        assert_eq!(described_bitrate(&kinco), Some(500_000));
        assert_eq!(bitrate(None, &[&swd]), 1_000_000);
        assert_eq!(
            bitrate(None, &[&swd, &swd]),
            1_000_000,
            "two nodes of one drive"
        );
        assert_eq!(
            bitrate(None, &[&swd, &kinco]),
            DEFAULT_BITRATE,
            "they disagree"
        );
        assert_eq!(bitrate(Some(250_000), &[&swd]), 250_000);
        assert_eq!(bitrate(None, &[]), DEFAULT_BITRATE);
        let _ = bitrate(None, &[&lafert]);
    }

    #[test]
    fn bitrates_are_the_slcan_ones() {
        assert_eq!(parse_bitrate("500k"), Ok(500_000));
        assert_eq!(parse_bitrate("1M"), Ok(1_000_000));
        assert_eq!(parse_bitrate("125000"), Ok(125_000));
        assert_eq!(parse_bitrate("10K"), Ok(10_000));
        assert_eq!(parse_bitrate("0.8m"), Ok(800_000));
        for bad in ["333k", "2M", "", "k", "-500k", "1e9", "NaN"] {
            assert!(parse_bitrate(bad).is_err(), "{bad}");
        }
    }
}
