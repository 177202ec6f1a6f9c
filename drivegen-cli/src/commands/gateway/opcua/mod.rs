//! The gateway's OPC UA server endpoint (feature `opcua`, docs/gateway.md): the drives' values
//! from the pollers' reports, typed, with their units, ranges and enum names; writes through the
//! pollers' set requests, the checks of `drivegen write`; a Basic256Sha256 Sign&Encrypt endpoint
//! always, one without security only for anonymous (read-only) clients when the file allows them.

mod kind;
mod nodes;
mod units;
mod users;
mod values;

use std::path::PathBuf;
use std::sync::Arc;

use drivegen::gateway_file::{OpcUaEntry, OpcUaRight};
use opcua::server::node_manager::memory::{InMemoryNodeManager, InMemoryNodeManagerBuilder};
use opcua::server::{ServerBuilder, ServerEndpoint, ServerUserToken, ANONYMOUS_USER_TOKEN_ID};
use tokio::sync::watch;

use super::exposed::Gateway;
use super::Feed;
use crate::error::CliError;
use nodes::{DriveSpec, GatewayNodes, GatewayNodesBuilder, Spec};

/// The endpoint a gateway file asks for, checked and bound before anything else opens.
pub struct Endpoint {
    entry: OpcUaEntry,
    /// The PKI directory, relative to the gateway file.
    pki: PathBuf,
    /// Each user's name, password (from the environment) and right.
    users: Vec<(String, String, OpcUaRight)>,
    /// Bound at once, so a port in use is refused before any bus opens.
    listener: std::net::TcpListener,
}

impl Endpoint {
    /// The endpoint of `gateway`'s `[opcua]`, if it has one: the users' passwords read from the
    /// environment, the port bound.
    pub fn prepare(gateway: &Gateway) -> Result<Option<Self>, CliError> {
        let Some(entry) = gateway.opcua.clone() else {
            return Ok(None);
        };
        let users = entry
            .users
            .iter()
            .map(|user| {
                let password = std::env::var(&user.password_env).map_err(|_| {
                    CliError::Usage(format!(
                        "the gateway file's OPC UA user `{}` has `password_env = {}`, which is not set",
                        user.name, user.password_env
                    ))
                })?;
                Ok((user.name.clone(), password, user.right))
            })
            .collect::<Result<_, CliError>>()?;
        let address = format!("{}:{}", entry.host, entry.port);
        let listener = std::net::TcpListener::bind(&address)
            .and_then(|l| l.set_nonblocking(true).map(|()| l))
            .map_err(|e| CliError::Io(format!("OPC UA: cannot listen on {address}: {e}")))?;
        Ok(Some(Self {
            pki: gateway.folder.join(&entry.pki_dir),
            entry,
            users,
            listener,
        }))
    }

    /// Serves `feeds` until `stop` turns true, on a runtime of its own (run on a thread of its
    /// own).
    pub fn run(self, gateway: &Gateway, feeds: Vec<Feed<'_>>, stop: watch::Receiver<bool>) {
        let runtime = tokio::runtime::Builder::new_current_thread()
            .enable_all()
            .build();
        match runtime {
            Ok(runtime) => runtime.block_on(self.serve(gateway, feeds, stop)),
            Err(e) => tracing::error!("OPC UA: cannot start its runtime: {e}"),
        }
    }

    /// Serves `feeds` until `stop` turns true.
    async fn serve(self, gateway: &Gateway, feeds: Vec<Feed<'_>>, mut stop: watch::Receiver<bool>) {
        let users = Arc::new(users::Users::new(&self.users));
        let drives = feeds.iter().map(|feed| drive_spec(gateway, feed)).collect();
        let builder =
            self.builder(Arc::clone(&users))
                .with_node_manager(InMemoryNodeManagerBuilder::new(GatewayNodesBuilder {
                    drives,
                    users,
                }));
        let (server, handle) = match builder.build() {
            Ok(built) => built,
            Err(why) => {
                tracing::error!("OPC UA: the server cannot start: {why}");
                return;
            }
        };
        let listener = match tokio::net::TcpListener::from_std(self.listener) {
            Ok(listener) => listener,
            Err(e) => {
                tracing::error!("OPC UA: cannot listen: {e}");
                return;
            }
        };
        let running = tokio::spawn(server.run_with(listener));
        let Some(manager) = handle
            .node_managers()
            .get_of_type::<InMemoryNodeManager<GatewayNodes>>()
        else {
            tracing::error!("OPC UA: the gateway's node manager is missing");
            handle.cancel();
            return;
        };
        tracing::info!(endpoint = %format!("opc.tcp://{}:{}/", self.entry.host, self.entry.port), "OPC UA serving");
        let mut updates = tokio::task::JoinSet::new();
        for feed in feeds {
            let update = values::Update::new(&manager, handle.subscriptions().clone(), feed);
            updates.spawn(update.run(stop.clone()));
        }
        while !*stop.borrow_and_update() {
            if stop.changed().await.is_err() {
                break;
            }
        }
        handle.cancel();
        while updates.join_next().await.is_some() {}
        match running.await {
            Ok(Err(why)) => tracing::warn!("OPC UA: the server ended: {why}"),
            Err(e) => tracing::warn!("OPC UA: the server ended: {e}"),
            Ok(Ok(())) => {}
        }
    }

