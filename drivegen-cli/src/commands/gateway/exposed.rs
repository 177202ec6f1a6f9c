//! A gateway file resolved against the descriptions it names: each drive's description loaded,
//! its parameters found, its writable ones writable, its bus options read the way the command
//! line reads them. Everything is checked here, before a bus or the broker is opened.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use clap::Parser;
use drivegen::gateway_file::{self, BusOption, DriveEntry, MqttEntry, Named, OpcUaEntry, PdoUse};
use drivegen::ir::{Device, Parameter};

use super::lines::Line;
use crate::connect::BusArgs;
use crate::error::CliError;

/// The gateway a file describes.
pub struct Gateway {
    /// The broker, unless the file serves OPC UA alone.
    pub mqtt: Option<MqttEntry>,
    /// The OPC UA endpoint, when the file has one (refused at load without the feature).
    #[cfg_attr(not(feature = "opcua"), allow(dead_code))]
    pub opcua: Option<OpcUaEntry>,
    /// The folder of the file, which its relative paths start from.
    #[cfg_attr(not(feature = "opcua"), allow(dead_code))]
    pub folder: PathBuf,
    /// TLS to the broker: the PEM files the file names, read.
    pub tls: Option<Tls>,
    /// Every write refused.
    pub read_only: bool,
    /// The drives, in the file's order.
    pub drives: Vec<Drive>,
    /// The connections the drives go through: drives on one serial line or CAN bus share one.
    pub lines: Vec<Line>,
}

/// TLS to the broker, its PEM files read at load.
pub struct Tls {
    /// The CA that signed the broker's certificate.
    pub ca: Vec<u8>,
    /// The gateway's certificate and key, when the broker asks for one.
    pub client: Option<(Vec<u8>, Vec<u8>)>,
}

/// One drive the gateway exposes.
pub struct Drive {
    /// Its topic level.
    pub name: String,
    /// Its description, shared with the other drives the same file describes (100 drives of
    /// one family hold one copy).
    pub device: Arc<Device>,
    /// How to reach it.
    pub bus: BusArgs,
    /// Milliseconds between polls.
    pub interval_ms: u32,
    /// Publish every poll rather than changes only.
    pub publish_every_poll: bool,
    /// The names of the parameters published, each in the description.
    pub parameters: Vec<String>,
    /// The names of the parameters clients may write, each writable in the description.
    pub writable: Vec<String>,
    /// CANopen: its values by TPDO where they can be, at SYNC or by event timer (`pdo`).
    pub pdo: PdoUse,
    /// With `pdo`: NMT Start before, Enter Pre-Operational after.
    pub pdo_start: bool,
    /// The line of its `[[drive]]` in the file (1-based), for refusals.
    pub line: u32,
}

/// The bus options alone, read by the command line's own parser.
#[derive(Parser)]
#[command(no_binary_name = true)]
struct BusOnly {
    #[command(flatten)]
    bus: BusArgs,
}

impl Gateway {
    /// Reads `path` and resolves every drive; the first problem is refused with the file, line
    /// and reason.
    pub fn load(path: &Path) -> Result<Self, CliError> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| CliError::Io(format!("cannot read {}: {e}", path.display())))?;
        let at = |line: Option<u32>| match line {
            Some(line) => format!("{}:{line}", path.display()),
            None => path.display().to_string(),
        };
        let file = gateway_file::parse(&text)
            .map_err(|e| CliError::Invalid(format!("{}: {}", at(e.line), e.kind_text())))?;
        let folder = path.parent().unwrap_or(Path::new("."));
        let mut loaded = Descriptions::default();
        let drives = file
            .drives
            .iter()
            .map(|entry| {
                Drive::resolve(entry, folder, &mut loaded)
                    .map_err(|(line, why)| CliError::Invalid(format!("{}: {why}", at(Some(line)))))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let lines = super::lines::lines(&drives)
            .map_err(|(line, why)| CliError::Invalid(format!("{}: {why}", at(Some(line)))))?;
        let read = |name: &str| {
            let path = folder.join(name);
            std::fs::read(&path).map_err(|e| {
                CliError::Io(format!("{}: cannot read {}: {e}", at(None), path.display()))
            })
        };
        if let Some(opcua) = &file.opcua {
            if !cfg!(feature = "opcua") {
                return Err(CliError::Invalid(format!(
                    "{}: [opcua] needs a drivegen built with the `opcua` feature \
                     (cargo install drivegen-cli --features opcua)",
                    at(Some(opcua.line))
                )));
            }
        }
        let tls = match file.mqtt.as_ref().and_then(|mqtt| mqtt.tls.as_ref()) {
            None => None,
            Some(entry) => Some(Tls {
                ca: read(&entry.ca_file)?,
                client: match &entry.client {
                    None => None,
                    Some((cert, key)) => Some((read(cert)?, read(key)?)),
                },
            }),
        };
        Ok(Self {
            mqtt: file.mqtt,
            opcua: file.opcua,
            folder: folder.to_path_buf(),
            tls,
            read_only: file.read_only,
            drives,
            lines,
        })
    }

    /// The broker password, from the environment variable the file names.
    pub fn password(&self) -> Result<Option<String>, CliError> {
        let Some(variable) = self.mqtt.as_ref().and_then(|m| m.password_env.as_ref()) else {
            return Ok(None);
        };
        std::env::var(variable).map(Some).map_err(|_| {
            CliError::Usage(format!(
                "the gateway file's `password_env` names {variable}, which is not set"
            ))
        })
    }
}

