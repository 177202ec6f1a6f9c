//! The predefined connection set (CiA 301 §7.3.5): the COB-IDs a node's first four PDOs have
//! by default.

/// The default COB-ID of PDO `number` of `node`: TPDO n at 180h/280h/380h/480h + node id,
/// RPDO n at 200h/300h/400h/500h + node id, for n = 1-4; other numbers have none (`None`).
/// `transmit` is seen from the node (its TPDOs).
pub const fn predefined_pdo_cob_id(transmit: bool, number: u16, node: u8) -> Option<u32> {
    if number < 1 || number > 4 {
        return None;
    }
    let base = if transmit { 0x080 } else { 0x100 };
    Some(base + 0x100 * number as u32 + node as u32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pdos_1_to_4_have_a_default_cob_id() {
        assert_eq!(predefined_pdo_cob_id(true, 1, 5), Some(0x185));
        assert_eq!(predefined_pdo_cob_id(true, 4, 5), Some(0x485));
        assert_eq!(predefined_pdo_cob_id(false, 1, 127), Some(0x27F));
        assert_eq!(predefined_pdo_cob_id(false, 4, 1), Some(0x501));
        assert_eq!(predefined_pdo_cob_id(true, 5, 1), None);
        assert_eq!(predefined_pdo_cob_id(false, 0, 1), None);
    }
}
