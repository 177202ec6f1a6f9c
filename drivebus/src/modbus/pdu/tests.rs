//! Encoding and decoding of both sides against the specification's and the manuals' frames.

use proptest::prelude::*;
use std::vec::Vec;

use super::client::decode_registers_slowly;
use super::*;

fn encoded(request: &Request<'_>) -> Vec<u8> {
    let mut out = [0u8; MAX_PDU];
    let len = request.encode(&mut out).unwrap();
    out[..len].to_vec()
}

#[test]
fn encodes_the_manuals_requests() {
    let write = Request::WriteSingleRegister {
        address: 0x0028,
        value: 2,
    };
    assert_eq!(encoded(&write), [0x06, 0x00, 0x28, 0x00, 0x02]);
    let read = Request::ReadInputRegisters {
        start: 0x0060,
        count: 17,
    };
    assert_eq!(encoded(&read), [0x04, 0x00, 0x60, 0x00, 0x11]);
    let coils = Request::write_coils(
        0x13,
        &[
            true, false, true, true, false, false, true, true, true, false,
        ],
    );
    // The specification's own example: 10 coils from 20 (0x13) = CD 01.
    assert_eq!(
        encoded(&coils),
        [0x0F, 0x00, 0x13, 0x00, 0x0A, 0x02, 0xCD, 0x01]
    );
    let regs = Request::write_registers(1, &[0x000A, 0x0102]);
    assert_eq!(
        encoded(&regs),
        [0x10, 0, 1, 0, 2, 4, 0x00, 0x0A, 0x01, 0x02]
    );
}

#[test]
fn rejects_out_of_spec_requests_before_sending() {
    let mut out = [0u8; MAX_PDU];
    for request in [
        Request::ReadHoldingRegisters { start: 0, count: 0 },
        Request::ReadHoldingRegisters {
            start: 0,
            count: 126,
        },
        Request::ReadCoils {
            start: 0,
            count: 2001,
        },
        Request::ReadInputRegisters {
            start: 0xFFFF,
            count: 2,
        },
        Request::write_registers(0, &[0; 124]),
    ] {
        assert!(matches!(
            request.encode(&mut out),
            Err(BusError::Unsupported(_))
        ));
    }
    let short = &mut [0u8; 4];
    let read = Request::ReadHoldingRegisters { start: 0, count: 1 };
    assert!(read.encode(short).is_err());
}

#[test]
fn decodes_responses_and_rejects_what_does_not_match() {
    let read = Request::ReadHoldingRegisters {
        start: 0x3C,
        count: 2,
    };
    let Ok(Response::Registers(regs)) = decode_response(&read, &[3, 4, 0x12, 0x34, 0xAB, 0xCD])
    else {
        panic!("valid response rejected");
    };
    assert_eq!(regs.iter().collect::<Vec<_>>(), [0x1234, 0xABCD]);
    let cases: [(&[u8], &str); 5] = [
        (
            &[4, 4, 0, 0, 0, 0],
            "function code does not match the request",
        ),
        (&[3, 2, 0, 0], "response length does not match the request"),
        (&[3, 6, 0, 0, 0, 0], "byte count does not match the request"),
        (&[], "empty response PDU"),
        (&[0x83, 2, 0], "exception response has the wrong length"),
    ];
    for (pdu, why) in cases {
        assert_eq!(decode_response(&read, pdu), Err(BusError::Frame(why)));
    }
    assert_eq!(
        decode_response(&read, &[0x83, 0x02]),
        Err(BusError::ModbusException {
            function: 3,
            code: crate::modbus::ExceptionCode::IllegalDataAddress
        })
    );
    // Kinco FD manual line 2424: the exception to FC 0x03 comes back as 0x81.
    assert_eq!(
        decode_response(&read, &[0x81, 0x02]),
        Err(BusError::ModbusException {
            function: 3,
            code: crate::modbus::ExceptionCode::IllegalDataAddress
        })
    );
    let write = Request::WriteSingleRegister {
        address: 0x28,
        value: 2,
    };
    assert_eq!(
        decode_response(&write, &[6, 0, 0x28, 0, 2]),
        Ok(Response::Written)
    );
    assert_eq!(
        decode_response(&write, &[6, 0, 0x28, 0, 3]),
        Err(BusError::Frame("write echo does not match the request"))
    );
}

