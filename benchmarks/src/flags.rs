//! The command lines of the benchmark programs: `--name NUMBER` pairs, each read once with its
//! default; an unknown flag is refused, since a typo would otherwise run the default silently.

/// The `--name value` pairs of a command line not read yet.
#[derive(Debug)]
pub struct Flags {
    pairs: Vec<(String, String)>,
}

impl Flags {
    /// The process's arguments.
    pub fn from_env() -> Result<Self, String> {
        Self::parse(std::env::args().skip(1))
    }

    /// `args` as `--name value` pairs.
    pub fn parse(args: impl IntoIterator<Item = String>) -> Result<Self, String> {
        let mut pairs = Vec::new();
        let mut args = args.into_iter();
        while let Some(flag) = args.next() {
            if !flag.starts_with("--") {
                return Err(format!("expected a --flag, found {flag}"));
            }
            let value = args.next().ok_or_else(|| format!("{flag} needs a value"))?;
            pairs.push((flag, value));
        }
        Ok(Self { pairs })
    }

    /// The number after `flag`, or `default` without one.
    pub fn number(&mut self, flag: &str, default: u64) -> Result<u64, String> {
        let Some(at) = self.pairs.iter().position(|(name, _)| name == flag) else {
            return Ok(default);
        };
        let (_, value) = self.pairs.remove(at);
        value
            .parse()
            .map_err(|_| format!("{flag} needs a number, not {value:?}"))
    }

    /// The text after `flag`, or `None` without one.
    pub fn text(&mut self, flag: &str) -> Option<String> {
        let at = self.pairs.iter().position(|(name, _)| name == flag)?;
        Some(self.pairs.remove(at).1)
    }

    /// Refuses the flags no [`Flags::number`] or [`Flags::text`] call read (unknown, or given
    /// twice).
    pub fn finish(self) -> Result<(), String> {
        match self.pairs.first() {
            None => Ok(()),
            Some((flag, _)) => Err(format!("unknown or repeated argument {flag}")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Flags;

    fn flags(line: &str) -> Result<Flags, String> {
        Flags::parse(line.split_whitespace().map(str::to_owned))
    }

    #[test]
    fn numbers_are_read_with_their_defaults() {
        let mut f = flags("--seconds 60").unwrap();
        assert_eq!(f.number("--seconds", 600), Ok(60));
        assert_eq!(f.number("--drives", 1000), Ok(1000));
        assert_eq!(f.finish(), Ok(()));
    }

    #[test]
    fn typos_missing_values_and_words_are_refused() {
        let f = flags("--second 60").unwrap();
        assert_eq!(
            f.finish(),
            Err("unknown or repeated argument --second".into())
        );
        assert_eq!(flags("--seconds").unwrap_err(), "--seconds needs a value");
        assert_eq!(flags("60").unwrap_err(), "expected a --flag, found 60");
        let mut f = flags("--seconds ten").unwrap();
        assert_eq!(
            f.number("--seconds", 1),
            Err("--seconds needs a number, not \"ten\"".into())
        );
    }

    #[test]
    fn texts_are_read_once() {
        let mut f = flags("--can socketcan:vcan0").unwrap();
        assert_eq!(f.text("--axis"), None);
        assert_eq!(f.text("--can").as_deref(), Some("socketcan:vcan0"));
        assert_eq!(f.text("--can"), None);
        assert_eq!(f.finish(), Ok(()));
    }

    #[test]
    fn a_flag_given_twice_is_refused() {
        let mut f = flags("--seconds 1 --seconds 2").unwrap();
        assert_eq!(f.number("--seconds", 0), Ok(1));
        assert!(f.finish().is_err());
    }
}
