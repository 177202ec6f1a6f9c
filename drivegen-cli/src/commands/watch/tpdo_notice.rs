//! What a TPDO set-up ([`TpdoSetup`](super::tpdo_setup::TpdoSetup)) tells while it works: a
//! TPDO mapped, a TPDO whose identifier clashes with another node's, a TPDO not put back. The
//! set-up only says it; each command shows it its own way (`watch` on standard error, the
//! gateway in its `tracing` log), so both show every notice.

use std::fmt;

use crate::error::CliError;

/// One thing a TPDO set-up tells.
#[derive(Debug)]
pub enum Notice {
    /// Node `node`'s TPDO `tpdo` was written for the reader (and is put back at the end).
    Mapped {
        /// The node.
        node: u8,
        /// The TPDO's number.
        tpdo: u16,
    },
    /// Node `node`'s TPDO `tpdo`, left as it is, goes out on `can_id`, which another node's
    /// watched TPDO uses: their values may mix.
    Clash {
        /// The node.
        node: u8,
        /// The TPDO's number.
        tpdo: u16,
        /// The identifier both use.
        can_id: u16,
    },
    /// A TPDO or NMT state could not be put back when the reader ended.
    NotRestored(CliError),
}

/// How bad a [`Notice`] is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Severity {
    /// Done as asked.
    Info,
    /// Works, but the values may be wrong.
    Warning,
    /// Something was left changed on a drive.
    Error,
}

impl Notice {
    /// How bad it is.
    pub fn severity(&self) -> Severity {
        match self {
            Notice::Mapped { .. } => Severity::Info,
            Notice::Clash { .. } => Severity::Warning,
            Notice::NotRestored(_) => Severity::Error,
        }
    }
}

impl fmt::Display for Notice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Notice::Mapped { node, tpdo } => write!(
                f,
                "node {node}: TPDO {tpdo} mapped for the watch (restored at the end)"
            ),
            Notice::Clash { node, tpdo, can_id } => write!(
                f,
                "node {node}: its TPDO {tpdo} also goes out on CAN id {can_id:03X}h, which \
                 another node's watched TPDO uses: their values may mix (switch it off, or give \
                 it an identifier of its own)"
            ),
            Notice::NotRestored(error) => write!(f, "{error}"),
        }
    }
}

/// How a command shows the notices of its TPDO set-up.
pub type Report = fn(&Notice);

/// `watch`'s way: on standard error, a warning or error saying so.
pub fn on_stderr(notice: &Notice) {
    match notice.severity() {
        Severity::Info => eprintln!("{notice}"),
        Severity::Warning => eprintln!("warning: {notice}"),
        Severity::Error => eprintln!("error: {notice}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn watch_prints_what_it_printed_before_the_notices() {
        let mapped = Notice::Mapped { node: 17, tpdo: 2 };
        assert_eq!(
            mapped.to_string(),
            "node 17: TPDO 2 mapped for the watch (restored at the end)"
        );
        let clash = Notice::Clash {
            node: 17,
            tpdo: 3,
            can_id: 0x390,
        };
        assert!(clash
            .to_string()
            .starts_with("node 17: its TPDO 3 also goes out on CAN id 390h, which another"));
        assert_eq!(clash.severity(), Severity::Warning);
        let lost = Notice::NotRestored(CliError::Usage("x".into()));
        assert_eq!(lost.severity(), Severity::Error);
    }
}
