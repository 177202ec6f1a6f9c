//! The gateway's address space: a folder per drive under Objects, a variable per parameter with
//! its data type, `EngineeringUnits`, `EURange` and `EnumValues`, and its access level; writes
//! to those variables go to the drive's poller as set requests.

use std::collections::HashMap;
use std::sync::{mpsc, Arc};

use async_trait::async_trait;
use opcua::nodes::VariableBuilder;
use opcua::server::address_space::{AccessLevel, AddressSpace};
use opcua::server::diagnostics::NamespaceMetadata;
use opcua::server::node_manager::memory::{
    InMemoryNodeManagerImpl, InMemoryNodeManagerImplBuilder,
};
use opcua::server::node_manager::{RequestContext, ServerContext, WriteNode};
use opcua::sync::RwLock;
use opcua::types::{
    AttributeId, DataTypeId, DataValue, EnumValueType, ExtensionObject, LocalizedText, NodeId,
    ObjectId, QualifiedName, Range, StatusCode, VariableTypeId, Variant,
};
use tokio::sync::oneshot;

use super::kind::Kind;
use super::units::eu_information;
use super::users::Users;
use crate::commands::gateway::poller::{SetReply, SetRequest};
use crate::commands::gateway::refusal::Refusal;

/// The namespace of the gateway's nodes.
pub const NAMESPACE: &str = "urn:drivegen:gateway";

/// A parameter as a variable.
pub struct Spec {
    /// The parameter's name: the variable's browse name.
    pub name: String,
    /// Its documentation: the variable's description.
    pub doc: Option<String>,
    /// Its shape.
    pub kind: Kind,
    /// Its unit symbol.
    pub unit: Option<String>,
    /// Its range in engineering units.
    pub range: Option<(f64, f64)>,
    /// An enum's values and names.
    pub enum_values: Vec<(i64, String)>,
    /// Whether clients with the write right may write it.
    pub writable: bool,
}

/// A drive as a folder.
pub struct DriveSpec {
    /// Its name: the folder's browse name.
    pub name: String,
    /// Milliseconds between polls: no variable changes faster.
    pub interval_ms: u32,
    /// Its parameters.
    pub parameters: Vec<Spec>,
    /// Its poller's set requests.
    pub requests: mpsc::Sender<SetRequest>,
}

/// The node ids of the gateway's namespace: `<drive>` for a folder, `<drive>.<parameter>` for
/// a variable, `<drive>.<parameter>.<property>` for its properties.
#[derive(Clone, Copy)]
pub struct Ids {
    namespace: u16,
}

impl Ids {
    /// The folder of `drive`.
    pub fn folder(self, drive: &str) -> NodeId {
        NodeId::new(self.namespace, drive)
    }

    /// The variable of `parameter` of `drive`.
    pub fn variable(self, drive: &str, parameter: &str) -> NodeId {
        NodeId::new(self.namespace, format!("{drive}.{parameter}"))
    }

    fn property(self, drive: &str, parameter: &str, property: &str) -> NodeId {
        NodeId::new(self.namespace, format!("{drive}.{parameter}.{property}"))
    }
}

/// Builds [`GatewayNodes`] once the server gives the namespace its index.
pub struct GatewayNodesBuilder {
    /// The drives.
    pub drives: Vec<DriveSpec>,
    /// The users and their rights.
    pub users: Arc<Users>,
}

impl InMemoryNodeManagerImplBuilder for GatewayNodesBuilder {
    type Impl = GatewayNodes;

    fn build(self, context: ServerContext, address_space: &mut AddressSpace) -> GatewayNodes {
        let namespace = context
            .type_tree
            .write()
            .namespaces_mut()
            .add_namespace(NAMESPACE);
        address_space.add_namespace(NAMESPACE, namespace);
        let ids = Ids { namespace };
        let targets = self
            .drives
            .iter()
            .enumerate()
            .flat_map(|(d, drive)| {
                let ids = &ids;
                (0..drive.parameters.len())
                    .map(move |p| (ids.variable(&drive.name, &drive.parameters[p].name), (d, p)))
            })
            .collect();
        GatewayNodes {
            metadata: NamespaceMetadata {
                namespace_uri: NAMESPACE.to_owned(),
                namespace_index: namespace,
                ..Default::default()
            },
            ids,
            drives: self.drives,
            targets,
            users: self.users,
        }
    }
}

