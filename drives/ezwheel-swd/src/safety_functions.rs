//! The SWD's safety-function signatures (manual section 11.8, lines 3633-3860) as data, and the
//! deliberate write of safety-function parameters through them.
//!
//! Each table lists, in order, the objects a function's signature covers and how many bytes of
//! each enter the CRC-16-CCITT (start value 0, lines 3497-3562). A sub-index range with a width
//! "for each sub-index" signs every sub-index; a range of one width per entry ("6691h 01 to 08,
//! 2 bytes" for the eight SLS) signs the sub-index of the function's own instance; objects the
//! tables call non-existent sign zeros.
//!
//! **Unverified.** The manual gives no test vector for any of these signatures, and they cover
//! objects whose values it never gives (the units 6600h-6603h, the Safe_out mapping 26F8h):
//! these are the tables as printed, with the decisions below, not checked against a drive.
//!
//! Decided (ERRATA.md): 26F1h is signed over sub-indices 01-06, as the STO table prints
//! (line 3658) and as the object has (six entries, line 3066); the other tables print 01-08
//! (e.g. line 3695), sub-indices the object does not have. 26F8h, which the manual only names,
//! is signed as each table prints it (01-04 for STO, line 3659; 01-08 elsewhere).

use drivebus::canopen::nmt::NmtState;
use drivebus::canopen::srdo::{
    write_safety_function, FunctionSignature, SafetyValue, SafetyWriteError, Signed,
};
use drivebus::canopen::{CanOpenLink, SdoBus};

use crate::Swd;

/// `index` sub-indices `first..=last`, four bytes each: a command or status mapping.
const fn mapping(index: u16, first: u8, last: u8) -> Signed {
    Signed::Each {
        index,
        first,
        last,
        bytes: 4,
    }
}

/// The safety word mappings every function signs after its own objects (e.g. lines 3642-3661):
/// 66F0h-66F7h, 66F8h-66FFh, 26F1h, 26F8h (sub-indices 01 to `safe_out_last`), 2624h, 2625h.
macro_rules! safety_word_mappings {
    ($safe_out_last:literal) => {
        [
            mapping(0x66F0, 1, 8),
            mapping(0x66F1, 1, 8),
            mapping(0x66F2, 1, 8),
            mapping(0x66F3, 1, 8),
            mapping(0x66F4, 1, 8),
            mapping(0x66F5, 1, 8),
            mapping(0x66F6, 1, 8),
            mapping(0x66F7, 1, 8),
            mapping(0x66F8, 1, 8),
            mapping(0x66F9, 1, 8),
            mapping(0x66FA, 1, 8),
            mapping(0x66FB, 1, 8),
            mapping(0x66FC, 1, 8),
            mapping(0x66FD, 1, 8),
            mapping(0x66FE, 1, 8),
            mapping(0x66FF, 1, 8),
            mapping(0x26F1, 1, 6),
            mapping(0x26F8, 1, $safe_out_last),
            mapping(0x2624, 1, 8),
            mapping(0x2625, 1, 8),
        ]
    };
}

/// `bytes` of `index` sub 0.
const fn one(index: u16, bytes: u8) -> Signed {
    Signed::One {
        index,
        subindex: 0,
        bytes,
    }
}

/// `bytes` of the function's own sub-index of `index`.
const fn own(index: u16, bytes: u8) -> Signed {
    Signed::OfFunction { index, bytes }
}

/// Joins a function's own objects and the safety word mappings into one table.
const fn table<const OWN: usize, const ALL: usize>(
    own: [Signed; OWN],
    mappings: [Signed; 20],
) -> [Signed; ALL] {
    let mut all = [Signed::Absent { bytes: 0 }; ALL];
    let mut i = 0;
    while i < OWN {
        all[i] = own[i];
        i += 1;
    }
    while i < ALL {
        all[i] = mappings[i - OWN];
        i += 1;
    }
    all
}

const STO_SIGNED: [Signed; 21] = table([one(0x6641, 1)], safety_word_mappings!(4));

/// STO (lines 3633-3661): one signature in 6645h sub 0 over 6641h and the safety word mappings.
pub const STO: FunctionSignature = FunctionSignature {
    name: "STO",
    index: 0x6645,
    instances: 0,
    signed: &STO_SIGNED,
};

