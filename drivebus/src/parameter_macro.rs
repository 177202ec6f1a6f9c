//! `parameter!`: the trait impls of one generated parameter marker, from a one-line declaration.
//!
//! Generated crates declare each marker struct themselves (with its docs) and then invoke this
//! macro for its `Parameter`, `ValueOf` and capability impls. Writing the impls once here instead of
//! in every generated crate keeps those crates small to generate and to compile.

/// Implements [`Parameter`](crate::Parameter), [`ValueOf`](crate::ValueOf) and the
/// [`Readable`](crate::Readable) / [`Writable`](crate::Writable) capabilities for a marker type.
///
/// ```
/// # use drivebus::parameter;
/// /// DC link voltage.
/// pub struct BusDcLink;
/// parameter!(BusDcLink = "bus_dc_link": u16 => drivebus::units::Volts, InUnit, scale = 1 / 100;
///     read modbus(input 0x0064));
/// /// Motor temperature.
/// pub struct MotorTemperature;
/// parameter!(MotorTemperature = "motor_temperature": u32 => drivebus::units::Celsius, InUnit,
///     scale = 1 / 10, offset = -40 / 1, range(0, 2000);
///     read modbus(input 0x0070, 2 words, LowFirst); read canopen(0x2001 sub 3, 4 bytes));
/// /// Velocity full scale.
/// pub struct FullScaleVelocity;
/// parameter!(FullScaleVelocity = "full_scale_velocity": u16 => drivebus::units::Rpm, InUnit;
///     read modbus(holding 0x0003));
/// /// Speed setpoint, within ± the full scale.
/// pub struct SpeedSetpoint;
/// parameter!(SpeedSetpoint = "speed_setpoint": i16 => drivebus::units::Rpm, InUnit;
///     write modbus(holding 0x0042) [bounds: magnitude = FullScaleVelocity]);
/// ```
///
/// After the name, raw type, value type and [`codec`](crate::codec) come optional clauses:
/// `scale = numerator / denominator` (with `, offset = numerator / denominator` after it),
/// `range(min, max)`, `one_of[values]` (raw values) and `stops(always)` or
/// `stops(mask => value, ...)` (the writes that stop the drive, never refused before sending). Then one clause per capability: `read`
/// or `write`, the protocol (`modbus`, `canopen` or `rs232`), and the placement — one address,
/// `(input 0x0064)` / `(holding 0x0010, 2 words, LowFirst)` or `(0x6041 sub 0, 2 bytes)`, or a
/// list with one slot per variant, `_` where absent. A write may name the parameters that bound
/// it, `[bounds: min = MinimumFrequency, max = MaximumFrequency]` or
/// `[bounds: magnitude = FullScale]` ([`Writable::BOUNDS`](crate::Writable::BOUNDS)). A trailing
/// `runtime` makes the capability take its scale from the marker's inherent `runtime_scale`.
#[doc(hidden)] // generated crates call it; users never need to
#[macro_export]
macro_rules! parameter {
    // What `#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]` gives a unit marker,
    // written here so that each generated marker is one line, not two.
    (@marker $name:ident) => {
        impl ::core::fmt::Debug for $name {
            fn fmt(&self, f: &mut ::core::fmt::Formatter<'_>) -> ::core::fmt::Result {
                f.write_str(::core::stringify!($name))
            }
        }
        impl ::core::clone::Clone for $name {
            fn clone(&self) -> Self {
                *self
            }
        }
        impl ::core::marker::Copy for $name {}
        impl ::core::default::Default for $name {
            fn default() -> Self {
                $name
            }
        }
        impl ::core::cmp::PartialEq for $name {
            fn eq(&self, _: &Self) -> bool {
                true
            }
        }
        impl ::core::cmp::Eq for $name {}
        impl ::core::hash::Hash for $name {
            fn hash<H: ::core::hash::Hasher>(&self, _: &mut H) {}
        }
    };
    (
        $name:ident = $param_name:literal : $raw:ty => $value:ty, $codec:ident
        $(, scale = $num:literal / $den:literal $(, offset = $off_num:literal / $off_den:literal)?)?
        $(, range($min:expr, $max:expr))?
        $(, one_of[$($allowed:expr),*])?
        $(, stops($($stops:tt)*))?
        $(; $direction:ident $protocol:ident $placement:tt
            $([bounds: $($bound:ident = $by:ident),+])? $($runtime:ident)?)*
        $(;)?
    ) => {
        $crate::parameter!(@marker $name);

        impl $crate::Parameter for $name {
            const NAME: &'static str = $param_name;
            $(const SCALE: $crate::Scale =
                $crate::Scale::fixed($num, $den, 0, 1) $(.with_offset($off_num, $off_den))?;)?
            type Raw = $raw;
            type Value = $value;
            type Codec = $crate::codec::$codec;
            #[allow(unused_variables)]
            fn check(raw: &$raw) -> Result<(), $crate::ValueError> {
                $($crate::check::in_range(Self::NAME, *raw, $min, $max)?;)?
                $($crate::check::one_of(Self::NAME, *raw, &[$($allowed),*])?;)?
                Ok(())
            }
            $(fn stops(raw: &$raw) -> bool {
                const STOPS: $crate::Stops<'static> = $crate::parameter!(@stops $($stops)*);
                STOPS.stops(i128::from(*raw))
            })?
        }

        #[diagnostic::do_not_recommend]
        impl $crate::ValueOf<$name> for $value {}

        $($crate::parameter!(@capability $name $direction $protocol $placement
            $([bounds: $($bound = $by),+])? $($runtime)?);)*
    };

    (@stops always) => { $crate::Stops::Always };
    (@stops $($mask:literal => $value:literal),+) => {
        $crate::Stops::Matching(&[$($crate::StopPattern { mask: $mask, value: $value }),+])
    };

    (@capability $name:ident read $protocol:ident $placement:tt $($runtime:ident)?) => {
        // Listing the other parameters that do have the capability would drown the message.
        #[diagnostic::do_not_recommend]
        impl $crate::Readable<$crate::parameter!(@protocol $protocol)> for $name {
            const READ_AT: $crate::Placement<$crate::parameter!(@address_type $protocol)> =
                $crate::parameter!(@placement $protocol $placement);
            $($crate::parameter!(@runtime $runtime read_scale $protocol);)?
        }
    };
    (@capability $name:ident write $protocol:ident $placement:tt
        $([bounds: $($bound:ident = $by:ident),+])? $($runtime:ident)?) => {
        #[diagnostic::do_not_recommend]
        impl $crate::Writable<$crate::parameter!(@protocol $protocol)> for $name {
            const WRITE_AT: $crate::Placement<$crate::parameter!(@address_type $protocol)> =
                $crate::parameter!(@placement $protocol $placement);
            $(const BOUNDS: &'static [$crate::BoundBy<$crate::parameter!(@protocol $protocol)>] =
                &[$($crate::BoundBy::of::<$by>($crate::parameter!(@bound $bound))),+];)?
            $($crate::parameter!(@runtime $runtime write_scale $protocol);)?
        }
    };

    // A safety-function parameter (`safety = true`): no `Writable`, only the deliberate write
    // `drivebus::canopen::srdo::write_safety_function` (feature `srdo`).
    (@capability $name:ident safety_write canopen $address:tt $($runtime:ident)?) => {
        #[diagnostic::do_not_recommend]
        impl $crate::canopen::srdo::SafetyFunctionParameter for $name {
            const OBJECT: $crate::canopen::ObjectAddress = $crate::parameter!(@address canopen $address);
        }
    };

    (@runtime runtime $scale_fn:ident $protocol:ident) => {
        fn $scale_fn<L: $crate::Link<Protocol = $crate::parameter!(@protocol $protocol)>>(
            device: &mut $crate::Device<L>,
        ) -> Result<$crate::Scale, $crate::Error> {
            Self::runtime_scale(device)
        }
    };

    (@bound min) => { $crate::Bound::Min };
    (@bound max) => { $crate::Bound::Max };
    (@bound magnitude) => { $crate::Bound::Magnitude };

    (@protocol modbus) => { $crate::modbus::Modbus };
    (@protocol canopen) => { $crate::canopen::CanOpen };
    (@protocol rs232) => { $crate::rs232::Rs232 };
    (@address_type modbus) => { $crate::modbus::ModbusAddress };
    (@address_type canopen) => { $crate::canopen::ObjectAddress };
    (@address_type rs232) => { $crate::canopen::ObjectAddress };

    (@placement $protocol:ident [$($slot:tt),* $(,)?]) => {
        $crate::Placement::PerVariant(&[$($crate::parameter!(@slot $protocol $slot)),*])
    };
    (@placement $protocol:ident $address:tt) => {
        $crate::Placement::Everywhere($crate::parameter!(@address $protocol $address))
    };
    (@slot $protocol:ident _) => { None };
    (@slot $protocol:ident $address:tt) => { Some($crate::parameter!(@address $protocol $address)) };

    (@address modbus ($table:ident $address:literal)) => {
        $crate::modbus::ModbusAddress::$table($address, 1, $crate::modbus::WordOrder::HighFirst)
    };
    (@address modbus ($table:ident $address:literal, $words:literal words, $order:ident)) => {
        $crate::modbus::ModbusAddress::$table($address, $words, $crate::modbus::WordOrder::$order)
    };
    (@address canopen ($index:literal sub $subindex:literal, $bytes:literal bytes)) => {
        $crate::canopen::ObjectAddress::new($index, $subindex, $bytes)
    };
    (@address rs232 ($index:literal sub $subindex:literal, $bytes:literal bytes)) => {
        $crate::canopen::ObjectAddress::new($index, $subindex, $bytes)
    };
}