    /// The server: its certificate in the PKI directory (made on first start), its endpoints,
    /// its users, the sampling interval.
    fn builder(&self, users: Arc<users::Users>) -> ServerBuilder {
        let entry = &self.entry;
        let mut token_ids: Vec<String> =
            self.users.iter().map(|(name, _, _)| name.clone()).collect();
        if entry.anonymous {
            token_ids.push(ANONYMOUS_USER_TOKEN_ID.to_owned());
        }
        let mut builder = ServerBuilder::new()
            .application_name("drivegen gateway")
            // Not the nodes' namespace: namespace 1, the server's own, is this URI.
            .application_uri("urn:drivegen:gateway:server")
            .product_uri("urn:drivegen")
            .pki_dir(&self.pki)
            .certificate_path("own/cert.der")
            .private_key_path("private/private.pem")
            .create_sample_keypair(true)
            .host(entry.host.clone())
            .port(entry.port)
            .discovery_urls(vec!["/".to_owned()])
            .subscription_poll_interval_ms(entry.sampling_interval_ms.into())
            .with_authenticator(users)
            .add_endpoint(
                "basic256sha256_sign_encrypt",
                ServerEndpoint::new_basic256sha256_sign_encrypt("/", &token_ids),
            );
        if entry.anonymous {
            builder = builder.add_endpoint(
                "none",
                ServerEndpoint::new_none("/", &[ANONYMOUS_USER_TOKEN_ID.to_owned()]),
            );
        }
        for (name, password, _) in &self.users {
            builder =
                builder.add_user_token(name.clone(), ServerUserToken::user_pass(name, password));
        }
        let limits = &mut builder.limits_mut().subscriptions;
        limits.min_sampling_interval_ms = f64::from(entry.sampling_interval_ms);
        limits.min_publishing_interval_ms = f64::from(entry.sampling_interval_ms);
        builder
    }
}

/// A drive's folder and variables: every parameter the file exposes, writable when the file's
/// `writable` list names it and the gateway is not read-only.
fn drive_spec(gateway: &Gateway, feed: &Feed<'_>) -> DriveSpec {
    let drive = feed.drive;
    let writable = drive.writable_names(gateway.read_only);
    let parameters = drive
        .parameters
        .iter()
        .filter_map(|name| drive.parameter(name))
        .map(|parameter| {
            let kind = kind::Kind::of(parameter);
            Spec {
                name: parameter.name.clone(),
                doc: parameter.doc.clone(),
                kind,
                unit: parameter.unit.clone(),
                range: kind::eu_range(parameter),
                enum_values: kind::enum_values(&drive.device, parameter)
                    .into_iter()
                    .map(|(value, name)| (value, name.to_owned()))
                    .collect(),
                writable: writable.contains(&parameter.name) && kind != kind::Kind::Bytes,
            }
        })
        .collect();
    DriveSpec {
        name: drive.name.clone(),
        interval_ms: drive.interval_ms,
        parameters,
        requests: feed.requests.clone(),
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::commands::gateway::exposed::Gateway;
    use crate::commands::gateway::poller::Report;

    /// A gateway file with `read_only` as given, loaded: one Lafert drive.
    fn gateway(read_only: bool) -> Gateway {
        let dir = std::env::temp_dir().join(format!(
            "drivegen-opcua-spec-{read_only}-{}",
            std::process::id()
        ));
        std::fs::create_dir_all(&dir).unwrap();
        let lafert = Path::new(env!("CARGO_MANIFEST_DIR")).join("../descriptions/lafert-smartris");
        let file = dir.join("gateway.toml");
        std::fs::write(
            &file,
            format!(
                "format = 1\nread_only = {read_only}\n[opcua]\nanonymous = true\n[[drive]]\n\
                 name = \"lafert\"\ndescription = \"{}\"\nbus = {{ modbus_tcp = \"127.0.0.1:1\" }}\n\
                 parameters = [\"bus_dc_link\", \"speed_ramp_up\", \"operation_mode\"]\n\
                 writable = [\"speed_ramp_up\", \"operation_mode\"]\n",
                lafert.display()
            ),
        )
        .unwrap();
        let gateway = Gateway::load(&file).unwrap();
        let _ = std::fs::remove_dir_all(&dir);
        gateway
    }

    fn spec(gateway: &Gateway) -> DriveSpec {
        let (requests, _pending) = std::sync::mpsc::channel();
        let (_reports, latest) = watch::channel(Report::Starting);
        let feed = Feed {
            drive: &gateway.drives[0],
            latest,
            requests,
        };
        drive_spec(gateway, &feed)
    }

    #[test]
    fn variables_take_their_shape_range_and_access_from_the_description_and_the_file() {
        let drive = spec(&gateway(false));
        let shapes: Vec<_> = drive
            .parameters
            .iter()
            .map(|p| (p.name.as_str(), p.kind, p.unit.as_deref(), p.writable))
            .collect();
        let u16_value = kind::Kind::Integer {
            int: kind::Int::U16,
            raw: false,
        };
        let u16_raw = kind::Kind::Integer {
            int: kind::Int::U16,
            raw: true,
        };
        assert_eq!(
            shapes,
            [
                ("bus_dc_link", kind::Kind::Double, Some("V"), false),
                ("speed_ramp_up", u16_value, Some("ms"), true),
                ("operation_mode", u16_raw, None, true),
            ]
        );
        assert_eq!(drive.parameters[1].range, Some((0.0, 32000.0)));
        let modes = &drive.parameters[2].enum_values;
        assert!(modes.contains(&(2, "velocity".to_owned())), "{modes:?}");
    }

    #[test]
    fn a_read_only_gateway_makes_every_variable_read_only() {
        let drive = spec(&gateway(true));
        assert!(drive.parameters.iter().all(|p| !p.writable));
    }
}