/// The gateway's node manager.
pub struct GatewayNodes {
    metadata: NamespaceMetadata,
    ids: Ids,
    drives: Vec<DriveSpec>,
    /// Each variable's drive and parameter, by index.
    targets: HashMap<NodeId, (usize, usize)>,
    users: Arc<Users>,
}

impl GatewayNodes {
    /// The node ids.
    pub fn ids(&self) -> Ids {
        self.ids
    }

    fn add_drive(&self, space: &mut AddressSpace, drive: &DriveSpec) {
        let folder = self.ids.folder(&drive.name);
        space.add_folder(
            &folder,
            QualifiedName::new(self.ids.namespace, &drive.name),
            drive.name.as_str(),
            &ObjectId::ObjectsFolder.into(),
        );
        for spec in &drive.parameters {
            self.add_variable(space, drive, &folder, spec);
        }
    }

    fn add_variable(
        &self,
        space: &mut AddressSpace,
        drive: &DriveSpec,
        folder: &NodeId,
        spec: &Spec,
    ) {
        let id = self.ids.variable(&drive.name, &spec.name);
        let access = match spec.writable {
            true => AccessLevel::CURRENT_READ | AccessLevel::CURRENT_WRITE,
            false => AccessLevel::CURRENT_READ,
        };
        let engineering =
            spec.kind.is_engineering() && (spec.unit.is_some() || spec.range.is_some());
        let type_definition = match (engineering, spec.enum_values.is_empty()) {
            (true, _) => VariableTypeId::AnalogItemType,
            (false, false) => VariableTypeId::MultiStateValueDiscreteType,
            (false, true) => VariableTypeId::BaseDataVariableType,
        };
        let mut variable = VariableBuilder::new(
            &id,
            QualifiedName::new(self.ids.namespace, &spec.name),
            spec.name.as_str(),
        )
        .data_type(spec.kind.data_type())
        .value_rank(-1)
        .access_level(access)
        .user_access_level(access)
        .minimum_sampling_interval(f64::from(drive.interval_ms))
        .has_type_definition(type_definition)
        .organized_by(folder.clone());
        if let Some(doc) = &spec.doc {
            variable = variable.description(LocalizedText::new("en", doc));
        }
        variable.insert(space);
        // Nothing read yet: Bad until the first poll, never a default shown as a reading.
        if let Some(opcua::nodes::NodeType::Variable(v)) = space.find_mut(&id) {
            v.set_data_value(DataValue {
                value: Some(Variant::Empty),
                status: Some(StatusCode::BadWaitingForInitialData),
                ..Default::default()
            });
        }
        if spec.kind.is_engineering() {
            if let Some(unit) = &spec.unit {
                let eu = ExtensionObject::from_message(eu_information(unit));
                self.add_property(
                    space,
                    drive,
                    spec,
                    "EngineeringUnits",
                    DataTypeId::EUInformation,
                    eu.into(),
                );
            }
            if let Some((low, high)) = spec.range {
                let range = ExtensionObject::from_message(Range { low, high });
                self.add_property(
                    space,
                    drive,
                    spec,
                    "EURange",
                    DataTypeId::Range,
                    range.into(),
                );
            }
        }
        if !spec.enum_values.is_empty() {
            let values: Vec<ExtensionObject> = spec
                .enum_values
                .iter()
                .map(|(value, name)| {
                    ExtensionObject::from_message(EnumValueType {
                        value: *value,
                        display_name: LocalizedText::new("", name),
                        description: LocalizedText::null(),
                    })
                })
                .collect();
            self.add_property(
                space,
                drive,
                spec,
                "EnumValues",
                DataTypeId::EnumValueType,
                Variant::from(values),
            );
        }
    }

