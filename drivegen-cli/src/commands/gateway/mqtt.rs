//! A drive's MQTT side: its own connection to the broker (so its last will is its own status),
//! the values the poller reports published retained, set messages forwarded to the poller and
//! answered on `.../set/result`.

use std::collections::{BTreeMap, BTreeSet};
use std::sync::mpsc;
use std::time::{Duration, SystemTime};

use rumqttc::{
    AsyncClient, Event, EventLoop, LastWill, MqttOptions, Outgoing, Packet, Publish, QoS,
    TlsConfiguration, Transport,
};
use tokio::sync::{oneshot, watch};
use tokio::task::JoinSet;

use drivegen::gateway_file::MqttEntry;

use super::exposed::Gateway;
use super::poller::{Report, SetRequest};
use super::signals::Signals;

/// A drive's topics: `<prefix>/<drive>/...`.
pub struct Topics {
    drive: String,
    base: String,
}

impl Topics {
    /// The topics of `drive` under `prefix`.
    pub fn new(prefix: &str, drive: &str) -> Self {
        Self {
            drive: drive.to_owned(),
            base: format!("{prefix}/{drive}"),
        }
    }

    fn status(&self) -> String {
        format!("{}/status", self.base)
    }

    fn error(&self) -> String {
        format!("{}/error", self.base)
    }

    fn value(&self, parameter: &str) -> String {
        format!("{}/{parameter}", self.base)
    }

    fn set_filter(&self) -> String {
        format!("{}/+/set", self.base)
    }

    fn result(&self, parameter: &str) -> String {
        format!("{}/{parameter}/set/result", self.base)
    }

    /// The parameter a set topic names.
    fn set_parameter<'t>(&self, topic: &'t str) -> Option<&'t str> {
        topic
            .strip_prefix(self.base.as_str())?
            .strip_prefix('/')?
            .strip_suffix("/set")
            .filter(|p| !p.contains('/'))
    }
}

/// One drive's MQTT task and what it talks to.
pub struct DriveTask {
    /// Its topics.
    pub topics: Topics,
    /// The parameters clients may write.
    pub writable: BTreeSet<String>,
    /// Publish every poll rather than changes only.
    pub publish_every_poll: bool,
    /// How many parameters it publishes.
    pub parameters: usize,
    /// The poller's newest report.
    pub latest: watch::Receiver<Report>,
    /// The poller's set requests.
    pub requests: mpsc::Sender<SetRequest>,
    /// Turns true when the gateway stops.
    pub stop: watch::Receiver<bool>,
}

/// Runs every drive's task until SIGINT or SIGTERM, then sets `stop` and waits for each to
/// publish its status offline and disconnect.
pub async fn serve(
    gateway: &Gateway,
    mqtt: &MqttEntry,
    password: Option<String>,
    tasks: Vec<DriveTask>,
    stop: watch::Sender<bool>,
    signals: &mut Signals,
) {
    let mut running = JoinSet::new();
    for task in tasks {
        let options = options(gateway, mqtt, password.as_deref(), &task);
        running.spawn(task.run(options));
    }
    tracing::info!(broker = %format!("{}:{}", mqtt.host, mqtt.port), "serving");
    let signal = signals.next().await;
    tracing::info!("{signal}: stopping");
    stop.send_replace(true);
    while running.join_next().await.is_some() {}
}

fn options(
    gateway: &Gateway,
    mqtt: &MqttEntry,
    password: Option<&str>,
    task: &DriveTask,
) -> MqttOptions {
    let id = format!(
        "drivegen-{}-{}",
        task.topics.base.replace('/', "-"),
        std::process::id()
    );
    let mut options = MqttOptions::new(id, mqtt.host.clone(), mqtt.port);
    options.set_keep_alive(Duration::from_secs(5));
    options.set_last_will(LastWill::new(
        task.topics.status(),
        "offline",
        QoS::AtLeastOnce,
        true,
    ));
    if let Some(user) = &mqtt.username {
        options.set_credentials(user.clone(), password.unwrap_or_default());
    }
    if let Some(tls) = &gateway.tls {
        options.set_transport(Transport::tls_with_config(TlsConfiguration::Simple {
            ca: tls.ca.clone(),
            alpn: None,
            client_auth: tls.client.clone(),
        }));
    }
    options
}

