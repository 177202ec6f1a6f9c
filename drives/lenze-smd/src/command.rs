//! Drive commands: register #1 takes one command bit per write (Note 1, lines 567-571: with
//! several bits set the drive obeys only STOP, or answers exception 04). The description gives
//! each bit as a command parameter of its own sharing #1 (`drive.start().trigger()`); a
//! [`Command`] names one, so a write can never carry two. The commands are in the lock's
//! `controls` scope: they are written only through an unlock guard ([`Unlocked::command`]), and
//! locking is [`Unlocked::lock`].

use drivebus::modbus::{ModbusLink, RegisterBus};

use crate::unlock::OpensControls;
use crate::{params, Trigger, UnlockError, Unlocked};

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

    /// The word this command writes to register #1, from the description.
    pub const fn word(self) -> u16 {
        match self {
            Self::UpdateBuffers => params::UpdateBuffers::TRIGGER,
            Self::Stop => params::Stop::TRIGGER,
            Self::Start => params::Start::TRIGGER,
            Self::Reverse => params::SetReverse::TRIGGER,
            Self::Forward => params::SetForward::TRIGGER,
            Self::SerialSpeedReference => params::SerialSpeedReference::TRIGGER,
            Self::LocalSpeedReference => params::LocalSpeedReference::TRIGGER,
        }
    }
}

impl<B: RegisterBus, U: OpensControls> Unlocked<'_, ModbusLink<B>, U> {
    /// Writes `command` to register #1 through its generated command parameter. A drive whose
    /// unlock ended answers exception 01: [`UnlockError::Locked`].
    pub fn command(&mut self, command: Command) -> Result<(), UnlockError> {
        let written = match command {
            Command::UpdateBuffers => self.update_buffers().trigger(),
            Command::Stop => self.stop().trigger(),
            Command::Start => self.start().trigger(),
            Command::Reverse => self.set_reverse().trigger(),
            Command::Forward => self.set_forward().trigger(),
            Command::SerialSpeedReference => self.serial_speed_reference().trigger(),
            Command::LocalSpeedReference => self.local_speed_reference().trigger(),
        };
        Ok(written?)
    }
}

// With drivebus's `async`: the same commands under an async unlock.
drivebus::if_async! {
    impl<L, U> crate::AsyncUnlocked<'_, L, U>
    where
        L: drivebus::asynch::AsyncLink<Protocol = drivebus::modbus::Modbus>,
        U: OpensControls,
    {
        /// [`Unlocked::command`] awaited: `command`'s word to register #1 through its generated
        /// command parameter; a drive whose unlock ended answers [`UnlockError::Locked`].
        pub async fn command(&mut self, command: Command) -> Result<(), UnlockError> {
            let word = command.word();
            let written = match command {
                Command::UpdateBuffers => self.update_buffers().write_raw(word).await,
                Command::Stop => self.stop().write_raw(word).await,
                Command::Start => self.start().write_raw(word).await,
                Command::Reverse => self.set_reverse().write_raw(word).await,
                Command::Forward => self.set_forward().write_raw(word).await,
                Command::SerialSpeedReference => self.serial_speed_reference().write_raw(word).await,
                Command::LocalSpeedReference => self.local_speed_reference().write_raw(word).await,
            };
            Ok(written?)
        }
    }
}
