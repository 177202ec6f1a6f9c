//! Blocking Modbus transports.