const SBC_SIGNED: [Signed; 23] = table(
    [one(0x6600, 4), own(0x6661, 2), one(0x2660, 1)],
    safety_word_mappings!(8),
);

/// SBC (lines 3663-3698): three signatures in 6662h sub 1-3 over the time unit, the SBC's brake
/// time delay, "brake present" and the safety word mappings.
pub const SBC: FunctionSignature = FunctionSignature {
    name: "SBC",
    index: 0x6662,
    instances: 3,
    signed: &SBC_SIGNED,
};

const SLS_SIGNED: [Signed; 31] = table(
    [
        one(0x6600, 4),
        one(0x6602, 4),
        one(0x6603, 4),
        own(0x6691, 2),
        Signed::Absent { bytes: 2 }, // 6692h, "object does not exist" (line 3714)
        own(0x6693, 4),
        own(0x6694, 2),
        Signed::Absent { bytes: 2 }, // 6695h (line 3717)
        Signed::Absent { bytes: 2 }, // 6696h (line 3718)
        Signed::Absent { bytes: 4 }, // 6697h (line 3719)
        own(0x6698, 4),
    ],
    safety_word_mappings!(8),
);

/// SLS (lines 3700-3743): eight signatures in 6699h sub 1-8.
pub const SLS: FunctionSignature = FunctionSignature {
    name: "SLS",
    index: 0x6699,
    instances: 8,
    signed: &SLS_SIGNED,
};

const SLSA_SIGNED: [Signed; 29] = table(
    [
        one(0x6600, 4),
        one(0x6602, 4),
        own(0x3051, 2),
        own(0x3052, 4),
        own(0x3053, 2),
        own(0x3054, 2),
        own(0x3055, 4),
        own(0x3056, 2),
        own(0x3057, 4),
    ],
    safety_word_mappings!(8),
);

/// SLSa (lines 3745-3783): eight signatures in 3058h sub 1-8.
pub const SLSA: FunctionSignature = FunctionSignature {
    name: "SLSa",
    index: 0x3058,
    instances: 8,
    signed: &SLSA_SIGNED,
};

const SDI_SIGNED: [Signed; 26] = table(
    [
        one(0x6601, 4),
        one(0x6602, 4),
        own(0x66D2, 2),
        own(0x66D3, 4),
        own(0x66D4, 2),
        own(0x66D5, 4),
    ],
    safety_word_mappings!(8),
);

/// SDI (lines 3785-3820): two signatures in 66D6h sub 1-2 (the SDI's position and velocity
/// zero windows; the table does not call the u16 objects 66D2h/66D4h non-existent, so they are
/// read from the drive).
pub const SDI: FunctionSignature = FunctionSignature {
    name: "SDI",
    index: 0x66D6,
    instances: 2,
    signed: &SDI_SIGNED,
};

const SMS_SIGNED: [Signed; 26] = table(
    [
        one(0x6602, 4),
        Signed::Absent { bytes: 2 }, // 66A9h, "objet inexistant" (line 3833)
        Signed::One {
            index: 0x66AA,
            subindex: 1,
            bytes: 4,
        },
        Signed::Absent { bytes: 2 }, // 66ABh (line 3835)
        Signed::One {
            index: 0x66AC,
            subindex: 1,
            bytes: 4,
        },
        Signed::One {
            index: 0x66AD,
            subindex: 1,
            bytes: 4,
        },
    ],
    safety_word_mappings!(8),
);

/// SMS (lines 3822-3860): one signature in 66AEh sub 1.
pub const SMS: FunctionSignature = FunctionSignature {
    name: "SMS",
    index: 0x66AE,
    instances: 1,
    signed: &SMS_SIGNED,
};

