//! What starts a capture, parsed from the text a user writes (`velocity_actual_value>1000`,
//! `statusword<0x27`, `emcy`, `nmt`) and checked against each decoded event.

use core::fmt;
use std::borrow::ToOwned;
use std::collections::HashMap;
use std::format;
use std::string::String;

/// An event of a decoded bus, as triggers see it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Event<'a> {
    /// A value of `parameter` of `node`, in engineering units.
    Sample {
        /// The node (CANopen node id, Modbus unit) it came from.
        node: u8,
        /// The parameter's name.
        parameter: &'a str,
        /// Its value.
        value: f64,
    },
    /// An EMCY of `node` with its error code.
    Emcy {
        /// The node that sent it.
        node: u8,
        /// Its error code (0000h: error reset).
        code: u16,
    },
    /// `node` reported NMT state `state` (a heartbeat; 0 is its boot-up).
    State {
        /// The node.
        node: u8,
        /// The state byte of its heartbeat.
        state: u8,
    },
    /// An NMT command from the master (`node` `None`: to all nodes).
    NmtCommand {
        /// The addressed node.
        node: Option<u8>,
    },
}

/// Which way a level is crossed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Crossing {
    /// From at or below the level to above it (`name>level`).
    Rising,
    /// From at or above the level to below it (`name<level`).
    Falling,
}

/// What starts a capture.
#[derive(Debug, Clone, PartialEq)]
pub enum Trigger {
    /// A parameter's value crossing a level, on any node.
    Crosses {
        /// The parameter's name.
        parameter: String,
        /// Which way.
        crossing: Crossing,
        /// The level, in the parameter's engineering unit.
        level: f64,
    },
    /// Any EMCY.
    Emcy,
    /// An NMT state change: a command from the master, or a node's heartbeat state other than
    /// its last one (a boot-up among them).
    Nmt,
}

/// Why a trigger text is refused.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TriggerError(String);

impl fmt::Display for TriggerError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}; write NAME>LEVEL, NAME<LEVEL (a number in the parameter's unit: 1000, -2.5, 0x27), emcy or nmt",
            self.0
        )
    }
}

impl std::error::Error for TriggerError {}

impl std::str::FromStr for Trigger {
    type Err = TriggerError;

    fn from_str(text: &str) -> Result<Self, TriggerError> {
        let text = text.trim();
        match text {
            "emcy" => return Ok(Trigger::Emcy),
            "nmt" => return Ok(Trigger::Nmt),
            _ => {}
        }
        let (at, crossing) = match (text.find('>'), text.find('<')) {
            (Some(at), None) => (at, Crossing::Rising),
            (None, Some(at)) => (at, Crossing::Falling),
            (None, None) => return Err(TriggerError(format!("`{text}` has no `>` or `<`"))),
            (Some(_), Some(_)) => {
                return Err(TriggerError(format!("`{text}` has both `>` and `<`")))
            }
        };
        let (parameter, level) = (text[..at].trim(), text[at + 1..].trim());
        let named = !parameter.is_empty()
            && parameter
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_');
        if !named {
            return Err(TriggerError(format!(
                "`{parameter}` is not a parameter name"
            )));
        }
        let level =
            number(level).ok_or_else(|| TriggerError(format!("`{level}` is not a number")))?;
        Ok(Trigger::Crosses {
            parameter: parameter.to_owned(),
            crossing,
            level,
        })
    }
}

/// A decimal or `0x` hexadecimal number, finite.
fn number(text: &str) -> Option<f64> {
    let (negative, digits) = match text.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, text),
    };
    let magnitude = match digits
        .strip_prefix("0x")
        .or_else(|| digits.strip_prefix("0X"))
    {
        Some(hex) => u64::from_str_radix(hex, 16).ok()? as f64,
        None if digits.starts_with(|c: char| c.is_ascii_digit() || c == '.') => {
            digits.parse::<f64>().ok()?
        }
        None => return None,
    };
    let value = if negative { -magnitude } else { magnitude };
    value.is_finite().then_some(value)
}

