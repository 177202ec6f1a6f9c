//! drivegen
