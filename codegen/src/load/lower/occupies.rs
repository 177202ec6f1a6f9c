//! Lowering of a Modbus address's `occupies`: how many registers of the map a value takes from its
//! address. Usually its word count; fewer where the device answers a multi-word read at a single
//! address (Lenze smd C99, a 4-word read at one register, guide lines 229 and 833-836).

use toml::Spanned;

use super::{Lowering, VALUE_RULE};
use crate::diagnostic::Span;

impl Lowering<'_> {
    /// `occupies` of an address of `words` words: 1..=words, `words` when left out.
    pub(super) fn occupied_registers(
        &mut self,
        occupies: Option<i64>,
        words: u16,
        span: &Span,
    ) -> Option<u16> {
        let Some(occupies) = occupies else {
            return Some(words);
        };
        let value = self.int_in::<u16>(&Spanned::new(span.range.clone(), occupies), "occupies")?;
        if value == 0 || value > words {
            self.error_help(
                VALUE_RULE,
                span.clone(),
                format!("`occupies = {value}` must lie within 1..={words} (the value's words)"),
                "`occupies` is the number of registers the value takes in the map; leave it out when it is `words`",
            );
            return None;
        }
        Some(value)
    }
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::{device, messages};

    const PACKED: &str = r#"
[[parameter]]
name = "software_version"
type = "string"
length = 8
modbus = { table = "holding", address = 89, words = 4, occupies = 1, access = "r" }
source = { doc = "m", line = 1 }
[[parameter]]
name = "next"
type = "u16"
modbus = { table = "holding", address = 90 }
source = { doc = "m", line = 1 }
"#;

    #[test]
    fn a_packed_read_leaves_its_neighbours_free() {
        let device = device(PACKED);
        let version = &device.parameters[0].modbus[0];
        assert_eq!((version.words, version.occupies), (4, 1));
        assert_eq!(device.parameters[1].modbus[0].occupies, 1);
    }

    #[test]
    fn without_occupies_the_words_overlap() {
        let body = PACKED.replace(", occupies = 1", "");
        assert_eq!(
            messages("addresses_do_not_overlap", &body),
            ["holding register 0x005a of `next` overlaps `software_version` at 0x0059"]
        );
    }

    #[test]
    fn occupies_beyond_the_words_is_refused() {
        let body = PACKED.replace("occupies = 1", "occupies = 5");
        assert_eq!(
            messages("values_are_well_formed", &body),
            ["`occupies = 5` must lie within 1..=4 (the value's words)"]
        );
        let body = PACKED.replace("occupies = 1", "occupies = 0");
        assert_eq!(
            messages("values_are_well_formed", &body),
            ["`occupies = 0` must lie within 1..=4 (the value's words)"]
        );
    }
}
