//! Saving to EEPROM (section 8.11, object 2FF0h): the control loop parameters (sub 1, value 1),
//! their initialisation (sub 1, value 10) and the motor parameters (sub 3, value 1); and the
//! switch of the RS-485 port from the Kinco RS-232 protocol (its factory setting) to Modbus.

use drivebus::{Error, Link, Writable};

use crate::params::{Rs485Protocol, StoreData, StoreMotorData};
use crate::types::{self, StoreDataCommand};
use crate::KincoFd;

/// What to save or reset with [`KincoFd::store`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Store {
    /// Store all control loop parameters (2FF0h sub 1 = 1); not the motor parameters.
    ControlLoop,
    /// Initialise all control loop parameters (2FF0h sub 1 = 10).
    InitialiseControlLoop,
    /// Store the motor parameters (2FF0h sub 3 = 1).
    Motor,
}

impl<L: Link> KincoFd<L> {
    /// Saves (or initialises) parameters in EEPROM. Settings marked "save and reboot" (baud
    /// rates, node id, RS-485 protocol) take effect after the drive restarts.
    pub fn store(&mut self, what: Store) -> Result<(), Error>
    where
        StoreData: Writable<L::Protocol>,
        StoreMotorData: Writable<L::Protocol>,
    {
        match what {
            Store::ControlLoop => self.store_data().write(StoreDataCommand::STORE),
            Store::InitialiseControlLoop => self.store_data().write(StoreDataCommand::INITIALISE),
            Store::Motor => self.store_motor_data().write(1u8),
        }
    }

    /// Switches the RS-485 port to Modbus RTU (6510h sub 0x0C = 0, line 2390) and stores it; the
    /// port speaks Modbus after the drive is rebooted. Out of the box it speaks the Kinco RS-232
    /// protocol, so this is written over CANopen or RS-232 (the object has no Modbus register).
    pub fn switch_rs485_to_modbus(&mut self) -> Result<(), Error>
    where
        Rs485Protocol: Writable<L::Protocol>,
        StoreData: Writable<L::Protocol>,
        StoreMotorData: Writable<L::Protocol>,
    {
        self.rs485_protocol().write(types::Rs485Protocol::MODBUS)?;
        self.store(Store::ControlLoop)
    }
}
