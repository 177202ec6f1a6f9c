//! Node-relative defaults (`$NODEID+0x180`) checked node by node: the set of node IDs on which such
//! a default is a value its own parameter accepts.
//!
//! A vendor EDS may give a COB-ID `DefaultValue=$NODEID+0x180` with absolute limits
//! `LowLimit=0x181` / `HighLimit=0x18F`: the drive's own default then lies within its limits on
//! node IDs 1..=15 only. Validation warns about such a narrowing (and refuses a default no node ID
//! makes acceptable); tools that open a drive at a node ID use [`Device::default_node_ids`] to say
//! when that node ID is outside the narrowed set.

use std::fmt;

use drivebus_model::canopen::NodeId;

use super::{Device, Number, Parameter};

/// A set of CANopen node IDs within 1..=127.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct NodeIds(u128);

impl NodeIds {
    /// Every node ID 1..=127.
    pub const ALL: NodeIds = NodeIds(u128::MAX << 1);
    /// No node ID.
    pub const NONE: NodeIds = NodeIds(0);

    /// The node IDs 1..=127 for which `keep` holds.
    pub fn matching(keep: impl Fn(u8) -> bool) -> Self {
        let bits = (NodeId::MIN..=NodeId::MAX)
            .filter(|&id| keep(id))
            .fold(0u128, |bits, id| bits | (1u128 << id));
        NodeIds(bits)
    }

    /// Whether `id` is in the set (never for 0 or above 127).
    pub fn contains(self, id: u8) -> bool {
        id < 128 && self.0 & (1u128 << id) != 0
    }

    /// Whether the set is empty.
    pub fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// Whether the set holds every node ID 1..=127.
    pub fn is_all(self) -> bool {
        self == Self::ALL
    }

    /// The node IDs in both sets.
    pub fn intersection(self, other: NodeIds) -> NodeIds {
        NodeIds(self.0 & other.0)
    }

    /// The node IDs 1..=127 not in the set.
    pub fn complement(self) -> NodeIds {
        NodeIds(!self.0 & Self::ALL.0)
    }

    /// The node IDs in the set, lowest first.
    pub fn iter(self) -> impl Iterator<Item = u8> {
        (NodeId::MIN..=NodeId::MAX).filter(move |&id| self.contains(id))
    }

    /// The set as runs of consecutive node IDs, each `(first, last)`, lowest first.
    pub fn runs(self) -> Vec<(u8, u8)> {
        let mut runs: Vec<(u8, u8)> = Vec::new();
        for id in self.iter() {
            match runs.last_mut() {
                Some((_, last)) if *last + 1 == id => *last = id,
                _ => runs.push((id, id)),
            }
        }
        runs
    }
}

/// `1..=15`, `5`, `1..=3, 9, 20..=127`, or `none`.
impl fmt::Display for NodeIds {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let runs = self.runs();
        if runs.is_empty() {
            return f.write_str("none");
        }
        for (i, (first, last)) in runs.into_iter().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            if first == last {
                write!(f, "{first}")?;
            } else {
                write!(f, "{first}..={last}")?;
            }
        }
        Ok(())
    }
}

/// What a parameter asks of a value, checked one at a time so a diagnostic names the one that
/// refuses (or narrows) a default.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DefaultCheck {
    /// The value fits the parameter's type.
    Type,
    /// The value lies within the parameter's range (always, without one).
    Range,
    /// The value is one of the allowed values (always, when none are listed).
    Allowed,
    /// The value is a declared value of the parameter's enum (always, without an enum or for a
    /// float).
    Enum,
}

impl DefaultCheck {
    /// Every check, in the order diagnostics report them.
    pub const ALL: [DefaultCheck; 4] = [Self::Type, Self::Range, Self::Allowed, Self::Enum];
}

impl Parameter {
    /// The default on node `node`: `node + default` for a node-relative default, else the default.
    pub fn default_on(&self, node: u8) -> Option<Number> {
        match (self.default?, self.default_plus_node_id) {
            (Number::Int(offset), true) => Some(Number::Int(offset.saturating_add(node.into()))),
            (d, _) => Some(d),
        }
    }

    /// Whether `value` fits this parameter's type.
    pub fn fits_type(&self, value: Number) -> bool {
        use super::DataType;
        match (self.data_type.integer_bounds(), value) {
            (Some((lo, hi)), Number::Int(i)) => (lo..=hi).contains(&i128::from(i)),
            (Some(_), Number::Float(_)) => false,
            (None, n) => match self.data_type {
                DataType::F32 => n.as_f64().abs() <= f64::from(f32::MAX),
                DataType::F64 => n.as_f64().is_finite(),
                _ => false,
            },
        }
    }
}

