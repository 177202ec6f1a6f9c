//! CANopen Safety (EN 50325-5) SRDOs, sans-I/O.
//!
//! An SRDO is two frames on two COB-IDs: the normal data and its bitwise complement. The
//! [`SrdoConsumer`] releases a value only when both frames arrive, agree and lie within the SRDO
//! valid time (SRVT) of each other, and reports a safeguard cycle time (SCT) expiry between
//! pairs; everything else is an [`SrdoError`] and no value. The [`SrdoProducer`] emits the pair.
//! Time is an input, as in every core of this crate. [`signature()`] computes the safety
//! configuration signature (13FFh) of an [`SrdoConfig`]; [`write_safety_configuration`] is the
//! only writer of safety configuration (Pre-Operational only, signature and validity flag after),
//! [`write_safety_function`] the only writer of safety-function parameters (Pre-Operational
//! only, the function's signature recomputed after).
//!
//! ```
//! use core::time::Duration;
//! use drivebus::canopen::srdo::{SrdoCobIds, SrdoConsumer, SrdoError, SrdoProducer, SrdoTiming};
//!
//! // SRDO1 of the ez-Wheel SWD at node 0x10: COB-IDs 11Fh / 120h, SCT 50 ms, SRVT 20 ms,
//! // one byte of data (SWD manual lines 1736-1746, 4100, 4111).
//! let ids = SrdoCobIds::new(0x11F, 0x120).unwrap();
//! let timing = SrdoTiming::from_millis(50, 20).unwrap();
//! let producer = SrdoProducer::new(ids, timing.sct(), 8).unwrap();
//! let mut consumer = SrdoConsumer::new(ids, timing, 8).unwrap();
//! let [normal, inverted] = producer.pair(&[0xFF]).unwrap();
//! let ms = Duration::from_millis;
//! assert_eq!(consumer.handle(&normal, ms(0)), Some(Ok(None)));
//! let value = consumer.handle(&inverted, ms(1)).unwrap().unwrap().unwrap();
//! assert_eq!(value.as_bytes(), [0xFF]);
//! // The same inverted frame 30 ms after its normal frame is too late.
//! consumer.handle(&normal, ms(10));
//! assert!(matches!(consumer.handle(&inverted, ms(40)), Some(Err(SrdoError::SrvtExpired { .. }))));
//! ```

mod complement;
mod config;
mod consumer;
mod function_write;
pub use drivebus_model::canopen::srdo::mapping;
mod producer;
pub mod safety_function;
pub mod safety_write;
pub mod signature;
mod stored_signature;

pub use complement::is_complement;
pub use config::{SrdoCommunication, SrdoConfig, SrdoDirection, MAX_SRDO};
pub use consumer::SrdoConsumer;
pub use drivebus_model::canopen::srdo::{SrdoCobIds, SrdoError, SrdoTiming};
pub use producer::SrdoProducer;
#[cfg(feature = "async")]
pub use safety_function::write_safety_function_async;
pub use safety_function::{
    function_signature, write_safety_function, FunctionSignature, SafetyFunctionParameter,
    SafetyValue, Signed,
};
#[cfg(feature = "async")]
pub use safety_write::write_safety_configuration_async;
pub use safety_write::{write_safety_configuration, MappingWrite, SafetyPlan, SafetyWriteError};
pub use signature::{signature, verify, SignatureMismatch, VerifyError};
pub use stored_signature::{check_stored_signature, StoredSignatureError};
