//! A read block (`[modbus] read_blocks`) covers only registers the description lists as readable
//! in every variant, so every word it returns decodes as a described parameter; a `zero_fill`
//! block may also cover registers no parameter occupies (answered as 0).

use crate::diagnostic::Diagnostic;
use crate::ir::{Device, ModbusAddress, Parameter, ReadBlock};

const RULE: &str = super::rule_name(module_path!());

/// Whether `a` of `p` is readable in every variant and occupies `register` of its table.
fn covers(p: &Parameter, a: &ModbusAddress, block: &ReadBlock, register: u32) -> bool {
    let start = u32::from(a.address);
    a.table == block.table
        && a.access.read
        && a.variant.is_none()
        && p.variants.is_empty()
        && (start..start + u32::from(a.occupies)).contains(&register)
}

/// Whether any address of any parameter occupies `register` of the block's table.
fn occupied(device: &Device, block: &ReadBlock, register: u32) -> bool {
    device.parameters.iter().flat_map(|p| &p.modbus).any(|a| {
        let start = u32::from(a.address);
        a.table == block.table && (start..start + u32::from(a.occupies)).contains(&register)
    })
}

/// Reports block registers that no readable, variant-independent parameter occupies (in a
/// `zero_fill` block: that a parameter occupies without being readable in every variant).
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let Some(caps) = &device.modbus else {
        return Vec::new();
    };
    caps.read_blocks
        .iter()
        .filter_map(|block| {
            let missing = block.registers().find(|&r| {
                let readable = device
                    .parameters
                    .iter()
                    .any(|p| p.modbus.iter().any(|a| covers(p, a, block, r)));
                // A zero-fill block may also cover registers nothing occupies.
                let unoccupied_and_filled = block.zero_fill && !occupied(device, block, r);
                !(readable || unoccupied_and_filled)
            })?;
            let message = format!(
                "the read block at {:#06x} covers register {missing:#06x}, which no parameter readable in every variant occupies",
                block.address
            )
            .to_lowercase();
            Some(
                Diagnostic::error(RULE, block.span.clone(), message)
                    .help("describe every register the block returns, or shorten the block"),
            )
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::{device, messages};

    fn body(words: u16) -> String {
        let mut body = format!(
            "[modbus]\nmax_read_registers = 1\nread_blocks = [{{ table = \"holding\", address = 24, words = {words} }}]\n"
        );
        for r in 24..27 {
            body.push_str(&format!(
                "[[parameter]]\nname = \"r{r}\"\ntype = \"u16\"\nmodbus = {{ table = \"holding\", address = {r}, access = \"r\" }}\nsource = {{ doc = \"m\", line = 1 }}\n"
            ));
        }
        body
    }

    #[test]
    fn a_block_over_described_registers_is_kept() {
        let device = device(&body(3));
        let block = &device.modbus.unwrap().read_blocks[0];
        assert_eq!((block.address, block.words), (24, 3));
    }

    #[test]
    fn a_block_past_the_described_registers_is_reported() {
        assert_eq!(
            messages(RULE, &body(4)),
            ["the read block at 0x0018 covers register 0x001b, which no parameter readable in every variant occupies"]
        );
    }

    #[test]
    fn a_zero_fill_block_may_cover_unoccupied_registers() {
        let zero_fill = body(4).replace("words = 4 }", "words = 4, zero_fill = true }");
        assert!(messages(RULE, &zero_fill).is_empty());
    }

    #[test]
    fn a_zero_fill_block_still_refuses_an_unreadable_register() {
        let zero_fill = body(4).replace("words = 4 }", "words = 4, zero_fill = true }")
            + "[[parameter]]\nname = \"w27\"\ntype = \"u16\"\nmodbus = { table = \"holding\", address = 27, access = \"w\" }\nsource = { doc = \"m\", line = 1 }\n";
        assert_eq!(
            messages(RULE, &zero_fill),
            ["the read block at 0x0018 covers register 0x001b, which no parameter readable in every variant occupies"]
        );
    }

    #[test]
    fn a_block_of_one_word_is_malformed() {
        assert_eq!(
            messages("values_are_well_formed", &body(1)),
            ["a read block of 1 words"]
        );
    }
}
