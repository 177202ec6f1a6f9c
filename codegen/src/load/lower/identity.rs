//! Lowering of `[identity]` (root file only).

use super::Lowering;
use crate::ir;
use crate::load::raw_identity::RawIdentity;

impl Lowering<'_> {
    /// The identity the description covers; out-of-range numbers are reported and left out.
    pub(super) fn expected_identity(&mut self, raw: &RawIdentity) -> ir::ExpectedIdentity {
        let revisions = raw.revisions.as_ref().and_then(|r| {
            let min = self.int_in::<u32>(&r.min, "revision number")?;
            let max = self.int_in::<u32>(&r.max, "revision number")?;
            Some((min, max))
        });
        ir::ExpectedIdentity {
            vendor_id: raw
                .vendor_id
                .as_ref()
                .and_then(|v| self.int_in::<u32>(v, "vendor-ID")),
            product_code: raw
                .product_code
                .as_ref()
                .and_then(|v| self.int_in::<u32>(v, "product code")),
            revisions,
            parameter: raw.parameter.as_ref().map(|p| p.get_ref().clone()),
            values: raw.values.iter().map(|v| *v.get_ref()).collect(),
            source: raw.source.as_ref().and_then(|c| self.citation(c)),
        }
    }
}
