//! The floor the benchmarks compare against: the least a Modbus client must do to send a 0x03
//! request and accept its answer, written by hand with a slice-by-16 CRC table and no abstraction.
//! Real clients (drivebus included) also validate more and frame more kinds of request; the
//! target is to stay within 1.2× of this.

pub mod flags;
pub mod latency;
pub mod mbap_sim;
pub mod process;
pub mod rs232;

/// CRC-16/MODBUS tables for slicing by 16: `TABLES[k][b]` is the CRC of byte `b` followed by `k`
/// zero bytes.
static TABLES: [[u16; 256]; 16] = tables();

const fn tables() -> [[u16; 256]; 16] {
    let mut t = [[0u16; 256]; 16];
    let mut b = 0;
    while b < 256 {
        let mut crc = b as u16;
        let mut bit = 0;
        while bit < 8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xA001
            } else {
                crc >> 1
            };
            bit += 1;
        }
        t[0][b] = crc;
        b += 1;
    }
    let mut k = 1;
    while k < 16 {
        let mut b = 0;
        while b < 256 {
            let prev = t[k - 1][b];
            t[k][b] = (prev >> 8) ^ t[0][(prev & 0xFF) as usize];
            b += 1;
        }
        k += 1;
    }
    t
}

/// CRC-16/MODBUS, 16 bytes per step.
pub fn crc16(data: &[u8]) -> u16 {
    let mut crc: u16 = 0xFFFF;
    let mut chunks = data.chunks_exact(16);
    for c in &mut chunks {
        let lo = c[0] ^ crc as u8;
        let hi = c[1] ^ (crc >> 8) as u8;
        crc = TABLES[15][lo as usize]
            ^ TABLES[14][hi as usize]
            ^ TABLES[13][c[2] as usize]
            ^ TABLES[12][c[3] as usize]
            ^ TABLES[11][c[4] as usize]
            ^ TABLES[10][c[5] as usize]
            ^ TABLES[9][c[6] as usize]
            ^ TABLES[8][c[7] as usize]
            ^ TABLES[7][c[8] as usize]
            ^ TABLES[6][c[9] as usize]
            ^ TABLES[5][c[10] as usize]
            ^ TABLES[4][c[11] as usize]
            ^ TABLES[3][c[12] as usize]
            ^ TABLES[2][c[13] as usize]
            ^ TABLES[1][c[14] as usize]
            ^ TABLES[0][c[15] as usize];
    }
    for &b in chunks.remainder() {
        crc = (crc >> 8) ^ TABLES[0][((crc as u8) ^ b) as usize];
    }
    crc
}

/// Encodes an RTU 0x03 request; returns its length (8).
pub fn rtu_encode(unit: u8, start: u16, count: u16, out: &mut [u8; 8]) -> usize {
    out[0] = unit;
    out[1] = 0x03;
    out[2..4].copy_from_slice(&start.to_be_bytes());
    out[4..6].copy_from_slice(&count.to_be_bytes());
    let crc = crc16(&out[..6]);
    out[6..8].copy_from_slice(&crc.to_le_bytes());
    8
}

/// Decodes an RTU 0x03 response into `out`; `None` if it is not the answer.
pub fn rtu_decode(unit: u8, frame: &[u8], out: &mut [u16]) -> Option<()> {
    let n = out.len();
    if frame.len() != 5 + 2 * n
        || frame[0] != unit
        || frame[1] != 0x03
        || frame[2] as usize != 2 * n
    {
        return None;
    }
    let body = frame.len() - 2;
    if crc16(&frame[..body]).to_le_bytes() != [frame[body], frame[body + 1]] {
        return None;
    }
    for (slot, pair) in out.iter_mut().zip(frame[3..body].chunks_exact(2)) {
        *slot = u16::from_be_bytes([pair[0], pair[1]]);
    }
    Some(())
}

/// Encodes an MBAP 0x03 request; returns its length (12).
pub fn tcp_encode(transaction: u16, unit: u8, start: u16, count: u16, out: &mut [u8; 12]) -> usize {
    out[0..2].copy_from_slice(&transaction.to_be_bytes());
    out[2..6].copy_from_slice(&[0, 0, 0, 6]);
    out[6] = unit;
    out[7] = 0x03;
    out[8..10].copy_from_slice(&start.to_be_bytes());
    out[10..12].copy_from_slice(&count.to_be_bytes());
    12
}

/// Decodes an MBAP 0x03 response into `out`; `None` if it is not the answer.
pub fn tcp_decode(transaction: u16, unit: u8, frame: &[u8], out: &mut [u16]) -> Option<()> {
    let n = out.len();
    if frame.len() != 9 + 2 * n
        || frame[0..2] != transaction.to_be_bytes()
        || frame[2..4] != [0, 0]
        || u16::from_be_bytes([frame[4], frame[5]]) as usize != 3 + 2 * n
        || frame[6] != unit
        || frame[7] != 0x03
        || frame[8] as usize != 2 * n
    {
        return None;
    }
    for (slot, pair) in out.iter_mut().zip(frame[9..].chunks_exact(2)) {
        *slot = u16::from_be_bytes([pair[0], pair[1]]);
    }
    Some(())
}

#[cfg(test)]
mod tests {
    #[test]
    fn floor_crc_matches_drivebus() {
        let data: Vec<u8> = (0..=255u8).collect();
        for len in 0..data.len() {
            assert_eq!(
                super::crc16(&data[..len]),
                drivebus::modbus::crc::crc16_modbus(&data[..len])
            );
        }
    }
}
