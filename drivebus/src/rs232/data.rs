//! The data protocol: the 8 bytes of a telegram, "compatible with the CANopen SDO protocol"
//! (manual lines 2224–2320).
//!
//! | byte | 0 | 1–2 | 3 | 4–7 |
//! | --- | --- | --- | --- | --- |
//! | content | command | index, low byte first | subindex | data, low byte first |
//!
//! Requests: upload (read) `40h`; download (write) `2Fh` / `2Bh` / `23h` with 1, 2 or 4 data
//! bytes. Answers: `4Fh` / `4Bh` / `43h` with 1, 2 or 4 data bytes to an upload, `60h` to a
//! download, `80h` "error, bytes 4…7 contain error cause" to either. The manual gives no other
//! widths (no 3-byte command), so none is sent or accepted.

use super::telegram::{Data, DATA_LEN};
use super::Rs232Error;

/// Command bytes of the data protocol (manual lines 2245–2317).
pub mod command {
    /// Upload request: "40(hex) always" (line 2292).
    pub const UPLOAD: u8 = 0x40;
    /// Download of 4 bytes (line 2245).
    pub const DOWNLOAD_4: u8 = 0x23;
    /// Download of 2 bytes.
    pub const DOWNLOAD_2: u8 = 0x2B;
    /// Download of 1 byte.
    pub const DOWNLOAD_1: u8 = 0x2F;
    /// Upload answer with 4 bytes (line 2311).
    pub const UPLOADED_4: u8 = 0x43;
    /// Upload answer with 2 bytes.
    pub const UPLOADED_2: u8 = 0x4B;
    /// Upload answer with 1 byte.
    pub const UPLOADED_1: u8 = 0x4F;
    /// Download answer: "Data successfully sent" (line 2268).
    pub const DOWNLOADED: u8 = 0x60;
    /// Error answer to either request (lines 2270, 2317).
    pub const ERROR: u8 = 0x80;
}

/// How many data bytes a value occupies: the widths the protocol has commands for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Width {
    /// 8 bits.
    One,
    /// 16 bits.
    Two,
    /// 32 bits.
    Four,
}

impl Width {
    /// The width of a value of `bytes` bytes, if the protocol can carry it.
    #[inline]
    pub const fn of(bytes: usize) -> Option<Self> {
        match bytes {
            1 => Some(Self::One),
            2 => Some(Self::Two),
            4 => Some(Self::Four),
            _ => None,
        }
    }

    /// The number of bytes.
    #[inline]
    pub const fn bytes(self) -> usize {
        match self {
            Self::One => 1,
            Self::Two => 2,
            Self::Four => 4,
        }
    }

    #[inline]
    const fn download_command(self) -> u8 {
        match self {
            Self::One => command::DOWNLOAD_1,
            Self::Two => command::DOWNLOAD_2,
            Self::Four => command::DOWNLOAD_4,
        }
    }

    #[inline]
    const fn uploaded_command(self) -> u8 {
        match self {
            Self::One => command::UPLOADED_1,
            Self::Two => command::UPLOADED_2,
            Self::Four => command::UPLOADED_4,
        }
    }

    #[inline]
    const fn from_download_command(command: u8) -> Option<Self> {
        match command {
            command::DOWNLOAD_1 => Some(Self::One),
            command::DOWNLOAD_2 => Some(Self::Two),
            command::DOWNLOAD_4 => Some(Self::Four),
            _ => None,
        }
    }

    #[inline]
    pub(super) const fn from_uploaded_command(command: u8) -> Option<Self> {
        match command {
            command::UPLOADED_1 => Some(Self::One),
            command::UPLOADED_2 => Some(Self::Two),
            command::UPLOADED_4 => Some(Self::Four),
            _ => None,
        }
    }
}

/// A value of 1, 2 or 4 bytes, little-endian, as bytes 4–7 carry it (unused bytes are zero).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Value {
    width: Width,
    bytes: [u8; 4],
}

impl Value {
    /// The value held in `bytes` (1, 2 or 4 of them, little-endian).
    #[inline]
    pub fn new(bytes: &[u8]) -> Result<Self, Rs232Error> {
        let width =
            Width::of(bytes.len()).ok_or(Rs232Error::UnsupportedWidth { bytes: bytes.len() })?;
        let mut padded = [0u8; 4];
        padded[..bytes.len()].copy_from_slice(bytes);
        Ok(Self {
            width,
            bytes: padded,
        })
    }

    /// How many bytes the value occupies.
    #[inline]
    pub fn width(&self) -> Width {
        self.width
    }

    /// The value's little-endian bytes.
    #[inline]
    pub fn as_bytes(&self) -> &[u8] {
        &self.bytes[..self.width.bytes()]
    }

