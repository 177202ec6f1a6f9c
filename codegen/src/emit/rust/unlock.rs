//! The write lock as a typed session (`[lock]`, `[[unlock]]`): a parameter that needs an unlock
//! has no setter on the handle (its handle accessor is drivebus's `LockedAccessor` read view, or
//! absent when it cannot be read); `drive.unlock_<name>(..)` checks the unlock's requirement,
//! writes the grant and returns an `Unlocked` guard borrowing the handle, whose methods are the
//! setters of the scopes the unlock opens. `lock()` or dropping the guard writes the lock
//! command. A write the drive refuses with the lock's exception code converts into
//! `UnlockError::Locked`. With drivebus's `async` (through `drivebus::if_async!`), the async
//! handle has `unlock_<name>_async(..).await` and the guard `AsyncUnlocked`, whose
//! `lock().await` locks; dropped without it, it leaves the lock owed on the device, sent before
//! the next request.

use proc_macro2::{Ident, TokenStream};
use quote::quote;

use super::{doc_attrs, enums::int_literal, ident};
use crate::emit::doc;
use crate::names;
use drivebus_model::write_lock::WriteLock;

use crate::ir::{Device, GrantKey, Lock, LockScope, Parameter, Unlock};

/// The trait an unlock marker implements for each scope it opens: `OpensControls`.
fn opens_trait(scope: &str) -> Ident {
    ident(&format!("Opens{}", names::camel(scope)))
}

/// The marker type of an unlock: `unlock::Controls`.
fn marker(unlock: &Unlock) -> Ident {
    ident(&names::camel(&unlock.name))
}

