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
/// generated `select_reported_variant`), and the async twins of the control driver's methods
/// (`cia402`: `enable_operation_async`, `disable_async`, `quick_stop_async`,
/// `fault_reset_async`, `cia402_state_async`; `quick_stop_option`:
/// `quick_stop_by_option_code_async`; `modes`: `set_mode_async`;
/// `machine(MODULE, GOTO, CURRENT)`: the vendor machine's walk and state, named `GOTO` and
/// `CURRENT`), over `drivebus::control::async_driver`.
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
    (@item $handle:ident cia402) => {
        impl<L: $crate::asynch::AsyncLink> $handle<$crate::asynch::Async<L>>
        where
            Self: $crate::control::Cia402Objects,
            <Self as $crate::control::Cia402Objects>::Controlword:
                $crate::Readable<L::Protocol> + $crate::Writable<L::Protocol>,
            <Self as $crate::control::Cia402Objects>::Statusword: $crate::Readable<L::Protocol>,
            <Self as $crate::control::Cia402Objects>::SafeTorqueOffWord:
                $crate::Readable<L::Protocol>,
        {
            /// `enable_operation` awaited: the same walk to CiA 402 *operation enabled*, polling
            /// on `timer` for at most `limit`; the error says where the drive got stuck and why.
            pub async fn enable_operation_async(
                &mut self,
                timer: &impl $crate::asynch::Timer,
                limit: ::core::time::Duration,
            ) -> Result<(), $crate::control::ControlError> {
                let target = $crate::control::Target::OperationEnabled;
                $crate::control::async_driver::drive_to::<Self, L>(self.device(), target, timer, limit)
                    .await
            }

            /// `disable` awaited: to CiA 402 *switch on disabled* (no voltage on the motor).
            pub async fn disable_async(
                &mut self,
                timer: &impl $crate::asynch::Timer,
                limit: ::core::time::Duration,
            ) -> Result<(), $crate::control::ControlError> {
                let target = $crate::control::Target::SwitchOnDisabled;
                $crate::control::async_driver::drive_to::<Self, L>(self.device(), target, timer, limit)
                    .await
            }

            /// `quick_stop` awaited: from operation enabled to *quick stop active*; disables
            /// from other states.
            pub async fn quick_stop_async(
                &mut self,
                timer: &impl $crate::asynch::Timer,
                limit: ::core::time::Duration,
            ) -> Result<(), $crate::control::ControlError> {
                $crate::control::async_driver::quick_stop::<Self, L>(self.device(), timer, limit)
                    .await
            }

            /// `fault_reset` awaited: resets a fault (rising edge of controlword bit 7, held as
            /// the description says).
            pub async fn fault_reset_async(
                &mut self,
                timer: &impl $crate::asynch::Timer,
                limit: ::core::time::Duration,
            ) -> Result<(), $crate::control::ControlError> {
                $crate::control::async_driver::fault_reset::<Self, L>(self.device(), timer, limit)
                    .await
            }

            /// `cia402_state` awaited: the CiA 402 state the statusword shows.
            pub async fn cia402_state_async(
                &mut self,
            ) -> Result<Option<$crate::control::State>, $crate::Error> {
                $crate::control::async_driver::state::<Self, L>(self.device()).await
            }
        }
    };
    (@item $handle:ident quick_stop_option) => {
        impl<L: $crate::asynch::AsyncLink> $handle<$crate::asynch::Async<L>>
        where
            Self: $crate::control::objects_on::QuickStopOptionOn<L::Protocol>,
        {
            /// `quick_stop_by_option_code` awaited: quick stop seen through to the end the
            /// drive's quick stop option code (605Ah) gives, polling on `timer` for at most
            /// `limit`. The quick stop command goes out first; 605Ah is read only then, within
            /// the same `limit`, so a slow or failed read of the code never holds the stop back.
            pub async fn quick_stop_by_option_code_async(
                &mut self,
                timer: &impl $crate::asynch::Timer,
                limit: ::core::time::Duration,
            ) -> Result<(), $crate::control::ControlError> {
                let device = self.device();
                $crate::control::async_driver::quick_stop_by_option_code::<Self, L>(device, timer, limit)
                    .await
            }
        }
    };
    (@item $handle:ident modes) => {
        impl<L: $crate::asynch::AsyncLink> $handle<$crate::asynch::Async<L>>
        where
            Self: $crate::control::Cia402Modes,
            <Self as $crate::control::Cia402Objects>::Controlword:
                $crate::Readable<L::Protocol> + $crate::Writable<L::Protocol>,
            <Self as $crate::control::Cia402Modes>::ModesOfOperation:
                $crate::Writable<L::Protocol>,
            <Self as $crate::control::Cia402Modes>::ModesOfOperationDisplay:
                $crate::Readable<L::Protocol>,
        {
            /// `set_mode` awaited: requests a mode of operation and waits, polling on `timer`
            /// for at most `limit`, until the mode display confirms it.
            pub async fn set_mode_async(
                &mut self,
                mode: <Self as $crate::control::Cia402Modes>::Mode,
                timer: &impl $crate::asynch::Timer,
                limit: ::core::time::Duration,
            ) -> Result<(), $crate::control::ControlError> {
                $crate::control::async_driver::set_mode::<Self, L>(self.device(), mode, timer, limit)
                    .await
            }
        }
    };
    (@item $handle:ident machine($module:ident, $goto:ident, $current:ident)) => {
        impl<L: $crate::asynch::AsyncLink> $handle<$crate::asynch::Async<L>>
        where
            <$module::Registers as $crate::control::VendorMachine>::Status:
                $crate::Readable<L::Protocol>,
            <$module::Registers as $crate::control::VendorMachine>::Command:
                $crate::Writable<L::Protocol>,
        {
            /// The blocking `goto_` method awaited: walks the state machine to `state`, writing
            /// commands and polling the status on `timer` for at most `limit`.
            pub async fn $goto(
                &mut self,
                state: $module::State,
                timer: &impl $crate::asynch::Timer,
                limit: ::core::time::Duration,
            ) -> Result<(), $crate::control::ControlError> {
                let device = self.device();
                $crate::control::async_driver::goto_state::<$module::Registers, L>(
                    device,
                    state.name(),
                    timer,
                    limit,
                )
                .await
            }

            /// The state the status register shows (`None`: none of the machine's states).
            pub async fn $current(&mut self) -> Result<Option<$module::State>, $crate::Error> {
                type Status = <$module::Registers as $crate::control::VendorMachine>::Status;
                let status = self.device().read_raw::<Status>().await?;
                Ok($module::State::from_status(status))
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

/// The items given, when drivebus is built with feature `async`; nothing otherwise: how a
/// generated crate writes async items of its own (the async unlock guard) without a `cfg`.
#[cfg(feature = "async")]
#[doc(hidden)]
#[macro_export]
macro_rules! if_async {
    ($($items:tt)*) => { $($items)* };
}

/// Without feature `async`, no async items.
#[cfg(not(feature = "async"))]
#[doc(hidden)]
#[macro_export]
macro_rules! if_async {
    ($($items:tt)*) => {};
}
