//! Unit newtypes: an engineering value carries its unit in its type, so volts cannot be passed
//! where rpm are expected.
//!
//! Each newtype wraps an `f64` in the unit its symbol names. [`ALL`] maps the symbols a description
//! may use to the newtype names; the generator reads it, so the two cannot drift apart.

/// A unit newtype.
pub trait Quantity: Copy + core::fmt::Debug + PartialEq + PartialOrd {
    /// Unit symbol as written in descriptions and printed after values.
    const SYMBOL: &'static str;
    /// Wraps a value in this unit.
    fn new(value: f64) -> Self;
    /// The value in this unit.
    fn get(self) -> f64;
}

macro_rules! units {
    ($($(#[$doc:meta])* $name:ident = $symbol:literal),* $(,)?) => {
        $(
            $(#[$doc])*
            #[derive(Debug, Clone, Copy, PartialEq, PartialOrd, Default)]
            pub struct $name(pub f64);

            impl Quantity for $name {
                const SYMBOL: &'static str = $symbol;
                #[inline]
                fn new(value: f64) -> Self {
                    Self(value)
                }
                #[inline]
                fn get(self) -> f64 {
                    self.0
                }
            }

            impl core::fmt::Display for $name {
                fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                    match f.precision() {
                        Some(p) => write!(f, "{:.*} {}", p, self.0, $symbol),
                        None => write!(f, "{} {}", self.0, $symbol),
                    }
                }
            }
        )*

        /// Every unit symbol a description may use, with the name of its newtype in this module.
        pub const ALL: &[(&str, &str)] = &[$(($symbol, stringify!($name))),*];
    };
}

units! {
    /// Volts.
    Volts = "V",
    /// Millivolts.
    Millivolts = "mV",
    /// Amperes.
    Amperes = "A",
    /// Amperes, root mean square.
    AmperesRms = "Arms",
    /// Milliamperes.
    Milliamperes = "mA",
    /// Revolutions per minute.
    Rpm = "rpm",
    /// Revolutions per minute per second (acceleration).
    RpmPerSecond = "rpm/s",
    /// Revolutions per second per second (acceleration, as Kinco's manual gives it).
    RpsPerSecond = "rps/s",
    /// Degrees Celsius.
    Celsius = "°C",
    /// Percent.
    Percent = "%",
    /// Per mille (CiA 402 expresses torque and current in thousandths of the rated value).
    PerMille = "‰",
    /// Seconds.
    Seconds = "s",
    /// Milliseconds.
    Milliseconds = "ms",
    /// Microseconds.
    Microseconds = "µs",
    /// Hertz.
    Hertz = "Hz",
    /// Watts.
    Watts = "W",
    /// Newton metres.
    NewtonMetres = "Nm",
    /// Encoder increments (pulses, counts).
    Increments = "inc",
    /// Revolutions.
    Revolutions = "rev",
    /// Metres per second.
    MetresPerSecond = "m/s",
    /// Millimetres.
    Millimetres = "mm",
    /// Ohms.
    Ohms = "Ω",
    /// Millihenries.
    Millihenries = "mH",
    /// Kilograms × square centimetres (rotor inertia).
    KilogramSquareCentimetres = "kg·cm²",
    /// Bits per second.
    BitsPerSecond = "bit/s",
}

/// The newtype name for a unit symbol, if the symbol is known.
pub fn type_name(symbol: &str) -> Option<&'static str> {
    ALL.iter()
        .find(|(s, _)| *s == symbol)
        .map(|(_, name)| *name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn symbols_are_unique_and_resolve() {
        for (i, (symbol, name)) in ALL.iter().enumerate() {
            assert!(
                ALL[i + 1..].iter().all(|(s, _)| s != symbol),
                "{symbol} twice"
            );
            assert_eq!(type_name(symbol), Some(*name));
        }
        assert_eq!(type_name("furlong"), None);
    }

    #[test]
    fn display_appends_the_symbol() {
        extern crate std;
        use std::format;
        assert_eq!(format!("{:.2}", Volts(49.5)), "49.50 V");
        assert_eq!(format!("{}", Rpm(-3000.0)), "-3000 rpm");
    }
}