pub fn emit(device: &Device) -> TokenStream {
    let Some(lock) = &device.lock else {
        return TokenStream::new();
    };
    let handle = ident(&names::camel(&device.device.handle));
    let lock_marker = ident(&names::camel(&lock.command));
    let lock_bound = quote! { params::#lock_marker: ::drivebus::Writable<L::Protocol> };
    let scopes = lock
        .scopes
        .iter()
        .map(|s| scope_setters(device, s, &lock_bound));
    let unlocks = lock
        .unlocks
        .iter()
        .map(|u| unlock_method(device, u, &handle, &lock_bound, Flavor::Blocking));
    let async_scopes = lock
        .scopes
        .iter()
        .map(|s| async_scope_setters(device, s, &lock_bound));
    let async_unlocks = lock
        .unlocks
        .iter()
        .map(|u| unlock_method(device, u, &handle, &lock_bound, Flavor::Async));
    let async_guard = async_guard(&handle, &lock_marker, &lock_bound);
    let refusal: proc_macro2::Literal = format!("0x{:02X}", lock.refusal)
        .parse()
        .expect("a hexadecimal integer is a literal");
    let refusal_doc = doc_attrs(&format!(
        "The Modbus exception code the drive answers a write with while it is locked ({:#04x}).",
        lock.refusal
    ));
    let items = [
        markers(lock),
        quote! {
            #refusal_doc
            pub const LOCKED_EXCEPTION: u8 = #refusal;
        },
        device.with_write_lock(write_lock_table).unwrap_or_default(),
        error_type(),
        guard(&handle, &lock_marker, &lock_bound),
    ];
    let blocking = quote! {
        #( #items )*
        #( #scopes )*
        #( #unlocks )*
    };
    // With drivebus's `async`: the async unlocks, their guard and its setters.
    let async_items = quote! {
        #async_guard
        #( #async_scopes )*
        #( #async_unlocks )*
    };
    let gated = super::layout::block_call("::drivebus::if_async", async_items);
    quote! {
        #blocking
        #gated
    }
}

/// Which API an item belongs to: the blocking handle's, or the async handle's (`_async`).
#[derive(Clone, Copy, PartialEq)]
enum Flavor {
    Blocking,
    Async,
}

/// `pub mod unlock`: a trait per scope and a marker per unlock implementing the scopes it opens.
fn markers(lock: &Lock) -> TokenStream {
    let traits = lock.scopes.iter().map(|s| {
        let name = opens_trait(&s.name);
        let text = s.doc.as_deref().map(doc::escape).unwrap_or_default();
        let docs = doc_attrs(&format!(
            "Unlocks that open the scope `{}`. {text}",
            doc::escape(&s.name)
        ));
        quote! { #docs pub trait #name {} }
    });
    let unlocks = lock.unlocks.iter().map(|u| {
        let name = marker(u);
        let text = u.doc.as_deref().map(doc::escape).unwrap_or_default();
        let docs = doc_attrs(&format!(
            "The unlock `{}` (`unlock_{}`). {text}",
            doc::escape(&u.name),
            names::snake(&u.name)
        ));
        let opens = u.allows.iter().map(|s| opens_trait(s));
        quote! {
            #docs
            #[derive(Debug)]
            pub enum #name {}
            #( impl #opens for #name {} )*
        }
    });
    quote! {
        /// What an unlock opens: one trait per scope of parameters, one marker per way of unlocking.
        pub mod unlock {
            #( #traits )*
            #( #unlocks )*
        }
    }
}

/// `WRITE_LOCK`: the lock as the runtime device follows it, so that a write to a locked
/// parameter through any path (`drive.device().write_raw(..)` too) is refused before sending;
/// written from the IR's view of the lock.
fn write_lock_table(lock: &WriteLock<'_>) -> TokenStream {
    let command = lock.command;
    let literal = |v: &i128| proc_macro2::Literal::i128_unsuffixed(*v);
    let scopes = lock.scopes.iter().map(|scope| {
        let (name, parameters, opened_by) = (scope.name, scope.parameters, scope.opened_by);
        quote! {
            ::drivebus::write_lock::LockScope {
                name: #name,
                parameters: &[#( #parameters ),*],
                opened_by: &[#( #opened_by ),*],
            }
        }
    });
    let unlocks = lock.unlocks.iter().map(|unlock| {
        let (name, grant, opens) = (unlock.name, unlock.grant, unlock.opens);
        let key = match &unlock.key {
            Some(v) => {
                let v = literal(v);
                quote! { Some(#v) }
            }
            None => quote! { None },
        };
        let lost_without = match &unlock.lost_without {
            Some(r) => {
                let parameter = r.parameter;
                let values = r.values.iter().map(literal);
                let scopes = r.scopes;
                quote! {
                    Some(::drivebus::write_lock::Requirement {
                        parameter: #parameter,
                        values: &[#( #values ),*],
                        scopes: &[#( #scopes ),*],
                    })
                }
            }
            None => quote! { None },
        };
        quote! {
            ::drivebus::write_lock::UnlockRule {
                name: #name,
                grant: #grant,
                key: #key,
                opens: &[#( #opens ),*],
                lost_without: #lost_without,
            }
        }
    });
    quote! {
        /// The write lock as the runtime device follows it: the handle starts locked, and a
        /// write to a parameter of a scope no unlock sent through the handle opens is refused
        /// before sending (`drivebus::WriteRefusal::Locked`), on the untyped
        /// `drive.device().write_raw(..)` path too.
        pub static WRITE_LOCK: ::drivebus::write_lock::WriteLock = ::drivebus::write_lock::WriteLock {
            command: #command,
            refusal: LOCKED_EXCEPTION,
            scopes: &[#( #scopes ),*],
            unlocks: &[#( #unlocks ),*],
        };
    }
}

/// The guard's setters of one scope: one accessor per parameter of the scope.
fn scope_setters(device: &Device, scope: &LockScope, lock_bound: &TokenStream) -> TokenStream {
    let opens = opens_trait(&scope.name);
    let setters = setters(device, scope, quote! { L });
    quote! {
        impl<'d, L: ::drivebus::Link, U: unlock::#opens> Unlocked<'d, L, U>
        where
            #lock_bound
        {
            #( #setters )*
        }
    }
}

/// The async guard's setters of one scope: the blocking guard's, over `Async<L>`.
fn async_scope_setters(
    device: &Device,
    scope: &LockScope,
    lock_bound: &TokenStream,
) -> TokenStream {
    let opens = opens_trait(&scope.name);
    let setters = setters(device, scope, quote! { ::drivebus::asynch::Async<L> });
    quote! {
        impl<'d, L: ::drivebus::asynch::AsyncLink, U: unlock::#opens> AsyncUnlocked<'d, L, U>
        where
            #lock_bound
        {
            #( #setters )*
        }
    }
}

/// One accessor over `link` per parameter of `scope`.
fn setters<'a>(
    device: &'a Device,
    scope: &'a LockScope,
    link: TokenStream,
) -> impl Iterator<Item = TokenStream> + 'a {
    device
        .scope_members(&scope.name)
        .filter(|p| !super::indexed::is_member(p, device))
        .map(move |p| setter(p, &link))
}

fn setter(p: &Parameter, link: &TokenStream) -> TokenStream {
    let method = ident(&names::method(&p.name));
    let marker = ident(&names::camel(&p.name));
    let summary = doc::summary(p.doc.as_deref(), &p.name);
    let docs = doc_attrs(&format!(
        "{summary} Writable while unlocked. Details: [`params::{marker}`]."
    ));
    let aliases = super::parameter_doc::aliases(p);
    quote! {
        #docs
        #aliases
        pub fn #method(&mut self) -> ::drivebus::Accessor<'_, #link, params::#marker> {
            self.drive.device.parameter()
        }
    }
}

/// `drive.unlock_<name>(..)`: checks the requirement, writes the grant, returns the guard.
fn unlock_method(
    device: &Device,
    unlock: &Unlock,
    handle: &Ident,
    lock_bound: &TokenStream,
    flavor: Flavor,
) -> TokenStream {
    let suffix = if flavor == Flavor::Async {
        "_async"
    } else {
        ""
    };
    let method = ident(&format!("unlock_{}{suffix}", names::snake(&unlock.name)));
    let awaited = (flavor == Flavor::Async).then(|| quote! { .await });
    let unlock_marker = marker(unlock);
    let Some(grant) = device.parameter(&unlock.grant.parameter) else {
        return TokenStream::new();
    };
    let grant_marker = ident(&names::camel(&grant.name));
    let (argument, value, key_doc) = match &unlock.grant.key {
        GrantKey::Value(v) => {
            let literal = int_literal(i128::from(*v), grant.data_type);
            (
                quote! {},
                quote! { #literal },
                format!("writes {v} to `{}`", grant.name),
            )
        }
        GrantKey::Password(password) => (
            quote! { password: <params::#grant_marker as ::drivebus::Parameter>::Raw },
            quote! { password },
            format!(
                "writes `password` (the drive's `{password}`) to `{}`",
                grant.name
            ),
        ),
    };
    let (requirement, requirement_bound, requirement_doc) = match &unlock.requires {
        Some(r) => {
            let marker = ident(&names::camel(&r.parameter));
            let name = &r.parameter;
            let values = r.values.iter().map(|v| super::unsuffixed(i128::from(*v)));
            let listed: Vec<String> = r.values.iter().map(i64::to_string).collect();
            (
                quote! {
                    let found = ::core::primitive::i128::from(self.device.read_raw::<params::#marker>() #awaited ?);
                    const ALLOWED: &[::core::primitive::i128] = &[#( #values ),*];
                    if !ALLOWED.contains(&found) {
                        return Err(UnlockError::Requirement { parameter: #name, found, allowed: ALLOWED });
                    }
                },
                quote! { params::#marker: ::drivebus::Readable<L::Protocol>, },
                format!(
                    " First reads `{name}`: unless it is {}, nothing is written and \
                     [`UnlockError::Requirement`] names the value found.",
                    listed.join(" or ")
                ),
            )
        }
        None => (quote! {}, quote! {}, String::new()),
    };
    let ends: Vec<String> = unlock
        .ends
        .iter()
        .map(|e| format!("`{}`", e.name()))
        .collect();
    let text = unlock.doc.as_deref().map(doc::escape).unwrap_or_default();
    let docs =
        doc_attrs(&format!(
        "Unlocks `{}`: {key_doc}, opening {}.{requirement_doc} {text}\n\nThe unlock lasts until \
         the guard is locked or dropped, or the drive ends it ({}); a write after that fails \
         with [`UnlockError::Locked`].",
        unlock.name,
        unlock.allows.iter().map(|s| format!("`{s}`")).collect::<Vec<_>>().join(" and "),
        ends.join(", ")
    ));
    let bounds = quote! {
        #lock_bound,
        params::#grant_marker: ::drivebus::Writable<L::Protocol>,
        #requirement_bound
    };
    let body = quote! {
        #requirement
        self.device.write_raw::<params::#grant_marker>(#value) #awaited ?;
    };
    match flavor {
        Flavor::Blocking => quote! {
            impl<L: ::drivebus::Link> #handle<L> where #bounds {
                #docs
                pub fn #method(&mut self, #argument) -> Result<Unlocked<'_, L, unlock::#unlock_marker>, UnlockError> {
                    #body
                    Ok(Unlocked::new(self))
                }
            }
        },
        Flavor::Async => {
            let blocking = format!("unlock_{}", names::snake(&unlock.name));
            let docs = doc_attrs(&format!(
                "`{blocking}` awaited: the same requirement and grant, and an [`AsyncUnlocked`] \
                 guard, which locks on `lock().await` (dropped without it, it leaves the lock \
                 owed: the handle's next request sends it first)."
            ));
            quote! {
                impl<L: ::drivebus::asynch::AsyncLink> #handle<::drivebus::asynch::Async<L>> where #bounds {
                    #docs
                    pub async fn #method(&mut self, #argument) -> Result<AsyncUnlocked<'_, L, unlock::#unlock_marker>, UnlockError> {
                        #body
                        Ok(AsyncUnlocked::new(self))
                    }
                }
            }
        }
    }
}

/// The async guard: borrows the async handle while unlocked; `lock().await` locks, and a guard
/// dropped without it leaves the lock owed on the device (`Device::owe_write`), sent before
/// the next request: `Drop` cannot await.
fn async_guard(handle: &Ident, lock_marker: &Ident, lock_bound: &TokenStream) -> TokenStream {
    quote! {
        /// A drive unlocked by `U` over an async link: the setters of the scopes `U` opens, as
        /// on [`Unlocked`]. [`AsyncUnlocked::lock`] locks the drive; dropped without it, the
        /// guard leaves the lock owed and the handle's next request sends it first.
        #[derive(Debug)]
        pub struct AsyncUnlocked<'d, L: ::drivebus::asynch::AsyncLink, U>
        where
            #lock_bound
        {
            drive: &'d mut #handle<::drivebus::asynch::Async<L>>,
            locked: bool,
            unlock: ::core::marker::PhantomData<U>,
        }

        impl<'d, L: ::drivebus::asynch::AsyncLink, U> AsyncUnlocked<'d, L, U>
        where
            #lock_bound
        {
            fn new(drive: &'d mut #handle<::drivebus::asynch::Async<L>>) -> Self {
                Self { drive, locked: false, unlock: ::core::marker::PhantomData }
            }

            /// The drive, for reads (a locked drive answers reads too).
            pub fn drive(&mut self) -> &mut #handle<::drivebus::asynch::Async<L>> {
                self.drive
            }

            /// Writes the lock command and ends the unlock. A drive that refuses it as locked
            /// has ended the unlock already: that is success too. Dropped before the drive
            /// answered, it leaves the lock owed.
            pub async fn lock(mut self) -> Result<(), UnlockError> {
                let outcome = self.drive.device.write_raw::<params::#lock_marker>(params::#lock_marker::TRIGGER).await;
                self.locked = true;
                match outcome.map_err(UnlockError::from) {
                    Err(UnlockError::Locked { .. }) => Ok(()),
                    other => other,
                }
            }
        }

        impl<L: ::drivebus::asynch::AsyncLink, U> Drop for AsyncUnlocked<'_, L, U>
        where
            #lock_bound
        {
            fn drop(&mut self) {
                if !self.locked {
                    // Only a lock command longer than 16 bytes fails to be recorded; none is.
                    let _ = self.drive.device.owe_write::<params::#lock_marker>(params::#lock_marker::TRIGGER);
                }
            }
        }
    }
}

/// The guard: borrows the handle while unlocked; locks on `lock()` and on drop.
fn guard(handle: &Ident, lock_marker: &Ident, lock_bound: &TokenStream) -> TokenStream {
    quote! {
        /// A drive unlocked by `U` (a marker of [`unlock`]): its methods are the setters of the
        /// scopes `U` opens. Locks the drive when dropped (best effort; [`Unlocked::lock`]
        /// reports).
        #[derive(Debug)]
        pub struct Unlocked<'d, L: ::drivebus::Link, U>
        where
            #lock_bound
        {
            drive: &'d mut #handle<L>,
            locked: bool,
            unlock: ::core::marker::PhantomData<U>,
        }

        impl<'d, L: ::drivebus::Link, U> Unlocked<'d, L, U>
        where
            #lock_bound
        {
            fn new(drive: &'d mut #handle<L>) -> Self {
                Self { drive, locked: false, unlock: ::core::marker::PhantomData }
            }

            /// The drive, for reads (a locked drive answers reads too).
            pub fn drive(&mut self) -> &mut #handle<L> {
                self.drive
            }

            /// Writes the lock command and ends the unlock. A drive that refuses it as locked
            /// has ended the unlock already: that is success too.
            pub fn lock(mut self) -> Result<(), UnlockError> {
                self.locked = true;
                match self.write_lock() {
                    Err(UnlockError::Locked { .. }) => Ok(()),
                    other => other,
                }
            }

            fn write_lock(&mut self) -> Result<(), UnlockError> {
                Ok(self.drive.device.write_raw::<params::#lock_marker>(params::#lock_marker::TRIGGER)?)
            }
        }

        impl<L: ::drivebus::Link, U> Drop for Unlocked<'_, L, U>
        where
            #lock_bound
        {
            fn drop(&mut self) {
                if !self.locked {
                    // Best effort: a failure shows as `Locked` or a bus error at the next write.
                    let _ = self.write_lock();
                }
            }
        }
    }
}

/// The error type of unlocks and of writes under one: `drivebus`'s, named with this lock's
/// refusal code.
fn error_type() -> TokenStream {
    quote! {
        /// Why an unlock, or a write under one, failed: a write the drive refuses with
        /// [`LOCKED_EXCEPTION`], or the handle refuses as locked before sending, is
        /// [`UnlockError::Locked`](::drivebus::UnlockError::Locked).
        pub type UnlockError = ::drivebus::UnlockError<LOCKED_EXCEPTION>;
    }
}
