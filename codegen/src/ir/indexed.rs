//! A member repeated over a run of sub-indices (`subindex = "1..=8"`), described once: ONE
//! parameter with its first and last sub-index. The generated crate has one marker and one
//! indexed, range-checked accessor for it (`drive.<name>(n)`).
//!
//! Where one object is the unit — the object dictionary of the simulator and of the EDS export,
//! addresses that must not overlap, `drivegen read <name>_<sub-index>`, coverage against a
//! manual's table — the loader also lists each member as a parameter of its own (named
//! `<name>_<sub-index>`, in `Device::parameters`); the Rust emitter reaches them through the run.

use serde::Serialize;

use crate::diagnostic::Span;
use crate::ir::Parameter;

/// A run of sub-indices of one object described by a single member.
#[derive(Debug, Clone, Serialize)]
pub struct IndexedParameter {
    /// Name of the run: the indexed accessor's name.
    pub name: String,
    /// Documentation of the member.
    pub doc: Option<String>,
    /// Object index.
    pub index: u16,
    /// First sub-index of the run.
    pub first: u8,
    /// Last sub-index of the run (inclusive).
    pub last: u8,
    /// The member parameters, one per sub-index from `first` to `last`.
    pub members: Vec<String>,
    /// The run as one parameter, named as the run and placed at its first sub-index.
    pub parameter: Parameter,
    /// Span of the member's name.
    #[serde(skip)]
    pub span: Span,
}

impl IndexedParameter {
    /// The name of the parameter the run expands to at `subindex`.
    pub fn member_name(name: &str, subindex: u8) -> String {
        format!("{name}_{subindex}")
    }

    /// The name, in snake case, of the run's marker type in the generated `params`
    /// (`sls_velocity_limit_run`, `params::SlsVelocityLimitRun`): the run's own name is its
    /// accessor type's in `indexed`, and one name for both would make every compiler message
    /// about either spell out its path.
    pub fn marker_name(&self) -> String {
        format!("{}_run", self.name)
    }
}
