//! The drive status block: registers #24-#29 in one 6-word read at #24, the documented exception
//! to one register per read (section 2.3 D, line 225; 5.4.1, lines 617-632; 7.4, line 1079).

use drivebus::modbus::{ModbusLink, RegisterBus, RegisterSpan};
use drivebus::units::Hertz;
use drivebus::{Error, Parameter};

use crate::params;
use crate::types::{
    DirectionAndControlMode, FaultAndCommandedDirection, LoadAndStatus, SpeedSourceAndReference,
};
use crate::LenzeSmd;

/// The block as the description lists it (`[modbus] read_blocks`).
const BLOCK: RegisterSpan = crate::MODBUS_READ_BLOCKS[0];
/// Register #24, where the block starts.
pub const STATUS_BLOCK_START: u16 = BLOCK.start;
/// Words of the block: #24 answers a read of exactly 1 or 6 words (line 617).
pub const STATUS_BLOCK_WORDS: usize = 6;
const _: () = assert!(BLOCK.count as usize == STATUS_BLOCK_WORDS && STATUS_BLOCK_START == 24);

/// The six words of the status block, decoded by the description's own types (Table 10).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StatusBlock {
    /// #24, commanded speed (D1).
    pub command_speed: Hertz,
    /// #25, actual speed (D2).
    pub actual_speed: Hertz,
    /// #26, load (D3H) and operational status (D3L).
    pub load_and_status: LoadAndStatus,
    /// #27, actual direction (D4H) and control mode (D4L).
    pub direction_and_control_mode: DirectionAndControlMode,
    /// #28, speed command source (D5H) and speed reference (D5L).
    pub speed_source_and_reference: SpeedSourceAndReference,
    /// #29, present fault (D6H) and commanded direction (D6L).
    pub fault_and_commanded_direction: FaultAndCommandedDirection,
}

/// Decodes one word of the block as parameter `P` would be read on its own.
fn word<P: Parameter<Raw = u16>>(raw: u16) -> Result<P::Value, Error> {
    P::decode(raw, P::SCALE).map_err(Error::Value)
}

impl StatusBlock {
    /// Decodes the six words, #24 first.
    pub fn decode(words: [u16; STATUS_BLOCK_WORDS]) -> Result<Self, Error> {
        let [d1, d2, d3, d4, d5, d6] = words;
        Ok(Self {
            command_speed: word::<params::CommandSpeed>(d1)?,
            actual_speed: word::<params::ActualSpeed>(d2)?,
            load_and_status: word::<params::LoadAndStatus>(d3)?,
            direction_and_control_mode: word::<params::DirectionAndControlMode>(d4)?,
            speed_source_and_reference: word::<params::SpeedSourceAndReference>(d5)?,
            fault_and_commanded_direction: word::<params::FaultAndCommandedDirection>(d6)?,
        })
    }
}

impl<B: RegisterBus> LenzeSmd<ModbusLink<B>> {
    /// Reads the whole status block (#24-#29) in one request, FC 0x03 with a count of 6: the
    /// request planner takes the block from `MODBUS_LIMITS.read_blocks`.
    pub fn status(&mut self) -> Result<StatusBlock, Error> {
        Ok(StatusBlock::from(self.read_many(Members::default())?))
    }
}

/// The block's six parameters, as `read_many` takes them (`Members::default()`: markers are
/// unit values).
pub(crate) type Members = (
    params::CommandSpeed,
    params::ActualSpeed,
    params::LoadAndStatus,
    params::DirectionAndControlMode,
    params::SpeedSourceAndReference,
    params::FaultAndCommandedDirection,
);

/// The six values of [`Members`], as `read_many` gives them.
type MemberValues = (
    Hertz,
    Hertz,
    LoadAndStatus,
    DirectionAndControlMode,
    SpeedSourceAndReference,
    FaultAndCommandedDirection,
);

impl From<MemberValues> for StatusBlock {
    fn from(values: MemberValues) -> Self {
        let (command_speed, actual_speed, load_and_status, direction, source, fault) = values;
        StatusBlock {
            command_speed,
            actual_speed,
            load_and_status,
            direction_and_control_mode: direction,
            speed_source_and_reference: source,
            fault_and_commanded_direction: fault,
        }
    }
}

drivebus::if_async! {
    impl<L: drivebus::asynch::AsyncLink<Protocol = drivebus::modbus::Modbus>>
        LenzeSmd<drivebus::asynch::Async<L>>
    {
        /// `status` awaited: the whole status block (#24-#29) in one request.
        pub async fn status_async(&mut self) -> Result<StatusBlock, Error> {
            Ok(StatusBlock::from(self.read_many_async(Members::default()).await?))
        }
    }
}
