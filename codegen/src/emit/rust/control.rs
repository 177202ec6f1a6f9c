//! Drive control: the CiA 402 driver hooks (quirks const, `Cia402Objects` / `Cia402Modes` impls,
//! `enable_operation` & co. on the handle) when the description has the CiA 402 objects, and a
//! vendor state machine as data (`[state_machine]`) with its typed states.

use drivebus_model::control::{Machine, Quirk, TransitionKind as Cause};
use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

use super::{doc_attrs, ident};
use crate::emit::doc;
use crate::ir::{DataType, Device, Parameter};
use crate::names;

/// The parameter at CANopen object `index`, subindex 0, of type `data_type`.
fn object(device: &Device, index: u16, data_type: DataType) -> Option<&Parameter> {
    device.parameters.iter().find(|p| {
        p.data_type == data_type
            && p.canopen
                .iter()
                .any(|a| a.index == index && a.subindex == 0)
    })
}

fn marker(parameter: &Parameter) -> Ident {
    ident(&names::camel(&parameter.name))
}

fn quirks(device: &Device) -> TokenStream {
    let Some(c) = &device.cia402 else {
        return quote! { ::drivebus::control::Quirks::STANDARD };
    };
    let named = c
        .quirks
        .iter()
        .filter_map(|q| Quirk::from_name(q))
        .map(|q| format_ident!("{}", format!("{q:?}")));
    let hold = proc_macro2::Literal::u32_unsuffixed(c.fault_reset_hold_ms);
    quote! {
        ::drivebus::control::Quirks {
            fault_reset_hold_ms: #hold,
            ..::drivebus::control::Quirks::STANDARD #( .with(::drivebus::control::Quirk::#named) )*
        }
    }
}