/// A trigger with what it remembers of the bus: the last value of its parameter on each node,
/// the last heartbeat state of each node.
#[derive(Debug, Clone)]
pub struct Armed {
    trigger: Trigger,
    last_value: HashMap<u8, f64>,
    last_state: HashMap<u8, u8>,
}

impl Trigger {
    /// The trigger, ready to watch events.
    pub fn arm(self) -> Armed {
        Armed {
            trigger: self,
            last_value: HashMap::new(),
            last_state: HashMap::new(),
        }
    }
}

impl Armed {
    /// Whether `event` fires the trigger. A level is crossed between two values of one node; the
    /// first value of a node only sets where it starts.
    pub fn fires(&mut self, event: &Event<'_>) -> bool {
        match (&self.trigger, *event) {
            (
                Trigger::Crosses {
                    parameter,
                    crossing,
                    level,
                },
                Event::Sample {
                    node,
                    parameter: name,
                    value,
                },
            ) if name == parameter => {
                let before = self.last_value.insert(node, value);
                before.is_some_and(|before| match crossing {
                    Crossing::Rising => before <= *level && value > *level,
                    Crossing::Falling => before >= *level && value < *level,
                })
            }
            (Trigger::Emcy, Event::Emcy { .. }) => true,
            (Trigger::Nmt, Event::NmtCommand { .. }) => true,
            (Trigger::Nmt, Event::State { node, state }) => {
                self.last_state.insert(node, state) != Some(state)
            }
            _ => false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::string::ToString;

    fn sample(node: u8, value: f64) -> Event<'static> {
        Event::Sample {
            node,
            parameter: "speed",
            value,
        }
    }

    #[test]
    fn texts_parse_or_say_why_not() {
        assert_eq!(
            "speed > 1000".parse(),
            Ok(Trigger::Crosses {
                parameter: "speed".into(),
                crossing: Crossing::Rising,
                level: 1000.0
            })
        );
        assert_eq!(
            "statusword<0x27".parse::<Trigger>().map(|t| match t {
                Trigger::Crosses { level, .. } => level,
                _ => f64::NAN,
            }),
            Ok(39.0)
        );
        assert_eq!("emcy".parse(), Ok(Trigger::Emcy));
        assert_eq!("nmt".parse(), Ok(Trigger::Nmt));
        for bad in [
            "speed",
            "a>b<c",
            ">5",
            "speed>",
            "speed>fast",
            "speed>1e999",
            "sp eed>1",
            "speed>-",
        ] {
            let error = bad.parse::<Trigger>().unwrap_err().to_string();
            assert!(error.contains("write NAME>LEVEL"), "{bad}: {error}");
        }
    }

    #[test]
    fn a_level_fires_when_crossed_per_node_and_not_at_the_first_value() {
        let mut armed = "speed>100".parse::<Trigger>().unwrap().arm();
        assert!(
            !armed.fires(&sample(1, 500.0)),
            "the first value only sets where it starts"
        );
        assert!(!armed.fires(&sample(1, 50.0)));
        assert!(!armed.fires(&sample(2, 50.0)));
        assert!(armed.fires(&sample(1, 100.5)));
        assert!(!armed.fires(&sample(1, 200.0)), "already above");
        assert!(armed.fires(&sample(2, 101.0)), "node 2 crosses on its own");
        let mut falling = "speed<0".parse::<Trigger>().unwrap().arm();
        assert!(!falling.fires(&sample(1, 0.0)));
        assert!(falling.fires(&sample(1, -1.0)));
    }

    #[test]
    fn nmt_fires_on_commands_and_changed_states_only() {
        let mut armed = Trigger::Nmt.arm();
        assert!(armed.fires(&Event::State { node: 3, state: 0 }), "boot-up");
        assert!(armed.fires(&Event::State {
            node: 3,
            state: 0x7F
        }));
        assert!(!armed.fires(&Event::State {
            node: 3,
            state: 0x7F
        }));
        assert!(armed.fires(&Event::NmtCommand { node: None }));
        assert!(!armed.fires(&Event::Emcy {
            node: 3,
            code: 0x2310
        }));
        assert!(Trigger::Emcy.arm().fires(&Event::Emcy {
            node: 3,
            code: 0x2310
        }));
    }
}
