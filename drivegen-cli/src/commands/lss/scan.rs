//! `drivegen lss scan`: Fastscan until no node without a node id is left. Without `--assign`
//! each node found stays in LSS configuration state, where Fastscan no longer finds it, so the
//! next scan finds the next one; all are switched back to waiting state at the end. With
//! `--assign FIRST` each gets node id FIRST, FIRST+1, ... as it is found, and boots up at it.

use std::time::Duration;

use drivebus::canopen::client::lss::BlockingLss;
use drivebus::canopen::lss::{LssAddress, LssError, LssMode, NewNodeId};
use drivegen::ir::Device;

use crate::connect::DynCan;

/// Arguments of `lss scan`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Give the nodes found node ids from FIRST up (1-127).
    #[arg(long, value_name = "FIRST")]
    pub(super) assign: Option<u8>,
    /// With --assign: store each node id, so it survives a power cycle.
    #[arg(long)]
    store: bool,
    /// How long each of the 133 Fastscan steps per node waits for answers, in milliseconds.
    #[arg(long, default_value_t = 20)]
    step_ms: u64,
    /// Print one JSON object per node.
    #[arg(long)]
    json: bool,
}

/// Scans, prints each node found, and assigns ids if asked.
pub fn run(args: &Args, lss: &mut BlockingLss<DynCan>, devices: &[Device]) -> Result<(), LssError> {
    // One "identify non-configured slaves" first, waiting the whole --timeout-ms: it tells
    // whether there is anything to scan for, and lets a node that is still starting (a
    // simulator behind candump:exec) answer before the short Fastscan steps begin.
    let waiting = lss.identify_non_configured()?;
    if waiting == 0 {
        eprintln!("no node without a node id answered");
        return Ok(());
    }
    eprintln!("{waiting} node(s) without a node id answered; Fastscan ...");
    let mut next = args.assign;
    let mut found = 0usize;
    let result = loop {
        let address = match lss.fastscan() {
            Ok(Some(address)) => address,
            Ok(None) => break Ok(()),
            Err(e) => break Err(e),
        };
        found += 1;
        let assigned = next;
        if let Some(id) = assigned {
            if let Err(e) = assign(lss, id, args.store) {
                break Err(e);
            }
            next = Some(id.saturating_add(1));
        }
        print(args.json, &address, assigned, devices);
    };
    let back = lss.switch_global(LssMode::Waiting);
    if found < waiting && result.is_ok() {
        eprintln!("Fastscan found {found} of them: try a longer --step-ms");
    }
    result.and(back)
}

impl Args {
    /// How long each Fastscan step waits.
    pub fn step(&self) -> Duration {
        Duration::from_millis(self.step_ms)
    }
}

/// Gives the node in configuration state node id `id`, stores it if asked, and lets it boot up.
fn assign(lss: &mut BlockingLss<DynCan>, id: u8, store: bool) -> Result<(), LssError> {
    // Checked before anything is sent: past 127 the nodes found are left without an id.
    NewNodeId::new(id)?;
    lss.configure_node_id(id)?;
    if store {
        lss.store()?;
    }
    lss.switch_global(LssMode::Waiting)
}

fn print(json: bool, address: &LssAddress, assigned: Option<u8>, devices: &[Device]) {
    if json {
        let matches = super::super::scan::canopen::matching_identity(
            devices,
            Some(address.vendor_id),
            Some(address.product_code),
            Some(address.revision),
        );
        let value = serde_json::json!({
            "vendor_id": address.vendor_id,
            "product_code": address.product_code,
            "revision": address.revision,
            "serial": address.serial,
            "node": assigned,
            "matches": super::super::scan::names(&matches),
        });
        println!("{value}");
    } else {
        println!("{}", describe(address, assigned, devices));
    }
}

/// One line: the LSS address, the node id (if known) and the descriptions that cover it.
pub fn describe(address: &LssAddress, node: Option<u8>, devices: &[Device]) -> String {
    let matches = super::super::scan::canopen::matching_identity(
        devices,
        Some(address.vendor_id),
        Some(address.product_code),
        Some(address.revision),
    );
    let node = match node {
        Some(0xFF) => "no node id".to_string(),
        Some(id) => format!("node {id:3}"),
        None => "no node id".to_string(),
    };
    format!(
        "{node}: vendor-ID {:#010x}, product code {:#010x}, revision {:#010x}, serial {:#010x}: {}",
        address.vendor_id,
        address.product_code,
        address.revision,
        address.serial,
        super::super::scan::verdict(&matches)
    )
}