    /// A property (a standard one: its browse name in namespace 0).
    fn add_property(
        &self,
        space: &mut AddressSpace,
        drive: &DriveSpec,
        spec: &Spec,
        name: &str,
        data_type: DataTypeId,
        value: Variant,
    ) {
        let array = matches!(value, Variant::Array(_));
        VariableBuilder::new(
            &self.ids.property(&drive.name, &spec.name, name),
            QualifiedName::new(0, name),
            name,
        )
        .data_type(data_type)
        .value_rank(if array { 1 } else { -1 })
        .value(value)
        .access_level(AccessLevel::CURRENT_READ)
        .user_access_level(AccessLevel::CURRENT_READ)
        .has_type_definition(VariableTypeId::PropertyType)
        .property_of(self.ids.variable(&drive.name, &spec.name))
        .insert(space);
    }

    /// One write: refused here when the variable is not writable through the gateway or the
    /// user has no write right, or the value is not of the variable's type; else a set request
    /// to the drive's poller, whose checks are `drivegen write`'s.
    async fn write_one(&self, context: &RequestContext, write: &WriteNode) -> StatusCode {
        let value = write.value();
        let Some(&(d, p)) = self.targets.get(&value.node_id) else {
            return StatusCode::BadNotWritable;
        };
        let (drive, spec) = (&self.drives[d], &self.drives[d].parameters[p]);
        if value.attribute_id != AttributeId::Value {
            return StatusCode::BadNotWritable;
        }
        if value.index_range.has_range() {
            return StatusCode::BadWriteNotSupported;
        }
        let user = context.token.0.as_str();
        if !spec.writable {
            tracing::warn!(drive = %drive.name, parameter = %spec.name, user, "OPC UA write refused: not writable through this gateway");
            return StatusCode::BadNotWritable;
        }
        if !self.users.may_write(&context.token) {
            tracing::warn!(drive = %drive.name, parameter = %spec.name, user, "OPC UA write refused: the user has no write right");
            return StatusCode::BadUserAccessDenied;
        }
        let message = match spec.kind.set_message(value.value.value.as_ref()) {
            Ok(message) => message,
            Err(status) => {
                tracing::warn!(drive = %drive.name, parameter = %spec.name, user, "OPC UA write refused: {status}");
                return status;
            }
        };
        let (reply, answer) = oneshot::channel();
        let request = SetRequest {
            parameter: spec.name.clone(),
            message: message.to_string().into_bytes(),
            reply,
        };
        if drive.requests.send(request).is_err() {
            return StatusCode::BadShutdown;
        }
        match answer.await {
            Ok(SetReply { refused: None, .. }) => StatusCode::Good,
            Ok(SetReply {
                refused: Some(refusal),
                ..
            }) => status(refusal),
            Err(_) => StatusCode::BadShutdown,
        }
    }
}

/// The status code of a refusal of `drivegen write`'s checks.
fn status(refusal: Refusal) -> StatusCode {
    match refusal {
        Refusal::OutOfRange => StatusCode::BadOutOfRange,
        Refusal::WrongType => StatusCode::BadTypeMismatch,
        Refusal::NotWritable => StatusCode::BadNotWritable,
        Refusal::Communication => StatusCode::BadCommunicationError,
    }
}

#[async_trait]
impl InMemoryNodeManagerImpl for GatewayNodes {
    async fn init(&self, address_space: &mut AddressSpace, _context: ServerContext) {
        for drive in &self.drives {
            self.add_drive(address_space, drive);
        }
    }

    fn name(&self) -> &str {
        "drivegen gateway"
    }

    fn namespaces(&self) -> Vec<NamespaceMetadata> {
        vec![self.metadata.clone()]
    }

    async fn write(
        &self,
        context: &RequestContext,
        _address_space: &RwLock<AddressSpace>,
        nodes_to_write: &mut [&mut WriteNode],
    ) -> Result<(), StatusCode> {
        // One after the other: the poller answers one request at a time anyway.
        for write in nodes_to_write.iter_mut() {
            let status = self.write_one(context, write).await;
            write.set_status(status);
        }
        Ok(())
    }
}
