//! `drivegen gateway CONFIG.toml`: the drives a gateway file names, polled on their buses and
//! published to an MQTT broker, with writes from MQTT clients through the checks of `drivegen
//! write` (docs/gateway.md).
//!
//! A thread per connection owns its blocking sessions (the bus I/O): drives on one serial line
//! or CAN bus share one, each polled at its own interval. The MQTT side runs on a tokio
//! runtime, a task per drive with its own connection so each drive has its own last will. The
//! two meet through channels only, so no bus call ever blocks the runtime.

mod connection;
mod exposed;
mod lines;
mod mqtt;
mod payload;
mod pdo;
mod poller;

use std::path::PathBuf;

use tokio::sync::watch;

use crate::error::CliError;

/// Arguments of `gateway`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The gateway file (docs/gateway.md): the broker, and each drive with its description,
    /// bus, parameters and the parameters clients may write.
    config: PathBuf,
}

/// Checks the whole file (descriptions, parameters, bus options) before any bus or broker is
/// opened, then serves until SIGINT or SIGTERM, when each drive's status goes offline.
pub fn run(args: Args) -> Result<(), CliError> {
    let gateway = exposed::Gateway::load(&args.config)?;
    let password = gateway.password()?;
    init_logging();
    // TLS through rustls on ring: the one provider compiled in, installed for the process.
    let _ = rustls::crypto::ring::default_provider().install_default();
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .map_err(|e| CliError::Io(format!("cannot start the gateway's runtime: {e}")))?;
    let (stop, stopped) = watch::channel(false);
    std::thread::scope(|scope| {
        let mut tasks = Vec::new();
        for line in &gateway.lines {
            let (forwarded, line_requests) = std::sync::mpsc::channel();
            let mut served = Vec::new();
            for (slot, &index) in line.iter().enumerate() {
                let drive = &gateway.drives[index];
                let (requests, pending) = std::sync::mpsc::channel();
                let (reports, latest) = watch::channel(poller::Report::Starting);
                let forwarded = forwarded.clone();
                scope.spawn(move || poller::forward(slot, &pending, &forwarded));
                served.push(poller::Served::new(drive, reports));
                tasks.push(mqtt::DriveTask {
                    topics: mqtt::Topics::new(&gateway.mqtt.topic_prefix, &drive.name),
                    writable: drive.writable_names(gateway.read_only),
                    publish_every_poll: drive.publish_every_poll,
                    parameters: drive.parameters.len(),
                    latest,
                    requests,
                    stop: stopped.clone(),
                });
            }
            // The poller's requests end when every drive's forwarder has ended.
            drop(forwarded);
            let connection = connection::Connection::new(&gateway.drives[line[0]], line.len() > 1);
            let poll_stop = stopped.clone();
            scope.spawn(move || poller::run(connection, served, &line_requests, &poll_stop));
        }
        // The pollers see the stop (or their dropped request channels) at their next wait and
        // end; the forwarders end with the MQTT tasks' request senders; the scope joins them.
        runtime.block_on(mqtt::serve(&gateway, password, tasks, stop))
    })
}

/// Log lines on standard error, info and above.
fn init_logging() {
    let _ = tracing_subscriber::fmt()
        .with_writer(std::io::stderr)
        .with_target(false)
        .try_init();
}
