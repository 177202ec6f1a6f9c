//! `drivegen safety signature`: the safety configuration signature (13FFh) of an SRDO the
//! description declares, with the configuration changes the user is about to write.

use std::path::{Path, PathBuf};

use drivebus::canopen::pdo::MappedObject;
use drivebus::canopen::srdo::{signature, SrdoCommunication, SrdoConfig, SrdoDirection};
use drivegen::ir::{Device, Mapping, SrdoDefaults};

use crate::error::CliError;

/// Arguments of `safety`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(subcommand)]
    action: Action,
}

#[derive(Debug, clap::Subcommand)]
enum Action {
    /// Print the signature of an SRDO's configuration, as 13FFh sub N must hold it.
    Signature(SignatureArgs),
}

/// Arguments of `safety signature`.
#[derive(Debug, clap::Args)]
struct SignatureArgs {
    /// Description file, or a folder with a device.toml.
    description: PathBuf,
    /// SRDO number (a `[[srdo]]` of the description).
    #[arg(long)]
    srdo: u8,
    /// Node-ID for node-relative COB-IDs; the description's default node-ID if omitted.
    #[arg(long, value_parser = parse_int::<u8>)]
    node_id: Option<u8>,
    /// Change a value before signing: `direction` (0/1/2, invalid/tx/rx), `sct_ms`, `srvt_ms`,
    /// `cob_id_normal`, `cob_id_inverted`, `entry.K` (mapping sub-index K, as
    /// index << 16 | sub << 8 | bits), or a parameter of the SRDO's communication or mapping
    /// object by name. Repeatable.
    #[arg(long = "set", value_name = "NAME=VALUE")]
    set: Vec<String>,
    /// Print JSON: the signature and the configuration it signs.
    #[arg(long)]
    json: bool,
}

/// Runs `safety signature`.
pub fn run(args: Args) -> Result<(), CliError> {
    match args.action {
        Action::Signature(args) => print_signature(&args),
    }
}

/// The configuration being signed, owned.
struct Configuration {
    number: u8,
    communication: SrdoCommunication,
    mapping: Vec<MappedObject>,
}

fn print_signature(args: &SignatureArgs) -> Result<(), CliError> {
    let device = super::load(&args.description)?;
    let (srdo, srdo_defaults) = find(&device, args.srdo, &args.description)?;
    let node_id = args
        .node_id
        .or(device.canopen.as_ref().map(|c| c.default_node_id));
    let mut config = defaults(&device, srdo, srdo_defaults, node_id)?;
    for assignment in &args.set {
        apply(&device, &mut config, assignment)?;
    }
    let value = signature(&SrdoConfig {
        number: config.number,
        communication: config.communication,
        mapping: &config.mapping,
    })
    .map_err(|e| CliError::Invalid(format!("SRDO {}: {e}", config.number)))?;
    if args.json {
        println!("{}", json(srdo, node_id, &config, value));
    } else {
        println!("{value:#06X}");
    }
    Ok(())
}

fn find<'a>(
    device: &'a Device,
    number: u8,
    path: &Path,
) -> Result<(&'a Mapping, &'a SrdoDefaults), CliError> {
    device
        .srdos()
        .find(|(_, s)| s.number == number)
        .ok_or_else(|| {
            let declared: Vec<String> = device.srdos().map(|(_, s)| s.number.to_string()).collect();
            CliError::Usage(format!(
                "{} declares no SRDO {number} (declared: {})",
                path.display(),
                if declared.is_empty() {
                    "none".into()
                } else {
                    declared.join(", ")
                }
            ))
        })
}

fn defaults(
    device: &Device,
    srdo: &Mapping,
    defaults: &SrdoDefaults,
    node_id: Option<u8>,
) -> Result<Configuration, CliError> {
    let [normal, inverted] = defaults.cob_ids.map(|c| c.resolve(node_id));
    let (Some(cob_id_normal), Some(cob_id_inverted)) = (normal, inverted) else {
        return Err(CliError::Usage(format!(
            "SRDO {} has node-relative COB-IDs: give --node-id",
            defaults.number
        )));
    };
    let mapping = srdo.mapped_objects(device).ok_or_else(|| {
        CliError::Invalid(format!("SRDO {} maps unknown objects", defaults.number))
    })?;
    let direction = SrdoDirection::from_u8(srdo.information_direction())
        .expect("information_direction is 0, 1 or 2");
    Ok(Configuration {
        number: defaults.number,
        communication: SrdoCommunication {
            direction,
            sct_ms: defaults.sct_ms,
            srvt_ms: defaults.srvt_ms,
            transmission_type: srdo.transmission_type.unwrap_or(0xFE),
            cob_id_normal,
            cob_id_inverted,
        },
        mapping,
    })
}