/// Why the file is refused, and the line to point at.
pub type Refusal = (u32, String);

/// The descriptions loaded so far, by path: each loaded and checked once.
type Descriptions = BTreeMap<PathBuf, Arc<Device>>;

impl Drive {
    fn resolve(
        entry: &DriveEntry,
        folder: &Path,
        loaded: &mut Descriptions,
    ) -> Result<Self, Refusal> {
        let path = folder.join(&entry.description);
        let device = match loaded.get(&path) {
            Some(device) => Arc::clone(device),
            None => {
                let device = super::super::load(&path)
                    .map_err(|e| (entry.line, format!("drive `{}`: {e}", entry.name)))?;
                Arc::clone(loaded.entry(path).or_insert(Arc::new(device)))
            }
        };
        let parameters = names(&device, &entry.parameters, |_| None)?;
        let writable = names(&device, &entry.writable, |p| {
            (!writable(p)).then(|| format!("`{}` is read-only in its description", p.name))
        })?;
        let bus = bus_args(&entry.bus, entry.line)?;
        if entry.pdo.on() && bus.can.is_none() {
            let why = "pdo: PDOs are CANopen's; name a `can` bus or leave `pdo` out";
            return Err((entry.line, format!("drive `{}`: {why}", entry.name)));
        }
        Ok(Self {
            name: entry.name.clone(),
            bus,
            device,
            interval_ms: entry.interval_ms,
            publish_every_poll: entry.publish_every_poll,
            parameters,
            writable,
            pdo: entry.pdo,
            pdo_start: entry.pdo_start,
            line: entry.line,
        })
    }

    /// The names clients may write: none when the whole gateway is read-only.
    pub fn writable_names(&self, read_only: bool) -> BTreeSet<String> {
        match read_only {
            true => BTreeSet::new(),
            false => self.writable.iter().cloned().collect(),
        }
    }

    /// The parameter called `name` (every name here was found in the description at load).
    pub fn parameter(&self, name: &str) -> Option<&Parameter> {
        self.device.parameter(name)
    }
}

/// The names, each found in `device` and passing `refuse`.
fn names(
    device: &Device,
    named: &[Named],
    refuse: impl Fn(&Parameter) -> Option<String>,
) -> Result<Vec<String>, Refusal> {
    named
        .iter()
        .map(|n| {
            let parameter =
                super::super::parameter(device, &n.name).map_err(|e| (n.line, e.to_string()))?;
            match refuse(parameter) {
                Some(why) => Err((n.line, why)),
                None => Ok(n.name.clone()),
            }
        })
        .collect()
}

/// Whether some protocol address of `parameter` takes writes.
fn writable(parameter: &Parameter) -> bool {
    let addresses = parameter.modbus.iter().map(|a| a.access.write);
    let canopen = parameter.canopen.iter().map(|a| a.access.write);
    let rs232 = parameter.rs232.iter().map(|a| a.access.write);
    addresses.chain(canopen).chain(rs232).any(|w| w)
}

/// The bus options as the command line would take them: `modbus_tcp = "H:P"` is
/// `--modbus-tcp H:P`, `rs232_loop = true` is `--rs232-loop`. A refusal points at the `bus`
/// table (else at the drive's `line`).
fn bus_args(options: &[BusOption], line: u32) -> Result<BusArgs, Refusal> {
    let line = options.first().map_or(line, |o| o.line);
    let mut argv = Vec::new();
    for option in options {
        argv.push(format!("--{}", option.name.replace('_', "-")));
        argv.extend(option.value.clone());
    }
    let parsed = BusOnly::try_parse_from(&argv).map_err(|e| {
        let why = e.to_string();
        let first = why
            .lines()
            .next()
            .unwrap_or("")
            .trim_start_matches("error: ");
        (line, format!("bus: {first}"))
    })?;
    let bus = parsed.bus;
    if bus.unit.len() > 1 || bus.node_id.len() > 1 {
        return Err((line, "bus: one drive per [[drive]]".into()));
    }
    let named = [&bus.modbus_tcp, &bus.serial, &bus.can, &bus.kinco_rs232];
    if named.iter().all(|b| b.is_none()) {
        return Err((
            line,
            "bus: name one of modbus_tcp, serial, can or kinco_rs232".into(),
        ));
    }
    Ok(bus)
}
