//! `async_handle!`: what a generated handle has over an async link, when drivebus is built with
//! feature `async`; nothing otherwise.
//!
//! The macro is defined here, where the feature is known: a generated crate calls it
//! unconditionally and needs no `cfg` of its own, so a crate generated without an `async`
//! feature still builds, and gets the async API as soon as anything in the dependency graph
//! enables drivebus's `async`.

/// The async handle's inherent items of generated handle `$handle` (which holds a
/// `device: Device<L>` and has `new`): `new_async`, `read_many_async`, and per item listed:
/// one async constructor per protocol (`modbus(LIMITS)`, `canopen`, `rs232`: `modbus_async`,
/// `canopen_async`, `rs232_async`), the async twins of the handle's procedures (`identity`:
/// `verify_identity_async`; `variant(SELECTOR, RAW)`: `detect_variant_async`, over the
/// generated `select_reported_variant`).
#[cfg(feature = "async")]
#[doc(hidden)] // generated crates call it; users never need to
#[macro_export]
macro_rules! async_handle {
    ($handle:ident $(, $item:ident $(($($argument:tt)*))?)* $(,)?) => {
        // Named apart from the blocking `new`/`read_many`: inherent impls of a downstream crate
        // may not share a name even where, as here, no link is both blocking and async.
        impl<L: $crate::asynch::AsyncLink> $handle<$crate::asynch::Async<L>> {
            /// A drive reached over any async link: its accessors return futures.
            pub fn new_async(link: L) -> Self {
                Self::new($crate::asynch::Async(link))
            }

            /// Reads several parameters at once, e.g.
            /// `drive.read_many_async((params::A, params::B)).await`, in as few requests as
            /// the link allows.
            pub async fn read_many_async<S: $crate::asynch::AsyncReadSet<L>>(
                &mut self,
                set: S,
            ) -> Result<S::Values, $crate::Error> {
                self.device().read_many(set).await
            }
        }
        $($crate::async_handle!(@item $handle $item $(($($argument)*))?);)*
    };
    (@item $handle:ident modbus($limits:expr)) => {
        impl<B: $crate::modbus::AsyncRegisterBus>
            $handle<$crate::asynch::Async<$crate::modbus::ModbusLink<B, $crate::modbus::StaticLimits>>>
        {
            /// A drive reached over an async Modbus client at `unit`.
            pub fn modbus_async(bus: B, unit: $crate::modbus::UnitId) -> Self {
                Self::new_async($crate::modbus::ModbusLink::new_static(bus, unit, $limits))
            }
        }
    };
    (@item $handle:ident canopen) => {
        impl<B: $crate::canopen::AsyncSdoBus>
            $handle<$crate::asynch::Async<$crate::canopen::CanOpenLink<B>>>
        {
            /// A drive reached over an async SDO client (`canopen::async_client::AsyncSdo`) at
            /// `node`.
            pub fn canopen_async(bus: B, node: $crate::canopen::NodeId) -> Self {
                Self::new_async($crate::canopen::CanOpenLink::new(bus, node))
            }
        }
    };
    (@item $handle:ident identity) => {
        impl<L: $crate::asynch::AsyncLink> $handle<$crate::asynch::Async<L>>
        where
            Self: $crate::IdentityChecks<L::Protocol>,
        {
            /// `verify_identity` over an async link: the same parameters read, awaited, and the
            /// same conclusion (every later write refused on a value the description does not
            /// cover).
            pub async fn verify_identity_async(&mut self) -> Result<(), $crate::Error> {
                let checks = <Self as $crate::IdentityChecks<L::Protocol>>::IDENTITY_CHECKS;
                self.device().verify_identity(checks).await
            }
        }
    };
    (@item $handle:ident variant($selector:ident, $raw:ty)) => {
        impl<L: $crate::asynch::AsyncLink> $handle<$crate::asynch::Async<L>>
        where
            params::$selector: $crate::Readable<L::Protocol, Raw = $raw>,
        {
            /// `detect_variant` over an async link: the same read, awaited, and the same
            /// selection (or refusal of writes on a value no variant is selected by).
            pub async fn detect_variant_async(
                &mut self,
            ) -> Result<VariantSelection, $crate::Error> {
                let raw = self.device().read_raw::<params::$selector>().await?;
                Ok(self.select_reported_variant(raw))
            }
        }
    };
    (@item $handle:ident rs232) => {
        impl<B: $crate::rs232::AsyncTelegramBus>
            $handle<$crate::asynch::Async<$crate::rs232::Rs232Link<B>>>
        {
            /// A drive reached over an async Kinco RS-232 host
            /// (`rs232::async_client::AsyncRs232Client`) at `station`.
            pub fn rs232_async(bus: B, station: $crate::rs232::StationId) -> Self {
                Self::new_async($crate::rs232::Rs232Link::new(bus, station))
            }
        }
    };
}

/// Without feature `async`, a generated handle has no async items.
#[cfg(not(feature = "async"))]
#[doc(hidden)]
#[macro_export]
macro_rules! async_handle {
    ($($tokens:tt)*) => {};
}
