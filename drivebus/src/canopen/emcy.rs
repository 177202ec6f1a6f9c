//! EMCY (CiA 301 §7.2.7): decoding emergency frames and naming their error codes.

use super::address::NodeId;
use super::frame::{cob, CanFrame};

/// A decoded emergency message.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Emcy {
    /// The node that sent it.
    pub node: NodeId,
    /// Emergency error code; 0x0000 = error reset / no error.
    pub code: u16,
    /// Error register (object 0x1001) at the time of the error.
    pub register: ErrorRegister,
    /// Manufacturer-specific error field.
    pub manufacturer: [u8; 5],
}

crate::bitflags::bitflags! {
    /// The error register (object 0x1001).
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
    pub struct ErrorRegister: u8 {
        /// Generic error.
        const GENERIC = 0x01;
        /// Current.
        const CURRENT = 0x02;
        /// Voltage.
        const VOLTAGE = 0x04;
        /// Temperature.
        const TEMPERATURE = 0x08;
        /// Communication error (overrun, error state).
        const COMMUNICATION = 0x10;
        /// Device-profile specific.
        const PROFILE = 0x20;
        /// Manufacturer specific.
        const MANUFACTURER = 0x80;
    }
}

impl Emcy {
    /// Decodes an EMCY frame (COB-ID 0x081..=0x0FF, 8 bytes); `None` for any other frame.
    /// SYNC (0x080) shares the function code and is not an EMCY.
    pub fn decode(frame: &CanFrame) -> Option<Self> {
        let id = frame.id();
        if frame.is_remote() || frame.dlc() != 8 || !(cob::EMCY + 1..=cob::EMCY + 127).contains(&id)
        {
            return None;
        }
        let d = frame.padded();
        Some(Self {
            node: NodeId((id - cob::EMCY) as u8),
            code: u16::from_le_bytes([d[0], d[1]]),
            register: ErrorRegister::from_bits_retain(d[2]),
            manufacturer: [d[3], d[4], d[5], d[6], d[7]],
        })
    }

    /// The frame `node` sends for this emergency.
    pub fn encode(&self) -> CanFrame {
        let [lo, hi] = self.code.to_le_bytes();
        let m = self.manufacturer;
        CanFrame::full(
            cob::EMCY + u16::from(self.node.0),
            [lo, hi, self.register.bits(), m[0], m[1], m[2], m[3], m[4]],
        )
    }

    /// Whether this message clears the node's errors (code 0x00xx).
    pub const fn is_reset(&self) -> bool {
        self.code & 0xFF00 == 0
    }

    /// The meaning of the code: the drive's own table first, then the generic CiA 301/402 one.
    pub fn meaning<T: EmcyTable + ?Sized>(&self, drive: &T) -> &'static str {
        describe(self.code, drive)
    }
}

/// A drive's own emergency codes; generated crates implement it (or pass a slice).
pub trait EmcyTable {
    /// The meaning of `code`, if the drive defines one.
    fn meaning(&self, code: u16) -> Option<&'static str>;
}

/// A table as `(code, meaning)` pairs, e.g. a generated `static EMCY: [(u16, &str); N]`.
impl EmcyTable for [(u16, &'static str)] {
    fn meaning(&self, code: u16) -> Option<&'static str> {
        self.iter().find(|(c, _)| *c == code).map(|(_, m)| *m)
    }
}

impl<const N: usize> EmcyTable for [(u16, &'static str); N] {
    fn meaning(&self, code: u16) -> Option<&'static str> {
        self.as_slice().meaning(code)
    }
}

impl<T: EmcyTable + ?Sized> EmcyTable for &T {
    fn meaning(&self, code: u16) -> Option<&'static str> {
        (**self).meaning(code)
    }
}

/// No drive-specific codes.
impl EmcyTable for () {
    fn meaning(&self, _code: u16) -> Option<&'static str> {
        None
    }
}

