//! `drivegen gateway CONFIG.toml`: the drives a gateway file names, polled on their buses and
//! published to an MQTT broker and/or served on an OPC UA endpoint (feature `opcua`), with
//! writes from clients through the checks of `drivegen write` (docs/gateway.md).
//!
//! A thread per connection owns its blocking sessions (the bus I/O): drives on one serial line
//! or CAN bus share one, each polled at its own interval. The MQTT side runs on a tokio
//! runtime, a task per drive with its own connection so each drive has its own last will; the
//! OPC UA server runs on a thread and runtime of its own. They meet the pollers through
//! channels only, so no bus call ever blocks a runtime.

mod connection;
mod exposed;
mod lines;
mod mqtt;
#[cfg(feature = "opcua")]
mod opcua;
mod payload;
mod pdo;
mod pdo_bus;
mod poller;
mod refusal;
mod signals;

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
/// opened, then serves until SIGINT or SIGTERM, when each drive's status goes offline and each
/// poller puts back what it changed on its drives (a further signal meanwhile is logged and
/// does not cut that short: [`signals`]).
pub fn run(args: Args) -> Result<(), CliError> {
    let gateway = exposed::Gateway::load(&args.config)?;
    let password = gateway.password()?;
    #[cfg(feature = "opcua")]
    let endpoint = opcua::Endpoint::prepare(&gateway)?;
    init_logging();
    // TLS through rustls on ring: the one provider compiled in, installed for the process.
    let _ = rustls::crypto::ring::default_provider().install_default();
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .map_err(|e| CliError::Io(format!("cannot start the gateway's runtime: {e}")))?;
    // Caught before any bus opens: a signal never finds a drive's TPDO changed and no handler.
    let mut signals = {
        let _inside = runtime.enter();
        signals::Signals::catch()?
    };
    let (stop, stopped) = watch::channel(false);
    // Each poller holds a sender until it ends, its drives put back.
    let (alive, pollers_done) = tokio::sync::mpsc::channel::<()>(1);
    std::thread::scope(|scope| {
        let mut tasks = Vec::new();
        let mut feeds = Vec::new();
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
                feeds.push(Feed {
                    drive,
                    latest: latest.clone(),
                    requests: requests.clone(),
                });
                tasks.push(mqtt::DriveTask {
                    topics: mqtt::Topics::new(
                        gateway.mqtt.as_ref().map_or("", |m| &m.topic_prefix),
                        &drive.name,
                    ),
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
            // Several CANopen nodes go through the network manager, unless PDOs are taken on
            // the bus: SYNCs and TPDOs then need the bus itself, beside one SDO client.
            let by_pdo = line.iter().any(|&i| gateway.drives[i].pdo.on());
            let several = line.len() > 1 && !by_pdo;
            let connection = connection::Connection::new(&gateway.drives[line[0]], several);
            let (poll_stop, alive) = (stopped.clone(), alive.clone());
            scope.spawn(move || {
                poller::run(connection, served, &line_requests, &poll_stop);
                drop(alive);
            });
        }
        // The OPC UA server on a thread and runtime of its own: its first start makes an RSA
        // key (seconds), which must not hold up the MQTT side. It ends when `stopped` turns
        // true, dropping its request senders.
        #[cfg(feature = "opcua")]
        if let Some(endpoint) = endpoint {
            let (gateway, stopped) = (&gateway, stopped.clone());
            scope.spawn(move || endpoint.run(gateway, feeds, stopped));
        }
        #[cfg(not(feature = "opcua"))]
        drop(feeds);
        drop(alive);
        // The pollers see the stop (or their dropped request channels) at their next wait and
        // end; the forwarders end with the last of each drive's request senders (the MQTT
        // tasks', the OPC UA endpoint's); the scope joins them.
        runtime.block_on(async {
            match &gateway.mqtt {
                Some(mqtt) => {
                    mqtt::serve(&gateway, mqtt, password, tasks, stop, &mut signals).await
                }
                None => {
                    drop(tasks);
                    let signal = signals.next().await;
                    tracing::info!("{signal}: stopping");
                    stop.send_replace(true);
                }
            }
            signals.until_stopped(pollers_done).await;
        });
        Ok(())
    })
}

/// What a drive's poller gives the endpoints: its newest report, and a way to send it writes.
#[cfg_attr(not(feature = "opcua"), allow(dead_code))]
struct Feed<'g> {
    /// The drive.
    drive: &'g exposed::Drive,
    /// Its poller's newest report.
    latest: watch::Receiver<poller::Report>,
    /// Its poller's set requests.
    requests: std::sync::mpsc::Sender<poller::SetRequest>,
}

/// Log lines on standard error, info and above.
fn init_logging() {
    let _ = tracing_subscriber::fmt()
        .with_writer(std::io::stderr)
        .with_target(false)
        .try_init();
}
