//! An independent CRC-16/MODBUS for the manuals' frame tests: written out bit by bit, so it shares
//! nothing with the table-driven implementation in `drivebus` that those tests check.

/// CRC-16/MODBUS (polynomial 0xA001 reflected, initial value 0xFFFF).
pub fn crc16_modbus(bytes: &[u8]) -> u16 {
    let mut crc = 0xFFFFu16;
    for &byte in bytes {
        crc ^= u16::from(byte);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xA001
            } else {
                crc >> 1
            };
        }
    }
    crc
}

/// The frame bytes followed by their CRC, low byte first, as it goes on the wire.
pub fn with_crc(bytes: &[u8]) -> Vec<u8> {
    let mut frame = bytes.to_vec();
    frame.extend_from_slice(&crc16_modbus(bytes).to_le_bytes());
    frame
}

/// The frame bytes followed by their CRC, high byte first, as some manuals print it.
pub fn with_crc_as_printed(bytes: &[u8]) -> Vec<u8> {
    let mut frame = bytes.to_vec();
    frame.extend_from_slice(&crc16_modbus(bytes).to_be_bytes());
    frame
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_reference_crc_is_crc16_modbus() {
        // The catalogue check value of CRC-16/MODBUS, and the classic "01 03 00 00 00 0A" → C5 CD.
        assert_eq!(crc16_modbus(b"123456789"), 0x4B37);
        assert_eq!(
            with_crc(&[0x01, 0x03, 0x00, 0x00, 0x00, 0x0A])[6..],
            [0xC5, 0xCD]
        );
    }

    #[test]
    fn the_crc_goes_low_byte_first_on_the_wire() {
        let crc = crc16_modbus(&[0x01, 0x03]).to_le_bytes();
        assert_eq!(with_crc(&[0x01, 0x03]), [0x01, 0x03, crc[0], crc[1]]);
        assert_eq!(
            with_crc_as_printed(&[0x01, 0x03]),
            [0x01, 0x03, crc[1], crc[0]]
        );
    }
}