/// What was last published, republished whole after a reconnect (a restarted broker has lost
/// its retained messages).
#[derive(Default)]
struct Published {
    values: BTreeMap<String, serde_json::Value>,
    online: Option<bool>,
    error: Option<String>,
}

/// A message to publish retained.
type Retained = (String, Vec<u8>);

impl DriveTask {
    async fn run(mut self, options: MqttOptions) {
        // Room for a whole republish (each value, the status and the error) with room to spare:
        // a republish that did not fit would leave unchanged values unpublished until they change.
        let capacity = 2 * self.parameters + 16;
        let (client, mut events) = AsyncClient::new(options, capacity);
        let mut published = Published::default();
        let mut connected = false;
        // The last connection error logged: a dead broker is logged once, not every second.
        let mut failing: Option<String> = None;
        loop {
            tokio::select! {
                event = events.poll() => match event {
                    Ok(Event::Incoming(Packet::ConnAck(_))) => {
                        connected = true;
                        failing = None;
                        tracing::info!(drive = %self.topics.drive, "connected to the broker");
                        self.on_connect(&client, &published);
                    }
                    Ok(Event::Incoming(Packet::Publish(set))) => self.on_set(&client, &set),
                    Ok(_) => {}
                    Err(e) => {
                        let why = e.to_string();
                        if failing.as_ref() != Some(&why) {
                            tracing::warn!(drive = %self.topics.drive, "no broker connection: {why}");
                            failing = Some(why);
                        }
                        connected = false;
                        // rumqttc reconnects at the next poll; do not spin against a dead broker.
                        tokio::time::sleep(Duration::from_secs(1)).await;
                    }
                },
                Ok(()) = self.latest.changed() => {
                    let report = self.latest.borrow_and_update().clone();
                    let changes = published.update(&self.topics, report, self.publish_every_poll);
                    if connected {
                        publish_all(&client, changes);
                    }
                }
                _ = self.stop.changed() => break,
            }
        }
        let _ = client.try_publish(self.topics.status(), QoS::AtLeastOnce, true, "offline");
        let _ = client.try_disconnect();
        finish(&mut events).await;
    }

    fn on_connect(&self, client: &AsyncClient, published: &Published) {
        if let Err(e) = client.try_subscribe(self.topics.set_filter(), QoS::AtLeastOnce) {
            tracing::warn!(drive = %self.topics.drive, "cannot subscribe to set messages: {e}");
        }
        publish_all(client, published.all(&self.topics));
    }

    /// A set message: refused here when the parameter is not writable through the gateway,
    /// else handed to the poller; its result is published when the poller answers.
    fn on_set(&self, client: &AsyncClient, set: &Publish) {
        let Some(parameter) = self.topics.set_parameter(&set.topic) else {
            return;
        };
        let result_topic = self.topics.result(parameter);
        if !self.writable.contains(parameter) {
            tracing::warn!(drive = %self.topics.drive, parameter, "write refused: not writable through this gateway");
            let refusal = serde_json::json!({
                "ok": false,
                "error": format!("`{parameter}` is not writable through this gateway"),
            });
            publish_result(client.clone(), result_topic, refusal);
            return;
        }
        let (reply, answer) = oneshot::channel();
        let request = SetRequest {
            parameter: parameter.to_owned(),
            message: set.payload.to_vec(),
            reply,
        };
        if self.requests.send(request).is_err() {
            let gone = serde_json::json!({ "ok": false, "error": "the gateway is stopping" });
            publish_result(client.clone(), result_topic, gone);
            return;
        }
        let client = client.clone();
        tokio::spawn(async move {
            if let Ok(result) = answer.await {
                let _ = client
                    .publish(
                        result_topic,
                        QoS::AtLeastOnce,
                        false,
                        result.payload.to_string(),
                    )
                    .await;
            }
        });
    }
}

