//! CANopen Safety (EN 50325-5) SRDO configuration values: the two COB-IDs, the two times, the
//! mapping rules, and why a configuration or frame yields no value. The consumer, producer and
//! safety writes that use them are in `drivebus::canopen::srdo`.

mod cob_ids;
mod error;
pub mod mapping;
mod timing;

pub use cob_ids::SrdoCobIds;
pub use error::SrdoError;
pub use timing::SrdoTiming;
