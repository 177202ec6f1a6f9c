//! Command registers (`command = { kind = ... }`): store to non-volatile memory, restore factory
//! parameters, reset.

use drivegen::ir::CommandKind;

use super::{Behaviour, Shared};
use crate::refusal::Refusal;
use crate::store::{ParamId, Store};

/// The command registers of a description.
#[derive(Debug)]
pub struct Commands {
    commands: Vec<(ParamId, CommandKind, Option<i64>)>,
}

impl Commands {
    /// Present when the description has at least one command register.
    pub fn detect(store: &Store) -> Option<Self> {
        let commands: Vec<_> = store
            .device()
            .parameters
            .iter()
            .enumerate()
            .flat_map(|(id, p)| {
                p.command
                    .iter()
                    .flat_map(move |c| c.values().map(move |v| (id, v.kind, v.value)))
            })
            .collect();
        (!commands.is_empty()).then_some(Self { commands })
    }

    /// The command of register `id` that `written` (its raw value, if known) triggers: the value's
    /// own where the register takes several, else the register's one command.
    fn command(&self, id: ParamId, written: Option<i128>) -> Option<(CommandKind, Option<i64>)> {
        let mut of_register = self.commands.iter().filter(|(c, _, _)| *c == id);
        let first = of_register.clone().next();
        of_register
            .find(|(_, _, value)| value.is_some_and(|v| Some(i128::from(v)) == written))
            .or(first)
            .map(|&(_, kind, value)| (kind, value))
    }
}

impl Behaviour for Commands {
    /// A command with a trigger value (e.g. CiA 301 "save") refuses any other value.
    fn accept(&self, store: &Store, id: ParamId, bytes: &[u8]) -> Result<(), Refusal> {
        let written = crate::raw::to_int(store.parameter(id).data_type, bytes);
        match self.command(id, written) {
            Some((_, Some(value))) => {
                if written == Some(i128::from(value)) {
                    Ok(())
                } else {
                    Err(Refusal::InvalidValue)
                }
            }
            _ => Ok(()),
        }
    }

    /// Runs the command; the register itself reads back its described value afterwards (a
    /// trigger is not a setting, e.g. CiA 301 1010h reads its storage capabilities).
    fn written(&mut self, store: &mut Store, shared: &mut Shared, id: ParamId) {
        let command = self.command(id, store.int(id));
        if command.is_some() {
            store.reset_to_factory(id);
        }
        match command {
            Some((CommandKind::Store, _)) => store.store(),
            Some((CommandKind::RestoreFactory, _)) => store.restore_factory(),
            Some((CommandKind::Reset, _)) => shared.reset_requested = true,
            Some((CommandKind::Action, _)) | None => {}
        }
    }
}