fn any_request() -> impl Strategy<Value = (u8, u16, Vec<u16>, Vec<bool>)> {
    (
        0u8..8,
        any::<u16>(),
        proptest::collection::vec(any::<u16>(), 1..=123),
        proptest::collection::vec(any::<bool>(), 1..=300),
    )
}

fn build<'a>(kind: u8, start: u16, regs: &'a [u16], bits: &'a [bool]) -> Request<'a> {
    let count = regs.len() as u16;
    match kind {
        0 => Request::ReadCoils {
            start,
            count: bits.len() as u16,
        },
        1 => Request::ReadDiscreteInputs {
            start,
            count: bits.len() as u16,
        },
        2 => Request::ReadHoldingRegisters { start, count },
        3 => Request::ReadInputRegisters { start, count },
        4 => Request::WriteSingleCoil {
            address: start,
            value: bits[0],
        },
        5 => Request::WriteSingleRegister {
            address: start,
            value: regs[0],
        },
        6 => Request::write_coils(start, bits),
        _ => Request::write_registers(start, regs),
    }
}

#[test]
fn decodes_registers_in_one_pass_with_the_general_errors() {
    let read = Request::ReadInputRegisters { start: 0, count: 2 };
    let mut out = [0u16; 2];
    decode_registers(&read, &[4, 4, 0x12, 0x34, 0xAB, 0xCD], &mut out).unwrap();
    assert_eq!(out, [0x1234, 0xABCD]);
    let cases: [(&[u8], BusError); 4] = [
        (
            &[0x84, 2],
            BusError::ModbusException {
                function: 4,
                code: crate::modbus::ExceptionCode::IllegalDataAddress,
            },
        ),
        (
            &[3, 4, 0, 0, 0, 0],
            frame_error("function code does not match the request"),
        ),
        (
            &[4, 5, 0, 0, 0, 0],
            frame_error("byte count does not match the request"),
        ),
        (
            &[4, 4, 0, 0],
            frame_error("response length does not match the request"),
        ),
    ];
    for (pdu, error) in cases {
        assert_eq!(decode_registers(&read, pdu, &mut out), Err(error));
    }
    assert_eq!(out, [0x1234, 0xABCD], "rejected answers leave `out` alone");
    assert_eq!(
        decode_registers(&read, &[4, 4, 0, 0, 0, 0], &mut [0u16; 3]),
        Err(frame_error("register count does not match the request"))
    );
    let write = Request::WriteSingleRegister {
        address: 0x28,
        value: 2,
    };
    assert_eq!(
        decode_registers(&write, &[6, 0, 0x28, 0, 2], &mut out),
        Err(frame_error("response does not match the request"))
    );
}

#[test]
fn register_answers_follow_from_the_request() {
    let read = |count| Request::ReadHoldingRegisters { start: 0, count };
    assert_eq!(read(1).register_answer(), Some(([3, 2], 4)));
    assert_eq!(read(125).register_answer(), Some(([3, 250], 252)));
    assert_eq!(read(127).register_answer(), Some(([3, 254], 256)));
    // No byte count can say 256 or more: no answer can match.
    assert_eq!(read(128).register_answer(), None);
    assert_eq!(read(u16::MAX).register_answer(), None);
    let coils = Request::ReadCoils { start: 0, count: 8 };
    assert_eq!(coils.register_answer(), None);
}