    #[inline]
    pub(super) fn from_data(width: Width, data: &Data) -> Self {
        // Whole-word masking instead of a copy of variable length (a `memcpy` call).
        let all = u32::from_le_bytes([data[4], data[5], data[6], data[7]]);
        let mask = u32::MAX >> (32 - 8 * width.bytes() as u32);
        Self {
            width,
            bytes: (all & mask).to_le_bytes(),
        }
    }

    /// The value zero-extended to 32 bits.
    #[inline]
    pub fn to_u32(&self) -> u32 {
        u32::from_le_bytes(self.bytes)
    }
}

/// An object dictionary entry as the data protocol addresses it: 16-bit index, 8-bit subindex.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Object {
    /// Object index.
    pub index: u16,
    /// Subindex.
    pub subindex: u8,
}

impl Object {
    #[inline]
    fn write_to(self, data: &mut Data) {
        data[1..3].copy_from_slice(&self.index.to_le_bytes());
        data[3] = self.subindex;
    }

    #[inline]
    pub(super) fn read_from(data: &Data) -> Self {
        Self {
            index: u16::from_le_bytes([data[1], data[2]]),
            subindex: data[3],
        }
    }
}

/// What the host asks of a drive.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Request {
    /// Read an object (command `40h`).
    Upload(Object),
    /// Write a value to an object (command `2Fh`, `2Bh` or `23h` by its width).
    Download(Object, Value),
}

impl Request {
    /// A read of `index`:`subindex`.
    #[inline]
    pub const fn upload(index: u16, subindex: u8) -> Self {
        Self::Upload(Object { index, subindex })
    }

    /// A write of the little-endian `bytes` (1, 2 or 4 of them) to `index`:`subindex`.
    #[inline]
    pub fn download(index: u16, subindex: u8, bytes: &[u8]) -> Result<Self, Rs232Error> {
        Ok(Self::Download(
            Object { index, subindex },
            Value::new(bytes)?,
        ))
    }

    /// The object the request addresses.
    #[inline]
    pub const fn object(&self) -> Object {
        match self {
            Self::Upload(object) | Self::Download(object, _) => *object,
        }
    }

    /// The 8 data bytes of the request.
    #[inline]
    pub fn encode(&self) -> Data {
        let mut data = [0u8; DATA_LEN];
        match self {
            Self::Upload(object) => {
                data[0] = command::UPLOAD;
                object.write_to(&mut data);
            }
            Self::Download(object, value) => {
                data[0] = value.width.download_command();
                object.write_to(&mut data);
                data[4..8].copy_from_slice(&value.bytes);
            }
        }
        data
    }

    /// The request in 8 data bytes, as a drive reads it; the unused bytes of an upload and the
    /// bytes past a download's width are ignored.
    #[inline]
    pub fn decode(data: &Data) -> Result<Self, Rs232Error> {
        let object = Object::read_from(data);
        match data[0] {
            command::UPLOAD => Ok(Self::Upload(object)),
            other => match Width::from_download_command(other) {
                Some(width) => Ok(Self::Download(object, Value::from_data(width, data))),
                None => Err(Rs232Error::UnexpectedCommand { command: other }),
            },
        }
    }
}

/// What a drive answers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Answer {
    /// The value of an uploaded object (command `4Fh`, `4Bh` or `43h`).
    Uploaded(Object, Value),
    /// A download was carried out (command `60h`).
    Downloaded(Object),
    /// The request failed (command `80h`); `cause` is bytes 4–7 read little-endian. The manual
    /// calls the protocol SDO-compatible and lists no causes of its own: they read as CiA 301
    /// abort codes.
    Refused(Object, u32),
}

impl Answer {
    /// The object the answer is about.
    #[inline]
    pub const fn object(&self) -> Object {
        match self {
            Self::Uploaded(object, _) | Self::Downloaded(object) | Self::Refused(object, _) => {
                *object
            }
        }
    }

    /// The uploaded value's little-endian bytes, if this answer carries one.
    #[inline]
    pub fn value(&self) -> Option<&[u8]> {
        match self {
            Self::Uploaded(_, value) => Some(value.as_bytes()),
            _ => None,
        }
    }

    /// The 8 data bytes of the answer; reserved bytes are zero.
    #[inline]
    pub fn encode(&self) -> Data {
        let mut data = [0u8; DATA_LEN];
        self.object().write_to(&mut data);
        match self {
            Self::Uploaded(_, value) => {
                data[0] = value.width.uploaded_command();
                data[4..8].copy_from_slice(&value.bytes);
            }
            Self::Downloaded(_) => data[0] = command::DOWNLOADED,
            Self::Refused(_, cause) => {
                data[0] = command::ERROR;
                data[4..8].copy_from_slice(&cause.to_le_bytes());
            }
        }
        data
    }

