//! The drive handle: constructors per protocol and one accessor method per parameter.

use drivebus_model::modbus::RegisterSpan;
use proc_macro2::{Ident, Literal, TokenStream};
use quote::quote;

use super::addresses::hex;
use super::{doc_attrs, ident, raw_type};
use crate::emit::doc;
use crate::ir::{Device, Table};
use crate::names;

fn modbus_limits(device: &Device) -> TokenStream {
    if device.modbus.is_none() {
        return quote! { ::drivebus::modbus::ModbusLimits::SPEC };
    }
    let limits = device.modbus_limits();
    let (read, write) = (limits.max_read_registers, limits.max_write_registers);
    let (multiple, gaps) = (limits.write_multiple, limits.read_gaps);
    let readable = register_spans(limits.readable);
    let unreadable = register_spans(limits.unreadable);
    let read_blocks = register_spans(limits.read_blocks);
    let whole_values = register_spans(limits.whole_values);
    quote! {
        ::drivebus::modbus::ModbusLimits {
            max_read_registers: #read,
            max_write_registers: #write,
            write_multiple: #multiple,
            read_gaps: #gaps,
            readable: #readable,
            unreadable: #unreadable,
            read_blocks: #read_blocks,
            whole_values: #whole_values,
        }
    }
}

/// Register runs as a `&[RegisterSpan]` expression.
fn register_spans(runs: &[RegisterSpan]) -> TokenStream {
    let runs = runs.iter().map(|run| {
        let table = match run.table {
            Table::Input => quote! { input },
            Table::Holding => quote! { holding },
        };
        let (start, count) = (hex(run.start), Literal::u16_unsuffixed(run.count));
        quote! { ::drivebus::modbus::RegisterSpan::#table(#start, #count) }
    });
    quote! { &[#(#runs),*] }
}

fn constructors(device: &Device, handle: &proc_macro2::Ident) -> TokenStream {
    let has_modbus = device.parameters.iter().any(|p| !p.modbus.is_empty());
    let has_canopen = device.parameters.iter().any(|p| !p.canopen.is_empty());
    let has_rs232 = device.parameters.iter().any(|p| !p.rs232.is_empty());
    let limits = modbus_limits(device);
    let modbus = has_modbus.then(|| {
        quote! {
            /// The device's Modbus limits, from its description.
            pub const MODBUS_LIMITS: ::drivebus::modbus::ModbusLimits = #limits;

            impl<B: ::drivebus::modbus::RegisterBus> #handle<::drivebus::modbus::ModbusLink<B>> {
                /// A drive reached over Modbus at `unit`.
                pub fn modbus(bus: B, unit: ::drivebus::modbus::UnitId) -> Self {
                    Self::new(::drivebus::modbus::ModbusLink::new(bus, unit, MODBUS_LIMITS))
                }
            }
        }
    });
    let lss = device.canopen.as_ref().is_some_and(|c| c.lss.is_some());
    let canopen = has_canopen.then(|| {
        quote! {
            /// Whether the drive is an LSS slave (CiA 305), so its node id and bit rate can be
            /// set over LSS (`drivebus::canopen::lss`); from its description.
            pub const LSS_SUPPORTED: bool = #lss;

            impl<B: ::drivebus::canopen::SdoBus> #handle<::drivebus::canopen::CanOpenLink<B>> {
                /// A drive reached over CANopen at `node`.
                pub fn canopen(bus: B, node: ::drivebus::canopen::NodeId) -> Self {
                    Self::new(::drivebus::canopen::CanOpenLink::new(bus, node))
                }
            }
        }
    });
    let rs232 = has_rs232.then(|| {
        quote! {
            impl<B: ::drivebus::rs232::TelegramBus> #handle<::drivebus::rs232::Rs232Link<B>> {
                /// A drive reached over the Kinco RS-232 protocol at `station`.
                pub fn rs232(bus: B, station: ::drivebus::rs232::StationId) -> Self {
                    Self::new(::drivebus::rs232::Rs232Link::new(bus, station))
                }
            }
        }
    });
    quote! { #modbus #canopen #rs232 }
}

/// The items of the async handle, as `async_handle!` takes them: the protocols of its
/// constructors (`, modbus(LIMITS)`), `, identity`, `, variant(SELECTOR, RAW)` and the control
/// items (`, cia402`, `, modes`, `, machine(..)`).
fn async_protocols(device: &Device) -> TokenStream {
    let has = |on: fn(&crate::ir::Parameter) -> bool| device.parameters.iter().any(on);
    let modbus = has(|p| !p.modbus.is_empty()).then(|| quote! { , modbus(MODBUS_LIMITS) });
    let canopen = has(|p| !p.canopen.is_empty()).then(|| quote! { , canopen });
    let rs232 = has(|p| !p.rs232.is_empty()).then(|| quote! { , rs232 });
    let identity = (!device.identity_checks().is_empty()).then(|| quote! { , identity });
    let variant = device.variant_selection().map(|(selector, _)| {
        let marker = ident(&names::camel(&selector.name));
        let raw = raw_type(selector.data_type);
        quote! { , variant(#marker, #raw) }
    });
    let control = super::control::async_items(device);
    quote! { #modbus #canopen #rs232 #identity #variant #control }
}

/// Whether any address of `p` allows reading.
fn readable(p: &crate::ir::Parameter) -> bool {
    p.modbus.iter().any(|a| a.access.read)
        || p.canopen.iter().any(|a| a.access.read)
        || p.rs232.iter().any(|a| a.access.read)
}

/// Every write of it stops the drive (`stops = true`): the handle writes it without an unlock.
/// A parameter only some of whose values stop (`start`, whose word may carry the stop bit) keeps
/// its place behind the unlock guard.
fn is_stop_command(p: &crate::ir::Parameter) -> bool {
    p.stops.as_ref().is_some_and(|s| s.patterns.is_none())
}

/// A marker as the accessor module names it: bare (the module glob-imports `params`), unless the
/// bare name means one of the module's own imports.
fn marker_path(marker: &Ident, handle: &Ident) -> TokenStream {
    let taken = ["Accessor", "LockedAccessor", "Unlocked", "L"];
    if marker == handle || taken.iter().any(|name| marker == name) {
        quote! { params::#marker }
    } else {
        quote! { #marker }
    }
}

pub fn emit(device: &Device) -> TokenStream {
    let handle = ident(&names::camel(&device.device.handle));
    let title = doc::escape(&device.device.name);
    let handle_doc = doc_attrs(&format!("A {title} drive, reached over the link `L`.\n\nEach parameter has an accessor: `drive.<parameter>().read()`, `.write(value)`, `.modify(f)`."));
    let accessors = device
        .parameters
        .iter()
        .filter(|p| !super::indexed::is_member(p, device))
        .filter(|p| device.lock_scope_of(p).is_none() || readable(p) || is_stop_command(p))
        .map(|p| {
            let method = ident(&names::method(&p.name));
            let marker = ident(&names::camel(&p.name));
            let marker_path = marker_path(&marker, &handle);
            let summary = doc::summary(p.doc.as_deref(), &p.name);
            let docs = doc_attrs(&format!("{summary} Details: [`params::{marker}`]."));
            let aliases = super::parameter_doc::aliases(p);
            // A stop is written from the handle too: never held back by the lock's account.
            if let Some(scope) = device.lock_scope_of(p).filter(|_| !is_stop_command(p)) {
                // Written only through the guard of an unlock opening its scope.
                let docs = doc_attrs(&format!(
                    "{summary} Read here; written only while unlocked (scope `{}`, see \
                     [`Unlocked`]). Details: [`params::{marker}`].",
                    doc::escape(&scope.name)
                ));
                return quote! {
                    #docs
                    #aliases
                    pub fn #method(&mut self) -> LockedAccessor<'_, L, #marker_path> {
                        LockedAccessor::new(self.device.parameter())
                    }
                };
            }
            quote! {
                #docs
                #aliases
                pub fn #method(&mut self) -> Accessor<'_, L, #marker_path> {
                    self.device.parameter()
                }
            }
        });
    let variant_setter = (!device.variants.is_empty()).then(|| {
        quote! {
            /// Selects the drive's firmware / configuration variant (the default is the first).
            pub fn set_variant(&mut self, variant: Variant) {
                self.device.set_variant(variant.id());
            }
        }
    });
    let constructors = constructors(device, &handle);
    let async_protocols = async_protocols(device);
    let lock_items = device.lock.is_some().then(|| quote! { , Unlocked });
    let locked_accessor = device.lock.is_some().then(|| quote! { , LockedAccessor });
    // A drive with a write lock: the device follows it (`unlock.rs` emits `WRITE_LOCK`).
    let write_lock = device
        .lock
        .is_some()
        .then(|| quote! { .with_write_lock(&WRITE_LOCK) });
    quote! {
        #handle_doc
        #[derive(Debug)]
        pub struct #handle<L> {
            device: ::drivebus::Device<L>,
        }

        #constructors

        impl<L> #handle<L> {
            /// A drive reached over any link (an async one as `Async(link)`, see `new_async`).
            pub fn new(link: L) -> Self {
                Self { device: ::drivebus::Device::new(link, ::drivebus::VariantId::default())#write_lock }
            }

            /// The runtime device, for generic code.
            pub fn device(&mut self) -> &mut ::drivebus::Device<L> {
                &mut self.device
            }

            /// Gives the link back.
            pub fn into_link(self) -> L {
                self.device.into_link()
            }

            #variant_setter
        }

        impl<L: ::drivebus::Link> #handle<L> {
            /// Reads several parameters at once, e.g. `drive.read_many((params::A, params::B))`,
            /// in as few requests as the link allows.
            pub fn read_many<S: ::drivebus::read_set::ReadSet<L>>(&mut self, set: S) -> Result<S::Values, ::drivebus::Error> {
                self.device.read_many(set)
            }
        }

        // With drivebus's `async`: `new_async`, `read_many_async` and the async constructors.
        ::drivebus::async_handle!(#handle #async_protocols);

        /// The handle's accessors, one per parameter: in a module of their own so that their
        /// signatures name `Accessor` and the markers without a path.
        mod parameter_accessors {
            use super::params::*;
            #[allow(unused_imports)]
            use super::{params, #handle #lock_items};
            use ::drivebus::{Accessor #locked_accessor};

            impl<L> #handle<L> {
                #( #accessors )*
            }
        }
    }
}