/// Generic codes of CiA 301 (table 21) and common CiA 402 codes, most specific first within a
/// class so that an unlisted code falls back to its class.
pub static GENERIC: &[(u16, &str)] = &[
    (0x0000, "error reset or no error"),
    (0x1000, "generic error"),
    (0x2000, "current"),
    (0x2100, "current, device input side"),
    (0x2200, "current inside the device"),
    (0x2300, "current, device output side"),
    (0x2310, "continuous over-current"),
    (0x2320, "short circuit / earth leakage"),
    (0x2330, "earth leakage"),
    (0x2340, "short circuit"),
    (0x3000, "voltage"),
    (0x3100, "mains voltage"),
    (0x3200, "voltage inside the device"),
    (0x3210, "DC link over-voltage"),
    (0x3220, "DC link under-voltage"),
    (0x3300, "output voltage"),
    (0x4000, "temperature"),
    (0x4100, "ambient temperature"),
    (0x4200, "device temperature"),
    (0x4210, "excess temperature device"),
    (0x4300, "drive temperature"),
    (0x4310, "excess temperature drive"),
    (0x5000, "device hardware"),
    (0x5500, "data storage"),
    (0x6000, "device software"),
    (0x6100, "internal software"),
    (0x6200, "user software"),
    (0x6300, "data set"),
    (0x6320, "parameter error"),
    (0x7000, "additional modules"),
    (0x7100, "power"),
    (0x7120, "motor"),
    (0x7121, "motor blocked"),
    (0x7300, "sensor"),
    (0x7305, "incremental sensor 1 fault"),
    (0x7310, "speed"),
    (0x7320, "position"),
    (0x8000, "monitoring"),
    (0x8100, "communication"),
    (0x8110, "CAN overrun (objects lost)"),
    (0x8120, "CAN in error passive mode"),
    (0x8130, "life guard error or heartbeat error"),
    (0x8140, "recovered from bus off"),
    (0x8150, "CAN-ID collision"),
    (0x8200, "protocol error"),
    (0x8210, "PDO not processed due to length error"),
    (0x8220, "PDO length exceeded"),
    (
        0x8230,
        "DAM MPDO not processed, destination object not available",
    ),
    (0x8240, "unexpected SYNC data length"),
    (0x8250, "RPDO timeout"),
    (0x8400, "velocity speed controller"),
    (0x8500, "position controller"),
    (0x8600, "positioning controller"),
    (0x8611, "following error"),
    (0x8612, "reference limit"),
    (0x9000, "external error"),
    (0xF000, "additional functions"),
    (0xFF00, "device specific"),
];

/// The meaning of an emergency code: the drive's table, then the generic table by exact code,
/// then by class (high byte, then high nibble).
pub fn describe<T: EmcyTable + ?Sized>(code: u16, drive: &T) -> &'static str {
    drive
        .meaning(code)
        .or_else(|| GENERIC.meaning(code))
        .or_else(|| GENERIC.meaning(code & 0xFF00))
        .or_else(|| GENERIC.meaning(code & 0xF000))
        .unwrap_or("unknown error code")
}

#[cfg(test)]
mod tests {
    use super::*;

    static DRIVE: [(u16, &str); 2] = [
        (0x8611, "drive: following error window exceeded"),
        (0xFF01, "drive: encoder cable"),
    ];

    #[test]
    fn decodes_code_register_and_manufacturer_bytes() {
        let frame = CanFrame::new(0x081, &[0x10, 0x23, 0x03, 1, 2, 3, 4, 5]).unwrap();
        let emcy = Emcy::decode(&frame).unwrap();
        assert_eq!(emcy.node, NodeId(1));
        assert_eq!(emcy.code, 0x2310);
        assert_eq!(
            emcy.register,
            ErrorRegister::GENERIC | ErrorRegister::CURRENT
        );
        assert_eq!(emcy.manufacturer, [1, 2, 3, 4, 5]);
        assert_eq!(emcy.meaning(&()), "continuous over-current");
        assert!(!emcy.is_reset());
        assert_eq!(emcy.encode(), frame);
    }

    #[test]
    fn the_drive_table_wins_and_classes_are_a_fallback() {
        assert_eq!(
            describe(0x8611, &DRIVE),
            "drive: following error window exceeded"
        );
        assert_eq!(describe(0x8611, &()), "following error");
        assert_eq!(describe(0xFF01, &DRIVE[..]), "drive: encoder cable");
        assert_eq!(describe(0xFF7A, &()), "device specific");
        assert_eq!(describe(0x3105, &()), "mains voltage");
        assert_eq!(describe(0x9ABC, &()), "external error");
        assert_eq!(describe(0x0000, &()), "error reset or no error");
        // The Lafert drive reports "state of CAN" with 0x8170 at start-up: class "communication".
        assert_eq!(describe(0x8170, &()), "communication");
    }

    #[test]
    fn sync_and_short_frames_are_not_emcy() {
        assert_eq!(Emcy::decode(&CanFrame::new(0x080, &[0; 8]).unwrap()), None);
        assert_eq!(Emcy::decode(&CanFrame::new(0x085, &[0; 4]).unwrap()), None);
        assert_eq!(Emcy::decode(&CanFrame::new(0x100, &[0; 8]).unwrap()), None);
        let reset = Emcy::decode(&CanFrame::new(0x085, &[0; 8]).unwrap()).unwrap();
        assert!(reset.is_reset());
    }
}
