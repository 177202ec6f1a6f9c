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
            .filter_map(|(id, p)| p.command.as_ref().map(|c| (id, c.kind, c.value)))
            .collect();
        (!commands.is_empty()).then_some(Self { commands })
    }

    fn command(&self, id: ParamId) -> Option<(CommandKind, Option<i64>)> {
        self.commands
            .iter()
            .find(|(c, _, _)| *c == id)
            .map(|&(_, kind, value)| (kind, value))
    }
}

impl Behaviour for Commands {
    /// A command with a trigger value (e.g. CiA 301 "save") refuses any other value.
    fn accept(&self, store: &Store, id: ParamId, bytes: &[u8]) -> Result<(), Refusal> {
        match self.command(id) {
            Some((_, Some(value))) => {
                let written = crate::raw::to_int(store.parameter(id).data_type, bytes);
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
        let command = self.command(id);
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
