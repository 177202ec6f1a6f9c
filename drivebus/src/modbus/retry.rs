//! Which failed requests may be sent again, and how often.
//!
//! A read can be repeated freely. A write whose answer was lost may or may not have been executed;
//! repeating it is harmless for a setpoint but not for "store to EEPROM", "reset" or a command
//! register. So writes are sent once unless the caller declares them idempotent, and registers
//! listed as non-idempotent are never repeated whatever else is declared.

use core::ops::RangeInclusive;

use crate::error::BusError;

use super::pdu::Request;

/// Whether sending a request twice has the same effect as sending it once.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Idempotency {
    /// Safe to repeat after a lost answer.
    Idempotent,
    /// Must be sent at most once.
    NonIdempotent,
}

/// How a client retries failed requests.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RetryPolicy {
    /// Further attempts after a failed idempotent request (0: every request is sent once).
    pub retries: u8,
    /// Whether writes count as idempotent by default. `false` (the default) sends every write once.
    pub writes_idempotent: bool,
    /// Holding registers / coils whose writes are never repeated (store, reset, command words),
    /// whatever `writes_idempotent` and per-call declarations say.
    pub non_idempotent: &'static [RangeInclusive<u16>],
}

impl Default for RetryPolicy {
    fn default() -> Self {
        Self::NONE
    }
}

impl RetryPolicy {
    /// Every request is sent once.
    pub const NONE: RetryPolicy = RetryPolicy {
        retries: 0,
        writes_idempotent: false,
        non_idempotent: &[],
    };

    /// Reads are retried `retries` times; writes are sent once.
    pub const fn reads(retries: u8) -> Self {
        Self {
            retries,
            writes_idempotent: false,
            non_idempotent: &[],
        }
    }

    /// Whether `request` may be repeated; `declared` overrides the default for writes (but never
    /// the `non_idempotent` list).
    pub fn is_idempotent(&self, request: &Request<'_>, declared: Option<Idempotency>) -> bool {
        if !request.is_write() {
            return true;
        }
        let (start, count) = request.span();
        let end = start as usize + count.max(1) - 1;
        let listed = self
            .non_idempotent
            .iter()
            .any(|range| *range.start() as usize <= end && start <= *range.end());
        if listed {
            return false;
        }
        match declared {
            Some(Idempotency::Idempotent) => true,
            Some(Idempotency::NonIdempotent) => false,
            None => self.writes_idempotent,
        }
    }

    /// How many times `request` may be sent in all.
    pub fn attempts(&self, request: &Request<'_>, declared: Option<Idempotency>) -> u32 {
        if self.is_idempotent(request, declared) {
            1 + u32::from(self.retries)
        } else {
            1
        }
    }
}

/// Whether another attempt could succeed where this one failed: lost or garbled answers and I/O
/// failures may be transient; an exception or an unsupported request is the device's answer.
pub fn is_transient(error: &BusError) -> bool {
    match error {
        BusError::Timeout | BusError::Frame(_) => true,
        #[cfg(feature = "std")]
        BusError::Io(_) => true,
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const STORE_AND_RESET: &[RangeInclusive<u16>] = &[0x0000..=0x0000, 0xA5A5..=0xA5A5];

    #[test]
    fn reads_retry_and_writes_do_not_by_default() {
        let policy = RetryPolicy::reads(2);
        let read = Request::ReadInputRegisters {
            start: 0x60,
            count: 17,
        };
        let write = Request::WriteSingleRegister {
            address: 0x28,
            value: 2,
        };
        assert_eq!(policy.attempts(&read, None), 3);
        assert_eq!(policy.attempts(&write, None), 1);
        assert_eq!(policy.attempts(&write, Some(Idempotency::Idempotent)), 3);
        assert_eq!(policy.attempts(&read, Some(Idempotency::NonIdempotent)), 3);
    }

    #[test]
    fn listed_registers_are_never_repeated() {
        let policy = RetryPolicy {
            retries: 3,
            writes_idempotent: true,
            non_idempotent: STORE_AND_RESET,
        };
        let store = Request::WriteSingleRegister {
            address: 0,
            value: 1,
        };
        let reset = Request::write_registers(0xA5A0, &[0; 8]);
        let setpoint = Request::WriteSingleRegister {
            address: 0x42,
            value: 1500,
        };
        assert_eq!(policy.attempts(&store, Some(Idempotency::Idempotent)), 1);
        assert_eq!(policy.attempts(&reset, None), 1);
        assert_eq!(policy.attempts(&setpoint, None), 4);
        assert_eq!(
            policy.attempts(&setpoint, Some(Idempotency::NonIdempotent)),
            1
        );
    }

    #[test]
    fn only_lost_or_garbled_answers_are_transient() {
        assert!(is_transient(&BusError::Timeout));
        assert!(is_transient(&BusError::Frame("CRC mismatch")));
        assert!(!is_transient(&BusError::ModbusException {
            function: 3,
            code: crate::modbus::ExceptionCode::IllegalDataAddress
        }));
        assert!(!is_transient(&BusError::Unsupported("x")));
    }
}