proptest! {
    #[test]
    fn request_and_response_round_trip((kind, start, regs, bits) in any_request()) {
        let request = build(kind, start, &regs, &bits);
        let mut pdu = [0u8; MAX_PDU];
        let Ok(len) = request.encode(&mut pdu) else {
            // Only requests running past 0xFFFF are refused.
            let (start, count) = request.span();
            prop_assert!(start as usize + count > 0x1_0000);
            return Ok(());
        };
        prop_assert_eq!(len, request.encoded_len());
        let server = decode_request(&pdu[..len]).unwrap();
        prop_assert_eq!(server, request, "the server decodes the request the client sent");
        let function = server.function();
        let mut reply = [0u8; MAX_PDU];
        let reply_len = match server {
            Request::ReadCoils { count, .. } | Request::ReadDiscreteInputs { count, .. } => {
                encode_bits_response(function, &bits[..count as usize], &mut reply)
            }
            Request::ReadHoldingRegisters { count, .. } | Request::ReadInputRegisters { count, .. } => {
                encode_registers_response(function, &regs[..count as usize], &mut reply)
            }
            Request::WriteMultipleCoils { values, .. } => {
                let mut back = std::vec![false; values.len()];
                values.copy_to(&mut back).unwrap();
                prop_assert_eq!(&back[..], &bits[..]);
                encode_write_response(&pdu[..len], &mut reply)
            }
            Request::WriteMultipleRegisters { values, .. } => {
                prop_assert_eq!(values.iter().collect::<Vec<_>>(), regs.clone());
                encode_write_response(&pdu[..len], &mut reply)
            }
            _ => encode_write_response(&pdu[..len], &mut reply),
        }
        .unwrap();
        prop_assert_eq!(reply_len, request.response_len());
        match decode_response(&request, &reply[..reply_len]).unwrap() {
            Response::Registers(got) => {
                let mut out = std::vec![0u16; got.len()];
                got.copy_to(&mut out).unwrap();
                prop_assert_eq!(&out[..], &regs[..]);
            }
            Response::Bits(got) => {
                let mut out = std::vec![false; got.len()];
                got.copy_to(&mut out).unwrap();
                prop_assert_eq!(&out[..], &bits[..]);
            }
            Response::Written => prop_assert!(request.is_write()),
        }
    }

    #[test]
    fn decoders_never_panic_on_arbitrary_bytes(
        (kind, start, regs, bits) in any_request(),
        bytes in proptest::collection::vec(any::<u8>(), 0..300),
    ) {
        let request = build(kind, start, &regs, &bits);
        if let Ok(Response::Registers(got)) = decode_response(&request, &bytes) {
            prop_assert_eq!(got.len(), request.span().1);
        }
        let _ = decode_request(&bytes);
    }

    #[test]
    fn decode_registers_agrees_with_the_general_decoder(
        (kind, start, regs, bits) in any_request(),
        bytes in proptest::collection::vec(any::<u8>(), 0..300),
        slots in 0usize..130,
    ) {
        let request = build(kind, start, &regs, &bits);
        let (mut fast, mut general) = (std::vec![0u16; slots], std::vec![0u16; slots]);
        let got = decode_registers(&request, &bytes, &mut fast);
        prop_assert_eq!(&got, &decode_registers_slowly(&request, &bytes, &mut general));
        prop_assert_eq!(fast, general);
    }

    #[test]
    fn decode_registers_agrees_on_damaged_answers(
        values in proptest::collection::vec(any::<u16>(), 1..=125),
        other_count in proptest::option::of(1u16..=127),
        flip in proptest::option::of((any::<prop::sample::Index>(), 1u8..)),
        cut in proptest::option::of(any::<prop::sample::Index>()),
    ) {
        let count = other_count.unwrap_or(values.len() as u16);
        let request = Request::ReadInputRegisters { start: 0, count };
        let mut pdu = [0u8; MAX_PDU];
        let mut len = encode_registers_response(4, &values, &mut pdu).unwrap();
        if let Some((at, bits)) = flip {
            pdu[at.index(len)] ^= bits;
        }
        if let Some(at) = cut {
            len = at.index(len);
        }
        let (mut fast, mut general) = (std::vec![0u16; values.len()], std::vec![0u16; values.len()]);
        let got = decode_registers(&request, &pdu[..len], &mut fast);
        prop_assert_eq!(&got, &decode_registers_slowly(&request, &pdu[..len], &mut general));
        prop_assert_eq!(&fast, &general);
        if flip.is_none() && cut.is_none() && usize::from(count) == values.len() {
            prop_assert_eq!(got, Ok(()));
            prop_assert_eq!(fast, values);
        }
    }
}
