//! A drive's variables kept to its poller's reports: each value with the poll time as its
//! source timestamp; every variable Bad while the drive does not answer, never the last value
//! shown as Good. Subscriptions are told of each change.

use std::sync::Arc;

use opcua::server::node_manager::memory::InMemoryNodeManager;
use opcua::server::SubscriptionCache;
use opcua::types::{DataValue, DateTime, NodeId, StatusCode, Variant};
use tokio::sync::watch;

use super::kind::Kind;
use super::nodes::GatewayNodes;
use super::Feed;
use crate::commands::gateway::poller::Report;

/// The task that keeps one drive's variables.
pub struct Update {
    manager: Arc<InMemoryNodeManager<GatewayNodes>>,
    subscriptions: Arc<SubscriptionCache>,
    /// Each variable's parameter name, node and shape.
    variables: Vec<(String, NodeId, Kind)>,
    latest: watch::Receiver<Report>,
}

impl Update {
    /// The task of `feed`'s drive.
    pub fn new(
        manager: &Arc<InMemoryNodeManager<GatewayNodes>>,
        subscriptions: Arc<SubscriptionCache>,
        feed: Feed<'_>,
    ) -> Self {
        let ids = manager.inner().ids();
        let drive = feed.drive;
        let variables = drive
            .parameters
            .iter()
            .filter_map(|name| drive.parameter(name))
            .map(|p| {
                (
                    p.name.clone(),
                    ids.variable(&drive.name, &p.name),
                    Kind::of(p),
                )
            })
            .collect();
        Self {
            manager: Arc::clone(manager),
            subscriptions,
            variables,
            latest: feed.latest,
        }
    }

    /// Sets the variables at each report until `stop` turns true or the poller ends.
    pub async fn run(mut self, mut stop: watch::Receiver<bool>) {
        loop {
            let report = self.latest.borrow_and_update().clone();
            let values = data_values(&self.variables, &report);
            let changes = values.iter().map(|(id, value)| (id, None, value.clone()));
            if let Err(status) = self.manager.set_values(&self.subscriptions, changes) {
                tracing::warn!("OPC UA: values not set: {status}");
            }
            tokio::select! {
                changed = self.latest.changed() => if changed.is_err() { return },
                _ = stop.changed() => return,
            }
        }
    }
}

/// The variables' values for `report`.
fn data_values(variables: &[(String, NodeId, Kind)], report: &Report) -> Vec<(NodeId, DataValue)> {
    let now = DateTime::now();
    // An empty value beside the status: the server reads a status only with a value.
    let bad = |status: StatusCode| DataValue {
        value: Some(Variant::Empty),
        status: Some(status),
        source_timestamp: Some(now),
        server_timestamp: Some(now),
        ..Default::default()
    };
    match report {
        Report::Starting => variables
            .iter()
            .map(|(_, id, _)| (id.clone(), bad(StatusCode::BadWaitingForInitialData)))
            .collect(),
        Report::Failed(_) => variables
            .iter()
            .map(|(_, id, _)| (id.clone(), bad(StatusCode::BadCommunicationError)))
            .collect(),
        Report::Values(payloads) => variables
            .iter()
            .map(|(name, id, kind)| {
                let payload = payloads.iter().find(|(n, _)| n == name).map(|(_, p)| p);
                let value = payload.and_then(|p| {
                    let variant = kind.variant(p)?;
                    let time = p.get("time")?.as_str()?;
                    let source = DateTime::parse_from_rfc3339(time).ok()?;
                    Some(DataValue {
                        value: Some(variant),
                        status: Some(StatusCode::Good),
                        source_timestamp: Some(source),
                        server_timestamp: Some(now),
                        ..Default::default()
                    })
                });
                // A value that did not decode: Bad, not a made-up reading.
                (
                    id.clone(),
                    value.unwrap_or_else(|| bad(StatusCode::BadDecodingError)),
                )
            })
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failed_drive_turns_every_variable_bad() {
        let variables = vec![("speed".to_owned(), NodeId::new(2, "d.speed"), Kind::Double)];
        let values = Report::Values(vec![(
            "speed".into(),
            serde_json::json!({ "value": 12.5, "raw": 125, "time": "2026-11-28T03:30:00.123Z" }),
        )]);
        let good = &data_values(&variables, &values)[0].1;
        assert_eq!(good.value, Some(Variant::Double(12.5)));
        assert_eq!(good.status, Some(StatusCode::Good));
        assert_eq!(
            good.source_timestamp,
            Some(DateTime::parse_from_rfc3339("2026-11-28T03:30:00.123Z").unwrap())
        );
        let failed = &data_values(&variables, &Report::Failed("timeout".into()))[0].1;
        assert_eq!(failed.status, Some(StatusCode::BadCommunicationError));
        assert_eq!(failed.value, Some(Variant::Empty));
    }
}
