//! What a network's node handle does with a request for another node: refuses it, since the
//! handle's node is its channel.

use crate::canopen::address::NodeId;
use crate::error::BusError;

/// `Ok` when `asked` is the handle's `own` node.
pub(crate) fn own_node(own: NodeId, asked: NodeId) -> Result<(), BusError> {
    if own == asked {
        Ok(())
    } else {
        Err(BusError::Unsupported(
            "a network node handle transfers to its own node only",
        ))
    }
}