fn cia402(device: &Device, handle: &Ident) -> Option<TokenStream> {
    let (control, status) = cia402_objects(device)?;
    let (control, status) = (marker(control), marker(status));
    let sto = device.cia402.as_ref().and_then(|c| c.sto_bit.as_ref());
    let sto_word = sto
        .and_then(|s| device.parameter(&s.parameter))
        .map_or_else(|| status.clone(), marker);
    let sto_bound = (sto_word != status)
        .then(|| quote! { params::#sto_word: ::drivebus::Readable<L::Protocol>, });
    let sto_bit = match sto.map(|s| s.bit) {
        Some(bit) => quote! { Some(#bit) },
        None => quote! { None },
    };
    let quirks = quirks(device);
    let walk_bounds = quote! {
        params::#control: ::drivebus::Readable<L::Protocol> + ::drivebus::Writable<L::Protocol>,
        params::#status: ::drivebus::Readable<L::Protocol>,
        #sto_bound
    };
    let quick_stop_option = super::quick_stop_option::emit(device, handle, &walk_bounds);
    let modes = modes(device, handle, &control);
    let motion = super::motion::emit(device, handle, &control, &status);
    Some(quote! {
        /// The drive's deviations from CiA 402 (its description's `[cia402]` table), read by the
        /// control driver.
        pub const CIA402_QUIRKS: ::drivebus::control::Quirks = #quirks;

        impl<L> ::drivebus::control::Cia402Objects for #handle<L> {
            type Controlword = params::#control;
            type Statusword = params::#status;
            type SafeTorqueOffWord = params::#sto_word;
            const SAFE_TORQUE_OFF_BIT: Option<u8> = #sto_bit;
            const QUIRKS: ::drivebus::control::Quirks = CIA402_QUIRKS;
        }

        #[cfg(feature = "std")]
        impl<L: ::drivebus::Link> #handle<L>
        where
            #walk_bounds
        {
            /// Brings the drive to CiA 402 *operation enabled* (halt clear), polling the statusword
            /// until `deadline`; the error says which state it got stuck in and why.
            pub fn enable_operation(&mut self, deadline: ::drivebus::control::driver::Instant) -> Result<(), ::drivebus::control::driver::ControlError> {
                ::drivebus::control::driver::drive_to::<Self, L>(&mut self.device, ::drivebus::control::Target::OperationEnabled, deadline)
            }

            /// Brings the drive to CiA 402 *switch on disabled* (no voltage on the motor).
            pub fn disable(&mut self, deadline: ::drivebus::control::driver::Instant) -> Result<(), ::drivebus::control::driver::ControlError> {
                ::drivebus::control::driver::drive_to::<Self, L>(&mut self.device, ::drivebus::control::Target::SwitchOnDisabled, deadline)
            }

            /// Quick stop: from operation enabled to *quick stop active*; disables from other states.
            pub fn quick_stop(&mut self, deadline: ::drivebus::control::driver::Instant) -> Result<(), ::drivebus::control::driver::ControlError> {
                ::drivebus::control::driver::quick_stop::<Self, L>(&mut self.device, deadline)
            }

            /// Resets a fault (rising edge of controlword bit 7, held as the description says).
            pub fn fault_reset(&mut self, deadline: ::drivebus::control::driver::Instant) -> Result<(), ::drivebus::control::driver::ControlError> {
                ::drivebus::control::driver::fault_reset::<Self, L>(&mut self.device, deadline)
            }

            /// The CiA 402 state the statusword shows (`None`: no defined state).
            pub fn cia402_state(&mut self) -> Result<Option<::drivebus::control::State>, ::drivebus::Error> {
                ::drivebus::control::driver::state::<Self, L>(&mut self.device)
            }
        }

        #quick_stop_option

        #modes

        #motion
    })
}

/// The controlword and statusword (0x6040, 0x6041), when the description has both.
fn cia402_objects(device: &Device) -> Option<(&Parameter, &Parameter)> {
    Some((
        object(device, 0x6040, DataType::Unsigned(2))?,
        object(device, 0x6041, DataType::Unsigned(2))?,
    ))
}

/// The modes of operation and their display (0x6060, 0x6061) with their one enumeration, when
/// the description has them.
fn mode_objects(device: &Device) -> Option<(&Parameter, &Parameter, &str)> {
    let request = object(device, 0x6060, DataType::Signed(1))?;
    let display = object(device, 0x6061, DataType::Signed(1))?;
    let modes = request.enumeration.as_deref()?;
    (display.enumeration.as_deref() == Some(modes)).then_some((request, display, modes))
}

fn modes(device: &Device, handle: &Ident, control: &Ident) -> Option<TokenStream> {
    let (request, display, modes) = mode_objects(device)?;
    let mode = ident(&names::camel(modes));
    let (request, display) = (marker(request), marker(display));
    Some(quote! {
        impl<L> ::drivebus::control::Cia402Modes for #handle<L> {
            type Mode = types::#mode;
            type ModesOfOperation = params::#request;
            type ModesOfOperationDisplay = params::#display;
        }

        #[cfg(feature = "std")]
        impl<L: ::drivebus::Link> #handle<L>
        where
            params::#control: ::drivebus::Readable<L::Protocol> + ::drivebus::Writable<L::Protocol>,
            params::#request: ::drivebus::Writable<L::Protocol>,
            params::#display: ::drivebus::Readable<L::Protocol>,
        {
            /// Requests a mode of operation and waits until the mode display confirms it.
            pub fn set_mode(&mut self, mode: types::#mode, deadline: ::drivebus::control::driver::Instant) -> Result<(), ::drivebus::control::driver::ControlError> {
                ::drivebus::control::driver::set_mode::<Self, L>(&mut self.device, mode, deadline)
            }
        }
    })
}

/// The machine's table as a `Machine<'static>` literal, written from the IR's view of it.
fn machine_data(m: &Machine<'_>) -> TokenStream {
    let states = m.states.iter().map(|s| {
        let name = s.name;
        let (masks, values): (Vec<TokenStream>, Vec<TokenStream>) = s
            .patterns
            .iter()
            .map(|p| (super::hex(p.mask.into()), super::hex(p.value.into())))
            .unzip();
        quote! {
            ::drivebus::control::StateDef {
                name: #name,
                patterns: &[ #( ::drivebus::control::StatePattern { mask: #masks, value: #values } ),* ],
            }
        }
    });
    let transitions = m.transitions.iter().map(|t| {
        let kind = match t.kind {
            Cause::Command(value) => {
                let value = super::unsuffixed(value.into());
                quote! { ::drivebus::control::TransitionKind::Command(#value) }
            }
            Cause::Automatic => quote! { ::drivebus::control::TransitionKind::Automatic },
            Cause::External => quote! { ::drivebus::control::TransitionKind::External },
        };
        let (name, text) = (t.name, t.doc);
        let from = proc_macro2::Literal::u8_unsuffixed(t.from);
        let to = proc_macro2::Literal::u8_unsuffixed(t.to);
        quote! {
            ::drivebus::control::TransitionDef { name: #name, from: #from, to: #to, kind: #kind, doc: #text }
        }
    });
    quote! {
        ::drivebus::control::Machine {
            states: &[ #( #states ),* ],
            transitions: &[ #( #transitions ),* ],
        }
    }
}

fn vendor(device: &Device, handle: &Ident) -> Option<TokenStream> {
    let m = device.state_machine.as_ref()?;
    let status = marker(device.parameter(&m.status)?);
    let command = marker(device.parameter(&m.command)?);
    let module = ident(&names::snake(&m.name));
    let variants: Vec<Ident> = m
        .states
        .iter()
        .map(|s| ident(&names::camel(&s.name)))
        .collect();
    let state_names = m.states.iter().map(|s| s.name.as_str());
    let state_docs = m
        .states
        .iter()
        .map(|s| doc_attrs(&doc::escape(s.doc.as_deref().unwrap_or(&s.name))));
    let module_doc = doc_attrs(&doc::escape(m.doc.as_deref().unwrap_or(&m.name)));
    let data = m.with_view(machine_data);
    let goto = format_ident!("goto_{}", module);
    let current = format_ident!("{}_state", module);
    Some(quote! {
        #module_doc
        pub mod #module {
            /// The states, recognised from the status register in this order.
            #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
            pub enum State {
                #( #state_docs #variants, )*
            }

            impl State {
                const ALL: &'static [State] = &[ #( State::#variants ),* ];

                /// Name as in the description.
                pub const fn name(self) -> &'static str {
                    match self { #( State::#variants => #state_names, )* }
                }

                /// The state a status register value shows, if any.
                pub fn from_status(status: u16) -> Option<State> {
                    let index = MACHINE.recognise(status)?;
                    Self::ALL.get(usize::from(index)).copied()
                }
            }

            /// States and transitions as data, walked by `drivebus::control::machine`'s planner.
            pub const MACHINE: ::drivebus::control::Machine<'static> = #data;

            /// The machine's registers, for `drivebus::control::driver::goto_state`.
            #[derive(Debug, Clone, Copy)]
            pub struct Registers;

            impl ::drivebus::control::VendorMachine for Registers {
                type Status = super::params::#status;
                type Command = super::params::#command;
                const MACHINE: ::drivebus::control::Machine<'static> = MACHINE;
            }
        }

        #[cfg(feature = "std")]
        impl<L: ::drivebus::Link> #handle<L>
        where
            params::#status: ::drivebus::Readable<L::Protocol>,
            params::#command: ::drivebus::Writable<L::Protocol>,
        {
            /// Walks the state machine to `state`, writing commands and polling the status until
            /// `deadline`; the error says where it got stuck and which transition was missing.
            pub fn #goto(&mut self, state: #module::State, deadline: ::drivebus::control::driver::Instant) -> Result<(), ::drivebus::control::driver::ControlError> {
                ::drivebus::control::driver::goto_state::<#module::Registers, L>(&mut self.device, state.name(), deadline)
            }

            /// The state the status register shows (`None`: none of the machine's states).
            pub fn #current(&mut self) -> Result<Option<#module::State>, ::drivebus::Error> {
                Ok(#module::State::from_status(self.device.read_raw::<params::#status>()?))
            }
        }
    })
}

/// The control items of the async handle, as `drivebus::async_handle!` takes them: `, cia402`,
/// `, quick_stop_option`, `, modes` and `, machine(MODULE, GOTO, CURRENT)` where the blocking
/// handle has the methods (the async ones are written once, in drivebus, over the same driver
/// steps).
pub fn async_items(device: &Device) -> TokenStream {
    let cia402 = cia402_objects(device).map(|_| {
        let quick_stop_option = super::quick_stop_option::async_item(device);
        quote! { , cia402 #quick_stop_option }
    });
    let modes = mode_objects(device).map(|_| quote! { , modes });
    let machine = device.state_machine.as_ref().filter(|m| {
        device.parameter(&m.status).is_some() && device.parameter(&m.command).is_some()
    });
    let machine = machine.map(|m| {
        let module = ident(&names::snake(&m.name));
        let goto = format_ident!("goto_{}_async", module);
        let current = format_ident!("{}_state_async", module);
        quote! { , machine(#module, #goto, #current) }
    });
    quote! { #cia402 #modes #machine }
}

/// Control items of the drive handle `handle`; empty when the description has none.
pub fn emit(device: &Device, handle: &Ident) -> TokenStream {
    let cia402 = cia402(device, handle);
    let vendor = vendor(device, handle);
    quote! { #cia402 #vendor }
}

#[cfg(test)]
mod tests {
    use crate::test_support::HEADER;

    /// The generated source of `HEADER + body`.
    fn generated(name: &str, body: &str) -> String {
        let dir =
            std::env::temp_dir().join(format!("drivegen-control-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("device.toml");
        std::fs::write(&path, format!("{HEADER}{body}")).unwrap();
        let checked = crate::check(&path);
        std::fs::remove_dir_all(&dir).unwrap();
        let device = checked.device.expect("the description is valid");
        crate::emit::rust::generate(&device, "test")
    }

    const OBJECTS: &str = r#"
[[parameter]]
name = "controlword"
type = "u16"
canopen = { index = 0x6040, access = "rw" }
source = { doc = "m", line = 1 }

[[parameter]]
name = "statusword"
type = "u16"
canopen = { index = 0x6041, access = "ro" }
source = { doc = "m", line = 2 }

[[parameter]]
name = "sto_status"
type = "u16"
canopen = { index = 0x6644, access = "ro" }
source = { doc = "m", line = 3 }
"#;

    #[test]
    fn declared_quirks_and_sto_bit_reach_the_generated_const() {
        let code = generated("quirks", &format!(
            "{OBJECTS}\n[cia402]\nquirks = [\"mode-change-needs-halt-clear\", \"honours-remote\"]\nfault_reset_hold_ms = 50\nsto_bit = {{ parameter = \"sto_status\", bit = 3 }}\nsource = {{ doc = \"m\", line = 4 }}\n"
        ));
        let flat: String = code.split_whitespace().collect();
        assert!(flat.contains("fault_reset_hold_ms:50,"), "{code}");
        assert!(flat.contains(".with(::drivebus::control::Quirk::ModeChangeNeedsHaltClear).with(::drivebus::control::Quirk::HonoursRemote)"), "{code}");
        assert!(
            flat.contains("typeSafeTorqueOffWord=params::StoStatus;"),
            "{code}"
        );
        assert!(
            flat.contains("constSAFE_TORQUE_OFF_BIT:Option<u8>=Some(3u8);"),
            "{code}"
        );
        assert!(code.contains("pub fn enable_operation"), "{code}");
    }

    #[test]
    fn no_cia402_objects_no_control_methods() {
        let code = generated("none", &OBJECTS.replace("0x6041", "0x2041"));
        assert!(!code.contains("Cia402Objects"), "{code}");
        assert!(!code.contains("enable_operation"), "{code}");
    }
}
