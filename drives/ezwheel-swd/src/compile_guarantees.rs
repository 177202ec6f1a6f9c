//! What the generated SWD API refuses to compile, each beside its accepted counterpart (doctests).
//!
//! A run of read-only sub-indices has no `write` (6690h SLS commands, read-only, line 3397):
//!
//! ```compile_fail
//! # use drivebus::canopen::{CanOpenLink, NodeId};
//! # use drivebus::testing::MemoryBus;
//! let mut drive = ezwheel_swd::Swd::canopen(MemoryBus::new(), NodeId(0x10));
//! let _ = drive.sls_command(3).write(true);
//! ```
//!
//! ```
//! # use drivebus::canopen::{CanOpenLink, NodeId};
//! # use drivebus::testing::MemoryBus;
//! let mut drive = ezwheel_swd::Swd::canopen(MemoryBus::new(), NodeId(0x10));
//! let _ = drive.sls_command(3).read();
//! ```
//!
//! Members of a run have no method of their own on the handle; the run's accessor reaches them:
//!
//! ```compile_fail
//! # use drivebus::canopen::NodeId;
//! # use drivebus::testing::MemoryBus;
//! let mut drive = ezwheel_swd::Swd::canopen(MemoryBus::new(), NodeId(0x10));
//! let _ = drive.sls_velocity_limit_3().read();
//! ```
//!
//! ```
//! # use drivebus::canopen::NodeId;
//! # use drivebus::testing::MemoryBus;
//! let mut drive = ezwheel_swd::Swd::canopen(MemoryBus::new(), NodeId(0x10));
//! let _ = drive.sls_velocity_limit(3).read();
//! ```
//!
//! A PDO whose COB-ID the manual does not give (TPDO 2, line 1325) has no `cob_id(node)`:
//!
//! ```compile_fail
//! let _ = ezwheel_swd::pdo::Tpdo2::cob_id(drivebus::canopen::NodeId(0x10));
//! ```
//!
//! ```
//! let _ = ezwheel_swd::pdo::Tpdo2::config_with_cob_id(0x4000_0290);
//! let _ = ezwheel_swd::pdo::Tpdo1::cob_id(drivebus::canopen::NodeId(0x10));
//! ```
