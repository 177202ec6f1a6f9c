//! What each master operation sends and how its outcome reads, once for every driver: the
//! blocking master (`canopen::client::lss`) and the async one (`canopen::async_client::lss`)
//! each run a [`Request`] through an [`Exchange`](super::Exchange) and call [`Request::finish`].

use core::ops::RangeInclusive;

use super::command::RangePart;
use super::exchange::MAX_COMMANDS;
use super::{
    BitTiming, Command, IdentityWord, LssAddress, LssError, LssMode, NewNodeId, Outcome, Response,
};

/// One master operation: the commands of one exchange, and what its outcome means.
#[derive(Debug, Clone, Copy)]
pub struct Request<T> {
    commands: [Command; MAX_COMMANDS],
    len: usize,
    finish: fn(Outcome) -> Result<T, LssError>,
}

impl<T> Request<T> {
    fn new(commands: &[Command], finish: fn(Outcome) -> Result<T, LssError>) -> Self {
        let mut all = [Command::IdentifyNonConfigured; MAX_COMMANDS];
        all[..commands.len()].copy_from_slice(commands);
        Self {
            commands: all,
            len: commands.len(),
            finish,
        }
    }

    /// The commands to send, in order.
    pub fn commands(&self) -> &[Command] {
        &self.commands[..self.len]
    }

    /// What the exchange's outcome means for this operation.
    pub fn finish(&self, outcome: Outcome) -> Result<T, LssError> {
        (self.finish)(outcome)
    }
}

/// Switch state global: every slave to `mode` (no answer).
pub fn switch_global(mode: LssMode) -> Request<()> {
    Request::new(&[Command::SwitchGlobal(mode)], |_| Ok(()))
}

/// Switch state selective: the slave at `address` enters configuration state. No answer is
/// [`LssError::NoAnswer`]; two are [`LssError::SeveralAnswers`] (the exchange's verdict).
pub fn switch_selective(address: LssAddress) -> Request<()> {
    let commands = IdentityWord::ALL
        .map(|word| Command::SwitchSelective(word, address.words()[usize::from(word.position())]));
    Request::new(&commands, |_| Ok(()))
}

/// Configure node id (the slave in configuration state); `raw` must be 1-127 or 255 (none):
/// anything else is refused here, before anything is sent. Takes effect at the node's next
/// reset; nothing is stored ([`store`] does that).
pub fn configure_node_id(raw: u8) -> Result<Request<()>, LssError> {
    let id = NewNodeId::new(raw)?;
    Ok(Request::new(&[Command::ConfigureNodeId(id)], confirmed))
}

/// Configure bit timing from the CiA 305 table; a refusal carries the slave's error code.
pub fn configure_bit_timing(timing: BitTiming) -> Request<()> {
    let command = Command::ConfigureBitTiming {
        table: 0,
        index: timing.index(),
    };
    Request::new(&[command], confirmed)
}

/// Activate bit timing on every slave after `delay_ms` (no answer).
pub fn activate_bit_timing(delay_ms: u16) -> Request<()> {
    Request::new(&[Command::ActivateBitTiming { delay_ms }], |_| Ok(()))
}

/// Store configuration: the slave keeps its node id and bit timing across a power cycle.
pub fn store() -> Request<()> {
    Request::new(&[Command::Store], confirmed)
}

/// One word of the LSS address of the slave in configuration state.
pub fn inquire(word: IdentityWord) -> Request<u32> {
    Request::new(&[Command::Inquire(word)], |outcome| {
        match answer(outcome)? {
            Response::Inquired(_, value) => Ok(value),
            _ => Err(LssError::NoAnswer),
        }
    })
}

/// The active node id of the slave in configuration state (255: none).
pub fn inquire_node_id() -> Request<u8> {
    Request::new(&[Command::InquireNodeId], |outcome| {
        match answer(outcome)? {
            Response::NodeId(id) => Ok(id),
            _ => Err(LssError::NoAnswer),
        }
    })
}

/// Identify remote slave: how many slaves of `vendor_id` and `product_code` have a revision
/// and serial number within the ranges.
pub fn identify_remote(
    vendor_id: u32,
    product_code: u32,
    revision: RangeInclusive<u32>,
    serial: RangeInclusive<u32>,
) -> Request<usize> {
    let values = [
        vendor_id,
        product_code,
        *revision.start(),
        *revision.end(),
        *serial.start(),
        *serial.end(),
    ];
    let commands: [Command; 6] =
        core::array::from_fn(|i| Command::IdentifyRemote(RangePart::ALL[i], values[i]));
    Request::new(&commands, |outcome| Ok(outcome.count))
}

/// Identify non-configured remote slave: how many slaves have no node id.
pub fn identify_non_configured() -> Request<usize> {
    Request::new(&[Command::IdentifyNonConfigured], |outcome| {
        Ok(outcome.count)
    })
}

/// The answer of a command only one slave may answer.
fn answer(outcome: Outcome) -> Result<Response, LssError> {
    outcome.response.ok_or(LssError::NoAnswer)
}

/// The verdict of a configure or store confirmation.
fn confirmed(outcome: Outcome) -> Result<(), LssError> {
    match answer(outcome)? {
        Response::Confirmed(_, verdict) => verdict.map_err(LssError::Refused),
        _ => Err(LssError::NoAnswer),
    }
}
