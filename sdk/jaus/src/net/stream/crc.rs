//! The CRC of JSerial's two checksums: CRC-16 with the CCITT polynomial x¹⁶ + x¹² + x⁵ +
//! 1 processed least significant bit first (0x8408 reflected), no final XOR: the
//! catalogue's CRC-16/MCRF4XX when started from 0xFFFF. The JAUS Tool Set's runtime
//! computes it byte-wise (`crc_accumulate` in its `ChecksumCRC.cpp`, which says it
//! follows SAE AS5669); this one is bit-wise and gives the same values.

/// The CRC of `bytes` continued from `init` (0xFFFF for a new one).
///
/// ```
/// // The catalogue's check value of CRC-16/MCRF4XX.
/// assert_eq!(jaus::net::stream::crc16(0xFFFF, b"123456789"), 0x6F91);
/// ```
pub fn crc16(init: u16, bytes: &[u8]) -> u16 {
    let mut crc = init;
    for &b in bytes {
        crc ^= u16::from(b);
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0x8408
            } else {
                crc >> 1
            };
        }
    }
    crc
}

#[cfg(test)]
mod tests {
    use super::crc16;

    #[test]
    fn continues_where_it_stopped() {
        let whole = crc16(0xFFFF, b"JAUS serial line");
        let part = crc16(0xFFFF, b"JAUS ser");
        assert_eq!(crc16(part, b"ial line"), whole);
        assert_eq!(crc16(0x1234, b""), 0x1234);
    }
}
