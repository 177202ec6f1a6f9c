//! Drive commands: register #1 takes one command bit per write (Note 1, lines 567-571: with
//! several bits set the drive obeys only STOP, or answers exception 04). A [`Command`] is one
//! bit, so a write can never carry two. Locking is [`Session::lock`](crate::Session::lock).

use crate::types::DriveControl;

/// One command of the drive control register #1 (Table 8, lines 538-557).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Command {
    /// Bit 0: start the drive using downloaded data (line 559).
    UpdateBuffers,
    /// Bit 2: coast to stop; writes 0x0004 (line 1069).
    Stop,
    /// Bit 3: start; writes 0x0008 (line 1070).
    Start,
    /// Bit 6: set reverse direction; writes 0x0040 (line 1071).
    Reverse,
    /// Bit 7: set forward direction; writes 0x0080 (line 1072).
    Forward,
    /// Bit 8: take the speed from #40, the serial speed command; writes 0x0100 (line 1063).
    SerialSpeedReference,
    /// Bit 9: take the speed reference locally.
    LocalSpeedReference,
}

impl Command {
    /// Every command, in bit order.
    pub const ALL: [Command; 7] = [
        Self::UpdateBuffers,
        Self::Stop,
        Self::Start,
        Self::Reverse,
        Self::Forward,
        Self::SerialSpeedReference,
        Self::LocalSpeedReference,
    ];

    /// The control word that carries this command alone.
    pub const fn control_word(self) -> DriveControl {
        match self {
            Self::UpdateBuffers => DriveControl::UPDATE_BUFFERS,
            Self::Stop => DriveControl::STOP,
            Self::Start => DriveControl::START,
            Self::Reverse => DriveControl::SET_REVERSE,
            Self::Forward => DriveControl::SET_FORWARD,
            Self::SerialSpeedReference => DriveControl::SERIAL_SPEED_REFERENCE,
            Self::LocalSpeedReference => DriveControl::LOCAL_SPEED_REFERENCE,
        }
    }
}