impl<B: SdoBus> Swd<CanOpenLink<B>> {
    /// The deliberate write of safety-function parameters: refused while the handle refuses
    /// writes (`verify_identity` found another drive), unless the node is in NMT
    /// Pre-Operational (`state`, as the caller knows it) and unless every value is covered by
    /// `function`'s signature, before any frame is sent; then writes `values`, reads back what
    /// the signature of `instance` covers and writes the recomputed signature. Returns the
    /// signature (unverified: see the module docs).
    ///
    /// ```no_run
    /// # use drivebus::canopen::{nmt::NmtState, srdo::SafetyValue};
    /// # use drivebus::units::Rpm;
    /// # fn f<B: drivebus::canopen::SdoBus>(drive: &mut ezwheel_swd::Swd<drivebus::canopen::CanOpenLink<B>>) -> Result<(), Box<dyn std::error::Error>> {
    /// use drivebus::indexed::At;
    /// use ezwheel_swd::params::SlsaPositiveVelocityLimitRun;
    /// use ezwheel_swd::safety_functions::SLSA;
    /// let limit = SafetyValue::of::<At<SlsaPositiveVelocityLimitRun, 3>, _>(drive.device(), Rpm(500.0))?;
    /// let signature = drive.write_safety_function(NmtState::PreOperational, &SLSA, 3, &[limit])?;
    /// # Ok(()) }
    /// ```
    pub fn write_safety_function(
        &mut self,
        state: NmtState,
        function: &FunctionSignature,
        instance: u8,
        values: &[SafetyValue],
    ) -> Result<u16, SafetyWriteError> {
        writes_allowed(self.device())?;
        let link = self.device().link_mut();
        write_safety_function_on(link, state, function, instance, values)
    }
}

/// `Err` while `device` refuses writes (`verify_identity` found another drive): checked before
/// any frame of a safety write.
fn writes_allowed<L>(device: &drivebus::Device<L>) -> Result<(), SafetyWriteError> {
    device.write_refusal().map_or(Ok(()), |reason| {
        Err(SafetyWriteError::WritesRefused(reason))
    })
}

/// [`write_safety_function`] to the node of `link`.
fn write_safety_function_on<B: SdoBus>(
    link: &mut CanOpenLink<B>,
    state: NmtState,
    function: &FunctionSignature,
    instance: u8,
    values: &[SafetyValue],
) -> Result<u16, SafetyWriteError> {
    let node = link.node();
    write_safety_function(link.bus_mut(), node, state, function, instance, values)
}

// Async items without a `cfg` of this crate: they exist when drivebus has `async`, as the
// generated async handle does (the other drive crates write theirs the same way).
drivebus::if_async! {
    impl<B: drivebus::canopen::AsyncSdoBus> Swd<drivebus::asynch::Async<CanOpenLink<B>>> {
        /// [`Swd::write_safety_function`] on the async handle: the same refusals before any frame
        /// is sent, the same writes, read-back and signature write, each awaited. The values are
        /// made with [`SafetyValue::of_async`].
        ///
        /// ```no_run
        /// # use drivebus::canopen::{nmt::NmtState, srdo::SafetyValue, AsyncSdoBus, CanOpenLink};
        /// # use drivebus::asynch::Async;
        /// # use drivebus::units::Rpm;
        /// # async fn f<B: AsyncSdoBus>(drive: &mut ezwheel_swd::Swd<Async<CanOpenLink<B>>>) -> Result<(), Box<dyn std::error::Error>> {
        /// use drivebus::indexed::At;
        /// use ezwheel_swd::params::SlsaPositiveVelocityLimitRun;
        /// use ezwheel_swd::safety_functions::SLSA;
        /// let limit = SafetyValue::of_async::<At<SlsaPositiveVelocityLimitRun, 3>, _>(drive.device(), Rpm(500.0)).await?;
        /// let signature = drive
        ///     .write_safety_function_async(NmtState::PreOperational, &SLSA, 3, &[limit])
        ///     .await?;
        /// # Ok(()) }
        /// ```
        pub async fn write_safety_function_async(
            &mut self,
            state: NmtState,
            function: &FunctionSignature,
            instance: u8,
            values: &[SafetyValue],
        ) -> Result<u16, SafetyWriteError> {
            writes_allowed(self.device())?;
            let link = self.device().link_mut().get_mut();
            let node = link.node();
            let bus = link.bus_mut();
            drivebus::canopen::srdo::write_safety_function_async(bus, node, state, function, instance, values).await
        }
    }
}
