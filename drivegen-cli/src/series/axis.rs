//! Axis ranges and tick marks: round numbers a person reads at a glance, formatted the same way
//! every time (a plot is snapshot-tested, so the same samples must give the same text).

/// A closed range `[low, high]` with `low < high`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Span {
    /// The lower end.
    pub low: f64,
    /// The upper end.
    pub high: f64,
}

impl Span {
    /// The range the values cover, widened when they are all one value (a flat line sits in
    /// the middle of its panel) and `[0, 1]` when there are none.
    pub fn of(values: impl IntoIterator<Item = f64>) -> Self {
        let (low, high) = values
            .into_iter()
            .filter(|v| v.is_finite())
            .fold(None, |range: Option<(f64, f64)>, v| match range {
                None => Some((v, v)),
                Some((low, high)) => Some((low.min(v), high.max(v))),
            })
            .unwrap_or((0.0, 1.0));
        if low < high {
            return Self { low, high };
        }
        let half = if low == 0.0 { 1.0 } else { low.abs() / 10.0 };
        Self::within_f64(low - half, high + half)
    }

    /// The range widened by `fraction` of its width at each end: a line at its extreme stays
    /// clear of the panel's frame.
    pub fn padded(self, fraction: f64) -> Self {
        let pad = self.width() * fraction;
        Self::within_f64(self.low - pad, self.high + pad)
    }

    /// `[low, high]` with ends that widening pushed past the limits of `f64` (values near
    /// them) brought back to the largest finite values.
    fn within_f64(low: f64, high: f64) -> Self {
        Self {
            low: low.max(f64::MIN),
            high: high.min(f64::MAX),
        }
    }

    /// `high - low`.
    pub fn width(self) -> f64 {
        self.high - self.low
    }

    /// Where `value` sits in the range, 0 at `low` and 1 at `high`.
    /// A range too wide for `f64` (values near its limits) puts everything in the middle.
    pub fn fraction(self, value: f64) -> f64 {
        let fraction = (value - self.low) / self.width();
        if fraction.is_finite() {
            fraction
        } else {
            0.5
        }
    }
}

/// About `wanted` round tick values inside `span` (steps of 1, 2 or 5 times a power of ten),
/// with the decimals that step needs.
pub fn ticks(span: Span, wanted: usize) -> (Vec<f64>, usize) {
    let raw = span.width() / wanted.max(1) as f64;
    if !raw.is_finite() || raw <= 0.0 {
        // Too wide (or narrow) for round steps: the ends alone.
        return (vec![span.low, span.high], 0);
    }
    let power = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * power)
        // A step equal to `raw` up to rounding is the step wanted, not one too small.
        .find(|s| *s >= raw * (1.0 - 1e-9))
        .unwrap_or(10.0 * power);
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    // Ends within rounding of a tick keep it: 0.01 / 0.002 may come out as 4.999999.
    let first = (span.low / step - 1e-9).ceil() as i64;
    let last = (span.high / step + 1e-9).floor() as i64;
    if last.saturating_sub(first) > 10 * wanted as i64 {
        // Rounding at the limits of `f64` made a step that does not divide the span sensibly.
        return (vec![span.low, span.high], decimals);
    }
    let values = (first..=last).map(|i| i as f64 * step).collect();
    (values, decimals)
}

/// A tick label: fixed decimals, and no `-0`.
pub fn label(value: f64, decimals: usize) -> String {
    let text = format!("{value:.decimals$}");
    match text.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_owned(),
        _ => text,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_round_and_inside_the_span() {
        let (values, decimals) = ticks(
            Span {
                low: 0.0,
                high: 0.01,
            },
            5,
        );
        assert_eq!(decimals, 3);
        let labels: Vec<String> = values.iter().map(|v| label(*v, decimals)).collect();
        assert_eq!(
            labels,
            ["0.000", "0.002", "0.004", "0.006", "0.008", "0.010"]
        );
        let (values, decimals) = ticks(
            Span {
                low: -1500.0,
                high: 1500.0,
            },
            4,
        );
        assert_eq!(decimals, 0);
        assert_eq!(values, [-1000.0, 0.0, 1000.0]);
    }

    #[test]
    fn a_flat_or_empty_series_still_has_a_range() {
        assert_eq!(
            Span::of([5.0, 5.0]),
            Span {
                low: 4.5,
                high: 5.5
            }
        );
        assert_eq!(
            Span::of([0.0]),
            Span {
                low: -1.0,
                high: 1.0
            }
        );
        assert_eq!(
            Span::of([f64::NAN]),
            Span {
                low: 0.0,
                high: 1.0
            }
        );
    }

    #[test]
    fn no_negative_zero() {
        assert_eq!(label(-0.0001, 2), "0.00");
        assert_eq!(label(-1.5, 1), "-1.5");
    }
}
