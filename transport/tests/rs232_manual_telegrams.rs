//! Every request telegram the Kinco FD manual prints (`003_8cc8f7f4f05b8633.txt`, section 9.4,
//! lines 2330–2365), encoded from its meaning and decoded back.
//!
//! Line 2359 prints the Statusword read with 9 bytes, `01 40 41 60 00 00 00 00 1E`. Decision:
//! one of the four reserved zero bytes was lost in print. Telegrams have a fixed length of 10
//! bytes (line 2185); the same request is printed with 10 bytes at lines 2333 and 2345, and its
//! checksum `1E` is that of those 10 bytes (zeros do not change a sum, so the checksum cannot tell
//! which zero is missing; the only byte that is not reserved, the subindex, is 0 in the other
//! prints).

use drivebus::rs232::data::Request;
use drivebus::rs232::telegram::{self, Telegram, TELEGRAM_LEN};
use drivebus::rs232::StationId;

/// A printed telegram: its manual line, its bytes as printed, and the request they mean.
struct Printed {
    line: u32,
    hex: &'static str,
    request: Request,
}

fn bytes(hex: &str) -> Vec<u8> {
    hex.split_whitespace()
        .map(|b| u8::from_str_radix(b, 16).unwrap())
        .collect()
}

fn write(index: u16, subindex: u8, value: &[u8]) -> Request {
    Request::download(index, subindex, value).unwrap()
}

const CONTROLWORD: u16 = 0x6040;
const OPERATION_MODE: u16 = 0x6060;

fn printed() -> Vec<Printed> {
    let controlword = |value: u16| write(CONTROLWORD, 0, &value.to_le_bytes());
    let mode = |value: i8| write(OPERATION_MODE, 0, &value.to_le_bytes());
    let read_statusword = Request::upload(0x6041, 0);
    let p = |line, hex, request| Printed { line, hex, request };
    vec![
        // Section 9.4, the example table.
        p(2330, "01 2B 40 60 00 2F 00 00 00 05", controlword(0x2F)),
        p(2331, "01 2F 60 60 00 06 00 00 00 0A", mode(6)),
        p(
            2332,
            "01 23 7A 60 00 50 C3 00 00 EF",
            write(0x607A, 0, &50_000i32.to_le_bytes()),
        ),
        p(2333, "01 40 41 60 00 00 00 00 00 1E", read_statusword),
        // Home mode.
        p(2339, "01 2B 40 60 00 0F 00 00 00 25", controlword(0x0F)),
        p(2340, "01 2F 60 60 00 06 00 00 00 0A", mode(6)),
        p(
            2341,
            "01 2F 98 60 00 21 00 00 00 B7",
            write(0x6098, 0, &[33]),
        ),
        p(
            2342,
            "01 23 99 60 01 55 55 08 00 30",
            write(0x6099, 1, &0x08_5555u32.to_le_bytes()),
        ),
        p(
            2343,
            "01 23 99 60 02 00 40 06 00 9B",
            write(0x6099, 2, &0x06_4000u32.to_le_bytes()),
        ),
        p(2344, "01 2B 40 60 00 1F 00 00 00 15", controlword(0x1F)),
        p(2345, "01 40 41 60 00 00 00 00 00 1E", read_statusword),
        // Position mode.
        p(2348, "01 2B 40 60 00 0F 00 00 00 25", controlword(0x0F)),
        p(2349, "01 2F 60 60 00 01 00 00 00 0F", mode(1)),
        p(
            2350,
            "01 23 7A 60 00 50 C3 00 00 EF",
            write(0x607A, 0, &50_000i32.to_le_bytes()),
        ),
        p(
            2351,
            "01 23 81 60 00 55 55 08 00 49",
            write(0x6081, 0, &0x08_5555u32.to_le_bytes()),
        ),
        p(2355, "01 2B 40 60 00 2F 00 00 00 05", controlword(0x2F)),
        p(2356, "01 2B 40 60 00 3F 00 00 00 F5", controlword(0x3F)),
        p(2357, "01 2B 40 60 00 4F 00 00 00 E5", controlword(0x4F)),
        p(2358, "01 2B 40 60 00 5F 00 00 00 D5", controlword(0x5F)),
        // Line 2359 as decided above: the lost reserved zero restored.
        p(2359, "01 40 41 60 00 00 00 00 00 1E", read_statusword),
        // Speed mode.
        p(2363, "01 2F 60 60 00 03 00 00 00 0D", mode(3)),
        p(
            2364,
            "01 23 FF 60 00 00 40 06 00 37",
            write(0x60FF, 0, &0x06_4000i32.to_le_bytes()),
        ),
        p(2365, "01 2B 40 60 00 0F 00 00 00 25", controlword(0x0F)),
    ]
}

#[test]
fn every_printed_request_is_encoded_byte_for_byte() {
    let vectors = printed();
    assert_eq!(
        vectors.len(),
        23,
        "lines 2330-2365 print 23 request telegrams"
    );
    for Printed { line, hex, request } in vectors {
        let encoded = telegram::encode(StationId(1), &request.encode());
        assert_eq!(encoded.to_vec(), bytes(hex), "line {line}");
    }
}

#[test]
fn every_printed_request_decodes_to_its_meaning() {
    for Printed { line, hex, request } in printed() {
        let telegram: Telegram = bytes(hex).try_into().unwrap();
        let (station, data) =
            telegram::decode(&telegram).unwrap_or_else(|e| panic!("line {line}: {e:?}"));
        assert_eq!(station, StationId(1), "line {line}");
        assert_eq!(Request::decode(data), Ok(request), "line {line}");
    }
}

#[test]
fn the_nine_byte_print_of_line_2359_is_the_statusword_read_with_a_zero_lost() {
    let as_printed = bytes("01 40 41 60 00 00 00 00 1E");
    assert_eq!(as_printed.len(), TELEGRAM_LEN - 1);
    let mut restored = as_printed.clone();
    restored.insert(5, 0x00);
    let full = telegram::encode(StationId(1), &Request::upload(0x6041, 0).encode());
    assert_eq!(restored, full.to_vec());
}