    /// The answer `data` gives to the `request` it follows: about the request's object (else
    /// [`Rs232Error::OtherObject`]), an upload's value or a download's confirmation as the
    /// request's command asks (else [`Rs232Error::UnexpectedCommand`]), and an error answer as
    /// [`Rs232Error::Refused`]. Decodes only what may answer the request, so an exchange does
    /// not build a general [`Answer`] first and compare it afterwards.
    pub fn reply_to(request: &Data, data: &Data) -> Result<Self, Rs232Error> {
        if data[1..4] != request[1..4] {
            let other = Object::read_from(data);
            return Err(Rs232Error::OtherObject {
                index: other.index,
                subindex: other.subindex,
            });
        }
        let object = Object::read_from(request);
        let upload = request[0] == command::UPLOAD;
        match data[0] {
            command::ERROR => Err(Rs232Error::Refused {
                cause: u32::from_le_bytes([data[4], data[5], data[6], data[7]]),
            }),
            command::DOWNLOADED if !upload => Ok(Self::Downloaded(object)),
            other => match Width::from_uploaded_command(other) {
                Some(width) if upload => Ok(Self::Uploaded(object, Value::from_data(width, data))),
                _ => Err(Rs232Error::UnexpectedCommand { command: other }),
            },
        }
    }

    /// The answer in 8 data bytes; reserved bytes and bytes past the width are ignored.
    #[inline]
    pub fn decode(data: &Data) -> Result<Self, Rs232Error> {
        let object = Object::read_from(data);
        match data[0] {
            command::DOWNLOADED => Ok(Self::Downloaded(object)),
            command::ERROR => Ok(Self::Refused(
                object,
                u32::from_le_bytes([data[4], data[5], data[6], data[7]]),
            )),
            other => match Width::from_uploaded_command(other) {
                Some(width) => Ok(Self::Uploaded(object, Value::from_data(width, data))),
                None => Err(Rs232Error::UnexpectedCommand { command: other }),
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn width() -> impl Strategy<Value = usize> {
        prop_oneof![Just(1usize), Just(2), Just(4)]
    }

    fn object() -> impl Strategy<Value = Object> {
        (any::<u16>(), any::<u8>()).prop_map(|(index, subindex)| Object { index, subindex })
    }

    fn value() -> impl Strategy<Value = Value> {
        (width(), any::<[u8; 4]>()).prop_map(|(w, bytes)| Value::new(&bytes[..w]).unwrap())
    }

    fn request() -> impl Strategy<Value = Request> {
        prop_oneof![
            object().prop_map(Request::Upload),
            (object(), value()).prop_map(|(o, v)| Request::Download(o, v)),
        ]
    }

    fn answer() -> impl Strategy<Value = Answer> {
        prop_oneof![
            (object(), value()).prop_map(|(o, v)| Answer::Uploaded(o, v)),
            object().prop_map(Answer::Downloaded),
            (object(), any::<u32>()).prop_map(|(o, c)| Answer::Refused(o, c)),
        ]
    }

    #[test]
    fn only_widths_with_a_command_are_carried() {
        for bytes in [0, 3, 5, 8] {
            assert_eq!(
                Request::download(0x6040, 0, &[0; 8][..bytes]),
                Err(Rs232Error::UnsupportedWidth { bytes })
            );
        }
    }

    #[test]
    fn an_error_answer_carries_its_cause_little_endian() {
        let data = [0x80, 0x41, 0x60, 0x00, 0x00, 0x00, 0x02, 0x06];
        assert_eq!(
            Answer::decode(&data),
            Ok(Answer::Refused(
                Object {
                    index: 0x6041,
                    subindex: 0
                },
                0x0602_0000
            ))
        );
    }

    #[test]
    fn a_request_is_not_an_answer() {
        let upload = Request::upload(0x6041, 0).encode();
        assert_eq!(
            Answer::decode(&upload),
            Err(Rs232Error::UnexpectedCommand { command: 0x40 })
        );
    }

    proptest! {
        #[test]
        fn requests_round_trip(request in request()) {
            prop_assert_eq!(Request::decode(&request.encode()), Ok(request));
        }

        #[test]
        fn answers_round_trip(answer in answer()) {
            prop_assert_eq!(Answer::decode(&answer.encode()), Ok(answer));
        }

        #[test]
        fn any_data_decodes_or_fails_without_panic(data: [u8; 8]) {
            let _ = Request::decode(&data);
            let _ = Answer::decode(&data);
        }
    }
}
