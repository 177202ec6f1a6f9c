//! The objects every CANopen device has (CiA 301 §7.5.2): device type (1000h), error register
//! (1001h) and the identity object (1018h, at least its sub-index 0 and the vendor-ID, sub-index
//! 1). Validation requires them of a CANopen description; the EDS writer lists them under
//! `[MandatoryObjects]`.

/// The mandatory objects: (index, sub-index, name in the CiA 301 profile).
pub const MANDATORY_OBJECTS: &[(u16, u8, &str)] = &[
    (0x1000, 0, "device_type"),
    (0x1001, 0, "error_register"),
    (0x1018, 0, "identity_count"),
    (0x1018, 1, "vendor_id"),
];
