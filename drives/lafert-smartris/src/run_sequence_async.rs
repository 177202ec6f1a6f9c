//! The run sequence's steps on the async handle (drivebus's `async`): `enable_async`,
//! `set_speed_async`, ..., the blocking steps' reads and writes awaited, with their decisions
//! ([`super::run_sequence`]'s functions) shared.

use drivebus::asynch::{Async, AsyncLink};
use drivebus::modbus::Modbus;
use drivebus::units::{AmperesRms, Rpm};

use crate::modbus_run;
use crate::run_sequence::{
    command_into, commanded_from, mode_verdict, status_verdict, ControlMode, RunError,
    StatusVerdict,
};
use crate::types::DriveStatus;
use crate::Smartris;

impl<L: AsyncLink<Protocol = Modbus>> Smartris<Async<L>> {
    /// `check_operation_mode` awaited: the operation mode (holding 0x0207) must be `mode`.
    pub async fn check_operation_mode_async(&mut self, mode: ControlMode) -> Result<(), RunError> {
        mode_verdict(mode, self.operation_mode().read().await?)
    }

    /// `enable` awaited: checks the mode and the state, writes RUN + STOP disabled (T2 / T5),
    /// and checks that the drive now runs in `mode`.
    pub async fn enable_async(&mut self, mode: ControlMode) -> Result<DriveStatus, RunError> {
        self.check_operation_mode_async(mode).await?;
        self.command_into_async(modbus_run::State::Run).await?;
        self.status_in_async(mode.run_status()).await
    }

    /// `set_speed` awaited: the speed setpoint while the drive runs in velocity mode.
    pub async fn set_speed_async(&mut self, speed: Rpm) -> Result<(), RunError> {
        self.status_in_async(DriveStatus::RUN_VELOCITY).await?;
        Ok(self.speed_setpoint().write(speed).await?)
    }

    /// `set_torque` awaited: the torque setpoint while the drive runs in torque mode.
    pub async fn set_torque_async(&mut self, torque: AmperesRms) -> Result<(), RunError> {
        self.status_in_async(DriveStatus::RUN_TORQUE).await?;
        Ok(self.torque_setpoint().write(torque).await?)
    }

    /// `stop_with_ramp` awaited: speed setpoint 0 in velocity mode.
    pub async fn stop_with_ramp_async(&mut self) -> Result<(), RunError> {
        self.set_speed_async(Rpm(0.0)).await
    }

    /// `stop` awaited: the stop command (T4), and the drive must report STOP.
    pub async fn stop_async(&mut self) -> Result<DriveStatus, RunError> {
        self.command_into_async(modbus_run::State::Stop).await?;
        self.status_in_async(DriveStatus::STOP).await
    }

    /// `standby` awaited: the standby command (T3 / T6), and the drive must report STANDBY.
    pub async fn standby_async(&mut self) -> Result<DriveStatus, RunError> {
        self.command_into_async(modbus_run::State::Standby).await?;
        self.status_in_async(DriveStatus::STANDBY).await
    }

    async fn command_into_async(&mut self, target: modbus_run::State) -> Result<(), RunError> {
        let expected = commanded_from(target);
        let status = self.status_in_async(expected).await?;
        let command = command_into(target, status, expected)?;
        self.control_word().write(command).await?;
        Ok(())
    }

    async fn status_in_async(&mut self, expected: DriveStatus) -> Result<DriveStatus, RunError> {
        match status_verdict(self.drive_status().read().await?, expected) {
            StatusVerdict::In(status) => Ok(status),
            StatusVerdict::Alarm => Err(RunError::InAlarm {
                code: self.error_code().read().await?,
            }),
            StatusVerdict::Refused(error) => Err(error),
        }
    }
}