/// A `--set` target: a communication sub-index or a mapping sub-index.
enum Target {
    Communication(u8),
    Mapping(u8),
}

fn target(device: &Device, number: u8, name: &str) -> Result<Target, CliError> {
    let communication = match name {
        "direction" => Some(1),
        "sct_ms" => Some(2),
        "srvt_ms" => Some(3),
        "transmission_type" => Some(4),
        "cob_id_normal" => Some(5),
        "cob_id_inverted" => Some(6),
        _ => None,
    };
    if let Some(sub) = communication {
        return Ok(Target::Communication(sub));
    }
    if let Some(k) = name.strip_prefix("entry.") {
        let k = parse_int::<u8>(k).map_err(CliError::Usage)?;
        return Ok(Target::Mapping(k));
    }
    let object = super::parameter(device, name)?
        .pdo_object()
        .ok_or_else(|| CliError::NoAccess(format!("`{name}` has no CANopen object")))?;
    match object.index {
        i if i == 0x1300 + u16::from(number) => Ok(Target::Communication(object.subindex)),
        i if i == 0x1380 + u16::from(number) => Ok(Target::Mapping(object.subindex)),
        _ => Err(CliError::Usage(format!(
            "`{name}` (0x{:04X}:{:02X}) is not in SRDO {number}'s communication or mapping object",
            object.index, object.subindex
        ))),
    }
}

fn apply(device: &Device, config: &mut Configuration, assignment: &str) -> Result<(), CliError> {
    let (name, text) = assignment
        .split_once('=')
        .ok_or_else(|| CliError::Usage(format!("--set `{assignment}`: expected NAME=VALUE")))?;
    let (name, text) = (name.trim(), text.trim());
    let c = &mut config.communication;
    let bad = |what: &str| CliError::Usage(format!("--set {name}={text}: {what}"));
    match target(device, config.number, name)? {
        Target::Communication(1) => {
            c.direction =
                direction(text).ok_or_else(|| bad("direction is 0/invalid, 1/tx or 2/rx"))?
        }
        Target::Communication(2) => c.sct_ms = parse_int(text).map_err(|e| bad(&e))?,
        Target::Communication(3) => c.srvt_ms = parse_int(text).map_err(|e| bad(&e))?,
        Target::Communication(4) => c.transmission_type = parse_int(text).map_err(|e| bad(&e))?,
        Target::Communication(5) => c.cob_id_normal = parse_int(text).map_err(|e| bad(&e))?,
        Target::Communication(6) => c.cob_id_inverted = parse_int(text).map_err(|e| bad(&e))?,
        Target::Communication(_) => return Err(bad("not a signed communication sub-index")),
        Target::Mapping(k) => {
            let entry: u32 = parse_int(text).map_err(|e| bad(&e))?;
            let slot = usize::from(k)
                .checked_sub(1)
                .and_then(|i| config.mapping.get_mut(i))
                .ok_or_else(|| bad("no such mapping sub-index"))?;
            *slot = MappedObject::from_entry(entry);
        }
    }
    Ok(())
}

fn direction(text: &str) -> Option<SrdoDirection> {
    match text {
        "invalid" => Some(SrdoDirection::Invalid),
        "tx" => Some(SrdoDirection::Transmit),
        "rx" => Some(SrdoDirection::Receive),
        number => SrdoDirection::from_u8(parse_int(number).ok()?),
    }
}

/// A decimal or `0x` hexadecimal integer.
fn parse_int<T: TryFrom<u64>>(text: &str) -> Result<T, String> {
    let value = match text.strip_prefix("0x").or_else(|| text.strip_prefix("0X")) {
        Some(hex) => u64::from_str_radix(&hex.replace('_', ""), 16),
        None => text.replace('_', "").parse(),
    }
    .map_err(|_| format!("`{text}` is not an integer"))?;
    T::try_from(value).map_err(|_| format!("`{text}` is out of range"))
}

fn json(srdo: &Mapping, node_id: Option<u8>, config: &Configuration, value: u16) -> String {
    let c = &config.communication;
    let mapping: Vec<String> = config
        .mapping
        .iter()
        .map(|m| format!("0x{:08X}", m.entry()))
        .collect();
    serde_json::to_string_pretty(&serde_json::json!({
        "srdo": config.number,
        "name": srdo.name,
        "node_id": node_id,
        "signature": format!("{value:#06X}"),
        "signature_value": value,
        "configuration": {
            "direction": c.direction as u8,
            "sct_ms": c.sct_ms,
            "srvt_ms": c.srvt_ms,
            "cob_id_normal": c.cob_id_normal,
            "cob_id_inverted": c.cob_id_inverted,
            "mapping": mapping,
        },
    }))
    .expect("a JSON value serializes")
}