impl Device {
    /// Whether `p` accepts `value` as far as `check` goes.
    pub fn passes(&self, p: &Parameter, check: DefaultCheck, value: Number) -> bool {
        match check {
            DefaultCheck::Type => p.fits_type(value),
            DefaultCheck::Range => p.range.as_ref().is_none_or(|r| r.contains(value)),
            DefaultCheck::Allowed => p.allows(|a| value.compare(a)),
            DefaultCheck::Enum => {
                let declared = p.enumeration.as_deref().and_then(|n| self.enumeration(n));
                match (declared, value) {
                    (Some(e), Number::Int(i)) => e.values.iter().any(|d| d.value == i),
                    _ => true,
                }
            }
        }
    }

    /// For a node-relative default, the node IDs on which `p` passes `check` with its default;
    /// `None` when `p` has no node-relative default.
    pub fn default_node_ids_passing(&self, p: &Parameter, check: DefaultCheck) -> Option<NodeIds> {
        if !p.default_plus_node_id || !matches!(p.default, Some(Number::Int(_))) {
            return None;
        }
        Some(NodeIds::matching(|id| {
            p.default_on(id).is_some_and(|v| self.passes(p, check, v))
        }))
    }

    /// For a node-relative default, the node IDs on which `p` accepts its own default (type,
    /// range, allowed values, enum); `None` when `p` has no node-relative default.
    pub fn default_node_ids(&self, p: &Parameter) -> Option<NodeIds> {
        DefaultCheck::ALL
            .into_iter()
            .try_fold(NodeIds::ALL, |ids, check| {
                Some(ids.intersection(self.default_node_ids_passing(p, check)?))
            })
    }

    /// The parameters whose node-relative default their own limits refuse on node `node`, with
    /// the node IDs they allow: a drive described so should not be given that node ID, or its
    /// defaults are outside its own limits there (the drive's answer is reported, not guessed).
    pub fn defaults_refusing_node(&self, node: u8) -> Vec<(&Parameter, NodeIds)> {
        self.parameters
            .iter()
            .filter_map(|p| Some((p, self.default_node_ids(p)?)))
            .filter(|(_, ids)| !ids.contains(node))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sets_print_as_runs() {
        assert_eq!(NodeIds::ALL.to_string(), "1..=127");
        assert_eq!(NodeIds::NONE.to_string(), "none");
        assert_eq!(NodeIds::matching(|id| id <= 15).to_string(), "1..=15");
        let odd = NodeIds::matching(|id| id == 5 || (9..=10).contains(&id) || id == 127);
        assert_eq!(odd.to_string(), "5, 9..=10, 127");
        assert_eq!(odd.runs(), [(5, 5), (9, 10), (127, 127)]);
        assert!(!NodeIds::ALL.contains(0));
        assert!(NodeIds::ALL.contains(127));
        assert!(!NodeIds::ALL.contains(200));
        assert_eq!(NodeIds::ALL.iter().count(), 127);
        assert_eq!(
            NodeIds::matching(|id| id <= 15).complement().to_string(),
            "16..=127"
        );
        assert!(NodeIds::matching(|_| true).is_all());
        assert!(NodeIds::matching(|_| false).is_empty());
    }

    #[test]
    fn a_node_relative_default_is_checked_node_by_node() {
        let body = r#"
[[parameter]]
name = "cob_id"
type = "u32"
default = 0x181
range = [0x181, 0x18F]
canopen = { index = 0x1800, subindex = 1, access = "rw" }
source = { doc = "m", line = 1 }

[[parameter]]
name = "fixed"
type = "u32"
default = 0x181
range = [0x181, 0x18F]
canopen = { index = 0x1801, subindex = 1, access = "rw" }
source = { doc = "m", line = 1 }
"#;
        let mut device = crate::test_support::device(body);
        device.parameters[0].default = Some(Number::Int(0x180));
        device.parameters[0].default_plus_node_id = true;
        let (cob_id, fixed) = (&device.parameters[0], &device.parameters[1]);
        assert_eq!(cob_id.default_on(16), Some(Number::Int(0x190)));
        assert_eq!(fixed.default_on(16), Some(Number::Int(0x181)));
        let ids = device.default_node_ids(cob_id).unwrap();
        assert_eq!(ids.to_string(), "1..=15");
        assert_eq!(device.default_node_ids(fixed), None);
        assert!(device.defaults_refusing_node(15).is_empty());
        let refusing = device.defaults_refusing_node(16);
        assert_eq!(refusing.len(), 1);
        assert_eq!(
            (refusing[0].0.name.as_str(), refusing[0].1),
            ("cob_id", ids)
        );
    }
}
