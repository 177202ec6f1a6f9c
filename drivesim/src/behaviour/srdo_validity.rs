//! CANopen Safety: changing an SRDO's configuration invalidates the safety configuration. "As
//! soon as the configuration of an SRDO has been modified, the object '13FE 00h Configuration
//! valid' automatically switches to the invalid state '00h'" (SWD manual line 3581).

use super::{object, Behaviour, Shared};
use crate::store::{ParamId, Store};

/// The configuration-valid object, 13FEh sub 0.
const CONFIGURATION_VALID: (u16, u8) = (0x13FE, 0);

/// SRDO communication (1301h..1340h) and mapping (1381h..13C0h) objects.
fn is_srdo_configuration(index: u16) -> bool {
    matches!(index, 0x1301..=0x1340 | 0x1381..=0x13C0)
}

/// Present when the description has 13FEh.
#[derive(Debug)]
pub struct SrdoValidity {
    valid: ParamId,
}

impl SrdoValidity {
    /// Present when the description has the configuration-valid object.
    pub fn detect(store: &Store) -> Option<Self> {
        object(store, CONFIGURATION_VALID.0, CONFIGURATION_VALID.1).map(|valid| Self { valid })
    }
}

impl Behaviour for SrdoValidity {
    fn written(&mut self, store: &mut Store, _shared: &mut Shared, id: ParamId) {
        let touched = store
            .parameter(id)
            .canopen
            .iter()
            .any(|a| is_srdo_configuration(a.index));
        if touched {
            store.set_int(self.valid, 0);
        }
    }
}