impl Published {
    /// Takes `report` in and returns what to publish: changed values (or all, when
    /// `every_poll`), and the status and error when they changed.
    fn update(&mut self, topics: &Topics, report: Report, every_poll: bool) -> Vec<Retained> {
        let mut out = Vec::new();
        let online = match report {
            Report::Starting => return out,
            Report::Values(values) => {
                for (name, payload) in values {
                    let same = self
                        .values
                        .get(&name)
                        .is_some_and(|old| super::payload::same_value(old, &payload));
                    if every_poll || !same {
                        out.push((topics.value(&name), payload.to_string().into_bytes()));
                    }
                    self.values.insert(name, payload);
                }
                self.error = None;
                true
            }
            Report::Failed(why) => {
                if self.error.as_ref() != Some(&why) {
                    out.push((topics.error(), error_payload(&why)));
                }
                self.error = Some(why);
                false
            }
        };
        if self.online != Some(online) {
            if online {
                // An empty retained message clears the error topic.
                out.push((topics.error(), Vec::new()));
            }
            out.push((topics.status(), status(online)));
            self.online = Some(online);
        }
        out
    }

    /// Everything, for a fresh connection.
    fn all(&self, topics: &Topics) -> Vec<Retained> {
        let mut out: Vec<Retained> = self
            .values
            .iter()
            .map(|(name, payload)| (topics.value(name), payload.to_string().into_bytes()))
            .collect();
        if let Some(why) = &self.error {
            out.push((topics.error(), error_payload(why)));
        }
        if let Some(online) = self.online {
            out.push((topics.status(), status(online)));
        }
        out
    }
}

fn status(online: bool) -> Vec<u8> {
    match online {
        true => b"online".to_vec(),
        false => b"offline".to_vec(),
    }
}

fn error_payload(why: &str) -> Vec<u8> {
    let time = humantime::format_rfc3339_millis(SystemTime::now()).to_string();
    serde_json::json!({ "error": why, "time": time })
        .to_string()
        .into_bytes()
}

/// Queues retained messages without waiting: the event loop sends them. A full queue (a broker
/// gone for long) drops them; everything is republished at the next connection.
fn publish_all(client: &AsyncClient, messages: Vec<Retained>) {
    for (topic, payload) in messages {
        if let Err(e) = client.try_publish(topic.clone(), QoS::AtLeastOnce, true, payload) {
            tracing::warn!(
                topic,
                "not published now, republished at the next connection: {e}"
            );
        }
    }
}

fn publish_result(client: AsyncClient, topic: String, result: serde_json::Value) {
    tokio::spawn(async move {
        let _ = client
            .publish(topic, QoS::AtLeastOnce, false, result.to_string())
            .await;
    });
}

/// Drives the event loop until the disconnect is out (or two seconds pass).
async fn finish(events: &mut EventLoop) {
    let sent = async {
        loop {
            match events.poll().await {
                Ok(Event::Outgoing(Outgoing::Disconnect)) | Err(_) => break,
                Ok(_) => {}
            }
        }
    };
    let _ = tokio::time::timeout(Duration::from_secs(2), sent).await;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn set_topics_name_their_parameter() {
        let topics = Topics::new("drivegen", "left");
        assert_eq!(
            topics.set_parameter("drivegen/left/speed/set"),
            Some("speed")
        );
        assert_eq!(topics.set_parameter("drivegen/left/speed/set/result"), None);
        assert_eq!(topics.set_parameter("drivegen/right/speed/set"), None);
        assert_eq!(topics.set_parameter("drivegen/leftover/speed/set"), None);
        assert_eq!(topics.set_parameter("drivegen/left/a/b/set"), None);
    }

    fn values(v: i64) -> Report {
        Report::Values(vec![(
            "speed".into(),
            serde_json::json!({ "value": v, "raw": v, "time": "t" }),
        )])
    }

    #[test]
    fn only_changes_are_published_and_the_status_follows_the_drive() {
        let topics = Topics::new("drivegen", "left");
        let mut published = Published::default();
        let first = published.update(&topics, values(1), false);
        let first_topics: Vec<&str> = first.iter().map(|(t, _)| t.as_str()).collect();
        assert_eq!(
            first_topics,
            [
                "drivegen/left/speed",
                "drivegen/left/error",
                "drivegen/left/status"
            ]
        );
        assert!(published.update(&topics, values(1), false).is_empty());
        assert_eq!(published.update(&topics, values(1), true).len(), 1);
        let failed = published.update(&topics, Report::Failed("timeout".into()), false);
        assert_eq!(failed.len(), 2);
        assert_eq!(
            failed[1],
            ("drivegen/left/status".into(), b"offline".to_vec())
        );
        // The value kept is the last read, with its own time: a fresh connection sees it,
        // beside the offline status and the error.
        assert_eq!(published.all(&topics).len(), 3);
    }
}
