//! The Modbus server side fed arbitrary request PDUs: the request decoder and the simulator's
//! server built from a shipped description.
//!
//! Input: `[device, request PDU...]`; `device % 3` picks the Lafert, Lenze or Kinco description.
//! Asserts that
//! * a decoded request re-encodes (as the client encodes it) to the same PDU, up to the unused
//!   bits of a coil write's last byte;
//! * the simulator always answers, with a PDU of at most `MAX_PDU` bytes that is an exception or
//!   carries the request's function code, and that the client's decoder accepts as the answer
//!   to a request it decoded.
#![no_main]

use drivebus::modbus::pdu::{decode_request, decode_response, Request, ServerRequest, MAX_PDU};
use drivebus::BusError;
use fuzz::shipped;
use drivesim::Simulator;
use libfuzzer_sys::fuzz_target;

/// The shipped descriptions with a Modbus map.
const DESCRIPTIONS: [&str; 3] = ["lafert-smartris", "lenze-smd", "kinco-fd"];

fuzz_target!(|data: &[u8]| {
    let Some((&device, pdu)) = data.split_first() else {
        return;
    };
    let decoded = decode_request(pdu);
    let mut coils = Vec::new();
    let mut registers = Vec::new();
    let request = decoded
        .ok()
        .map(|decoded| as_client_request(decoded, &mut coils, &mut registers));
    if let Some(request) = &request {
        check_re_encodes(request, pdu);
    }
    let sim = Simulator::new(
        shipped::device(DESCRIPTIONS[usize::from(device) % DESCRIPTIONS.len()]).clone(),
    );
    let server = sim.modbus_server();
    let mut out = [0u8; MAX_PDU];
    let len = sim.with(|drive| server.handle(drive, pdu, &mut out));
    assert!((1..=MAX_PDU).contains(&len), "answer of {len} bytes");
    let answer = &out[..len];
    let Some(request) = request else {
        assert!(
            answer[0] & 0x80 != 0,
            "an undecodable request got a normal answer"
        );
        return;
    };
    match decode_response(&request, answer) {
        Ok(_) | Err(BusError::ModbusException { .. }) => {}
        Err(e) => panic!("the client refuses the simulator's answer {answer:02X?}: {e}"),
    }
});

/// The client request a decoded server request stands for; payloads land in `coils` /
/// `registers`.
fn as_client_request<'a>(
    decoded: ServerRequest<'_>,
    coils: &'a mut Vec<bool>,
    registers: &'a mut Vec<u16>,
) -> Request<'a> {
    match decoded {
        ServerRequest::Read {
            function,
            start,
            count,
        } => match function {
            0x01 => Request::ReadCoils { start, count },
            0x02 => Request::ReadDiscreteInputs { start, count },
            0x03 => Request::ReadHoldingRegisters { start, count },
            0x04 => Request::ReadInputRegisters { start, count },
            other => panic!("decoded a read with function {other:#04X}"),
        },
        ServerRequest::WriteSingleCoil { address, value } => {
            Request::WriteSingleCoil { address, value }
        }
        ServerRequest::WriteSingleRegister { address, value } => {
            Request::WriteSingleRegister { address, value }
        }
        ServerRequest::WriteMultipleCoils { start, values } => {
            coils.resize(values.len(), false);
            values
                .copy_to(coils)
                .expect("bits copy to a buffer of their length");
            Request::WriteMultipleCoils {
                start,
                values: coils,
            }
        }
        ServerRequest::WriteMultipleRegisters { start, values } => {
            registers.resize(values.len(), 0);
            values
                .copy_to(registers)
                .expect("registers copy to a buffer of their length");
            Request::WriteMultipleRegisters {
                start,
                values: registers,
            }
        }
    }
}

/// The client's encoding of `request` is `pdu`, but for the unused bits of a coil write.
fn check_re_encodes(request: &Request<'_>, pdu: &[u8]) {
    request
        .validate()
        .expect("a request the server decodes is one the client may send");
    let mut out = [0u8; MAX_PDU];
    let len = request.encode(&mut out).expect("a decoded request encodes");
    let mut expected = pdu.to_vec();
    if let Request::WriteMultipleCoils { values, .. } = request {
        let unused = (8 - values.len() % 8) % 8;
        if let Some(last) = expected.last_mut() {
            *last &= 0xFF >> unused;
        }
    }
    assert_eq!(&out[..len], &expected[..], "decoded {request:?}");
}
