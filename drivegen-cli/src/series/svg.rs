//! A plot as an SVG document: one panel per series stacked on a shared time axis, each with its
//! own value axis labelled with the series' unit (an enumeration's axis with its value names).
//!
//! The data of a panel is drawn in a nested `<svg class="plot">` whose viewBox is in seconds
//! across and the panel's height split in [`LEVELS`] down: the HTML page zooms in time by
//! changing only that viewBox (the line keeps its width through `non-scaling-stroke`).
//! Every number is written with fixed decimals, so the same samples give the same bytes.

use std::fmt::Write;

use super::axis::{self, Span};
use super::decimate::decimate;
use super::Series;

/// The document's width in pixels.
pub const WIDTH: f64 = 900.0;
/// Left of the plot areas: room for value labels and the unit.
pub const LEFT: f64 = 150.0;
/// Right margin.
const RIGHT: f64 = 20.0;
/// A plot area's height.
const PANEL: f64 = 140.0;
/// Room above a plot area for its title.
const ABOVE: f64 = 30.0;
/// Room below a plot area for its time labels.
const BELOW: f64 = 26.0;
/// The vertical extent of a panel's data coordinates.
pub const LEVELS: f64 = 1000.0;
/// Series colours, in turn.
const COLOURS: [&str; 6] = [
    "#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf",
];
/// At most this many value names label an enumeration's axis; more and it gets numbers.
const MOST_NAMES: usize = 12;

/// The SVG document of `series` (a panel saying so for a series without samples).
pub fn render(series: &[Series]) -> String {
    let time = Span::of(series.iter().flat_map(|s| s.samples.iter().map(|p| p.0)));
    let height = series.len().max(1) as f64 * (ABOVE + PANEL + BELOW) + 24.0;
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" class="drivegen-plot" width="{WIDTH:.0}" height="{height:.0}" viewBox="0 0 {WIDTH:.0} {height:.0}" data-t0="{}" data-t1="{}" data-left="{LEFT:.0}" data-width="{:.0}">"#,
        coordinate(time.low),
        coordinate(time.high),
        plot_width()
    );
    out.push_str(STYLE);
    for (i, s) in series.iter().enumerate() {
        let top = i as f64 * (ABOVE + PANEL + BELOW) + ABOVE;
        panel(&mut out, s, top, time, COLOURS[i % COLOURS.len()]);
    }
    let _ = writeln!(
        out,
        r#"<text class="axis-title" x="{:.0}" y="{:.0}" text-anchor="middle">time (s)</text>"#,
        LEFT + plot_width() / 2.0,
        height - 6.0
    );
    out.push_str("</svg>\n");
    out
}

const STYLE: &str = "<style>\
.drivegen-plot{font-family:sans-serif;font-size:12px;background:#fff}\
.drivegen-plot .frame{fill:none;stroke:#888}\
.drivegen-plot .grid{stroke:#e4e4e4}\
.drivegen-plot .title{font-weight:bold}\
.drivegen-plot .series{fill:none;stroke-width:1.5;stroke-linecap:round;stroke-linejoin:round}\
.drivegen-plot .empty{fill:#888}\
</style>\n";

fn plot_width() -> f64 {
    WIDTH - LEFT - RIGHT
}

/// One series' panel: title, frame, value axis, time labels and the line.
fn panel(out: &mut String, series: &Series, top: f64, time: Span, colour: &str) {
    let name = escape(&series.parameter);
    let _ = writeln!(out, r#"<g class="panel" data-parameter="{name}">"#);
    let _ = writeln!(
        out,
        r#"<text class="title" x="{LEFT:.0}" y="{:.0}">{}</text>"#,
        top - 10.0,
        escape(&series.title())
    );
    let values = Span::of(series.samples.iter().map(|p| p.1)).padded(0.05);
    value_axis(out, series, top, values);
    time_labels(out, top, time);
    let _ = writeln!(
        out,
        r#"<rect class="frame" x="{LEFT:.0}" y="{top:.0}" width="{:.0}" height="{PANEL:.0}"/>"#,
        plot_width()
    );
    if series.samples.is_empty() {
        let _ = writeln!(
            out,
            r#"<text class="empty" x="{:.0}" y="{:.0}" text-anchor="middle">no numeric samples</text>"#,
            LEFT + plot_width() / 2.0,
            top + PANEL / 2.0
        );
    } else {
        let _ = writeln!(
            out,
            r#"<svg class="plot" x="{LEFT:.0}" y="{top:.0}" width="{:.0}" height="{PANEL:.0}" viewBox="{} 0 {} {LEVELS:.0}" preserveAspectRatio="none">"#,
            plot_width(),
            coordinate(time.low),
            coordinate(time.width()),
        );
        let _ = writeln!(
            out,
            r#"<path class="series" data-parameter="{name}" stroke="{colour}" vector-effect="non-scaling-stroke" d="{}"/>"#,
            path(series, time, values)
        );
        out.push_str("</svg>\n");
    }
    out.push_str("</g>\n");
}

/// Grid lines and labels of the value axis, and the unit written up its side.
fn value_axis(out: &mut String, series: &Series, top: f64, values: Span) {
    let y = |v: f64| top + PANEL * (1.0 - values.fraction(v));
    for (value, text) in value_ticks(series, values) {
        let at = y(value);
        let _ = writeln!(
            out,
            r#"<line class="grid" x1="{LEFT:.0}" x2="{:.0}" y1="{at:.2}" y2="{at:.2}"/><text class="ytick" x="{:.0}" y="{:.2}" text-anchor="end">{}</text>"#,
            LEFT + plot_width(),
            LEFT - 6.0,
            at + 4.0,
            escape(&text)
        );
    }
    if let Some(unit) = &series.unit {
        let (x, middle) = (14.0, top + PANEL / 2.0);
        let _ = writeln!(
            out,
            r#"<text class="unit" x="{x:.0}" y="{middle:.0}" text-anchor="middle" transform="rotate(-90 {x:.0} {middle:.0})">{}</text>"#,
            escape(unit)
        );
    }
}

/// The value axis's ticks: an enumeration's values present, by name, or round numbers.
fn value_ticks(series: &Series, values: Span) -> Vec<(f64, String)> {
    let mut present: Vec<i64> = series.samples.iter().map(|p| p.1 as i64).collect();
    present.sort_unstable();
    present.dedup();
    if !series.names.is_empty() && present.len() <= MOST_NAMES {
        return present
            .into_iter()
            .map(|raw| {
                let name = series.names.get(&raw).cloned();
                (raw as f64, name.unwrap_or_else(|| raw.to_string()))
            })
            .collect();
    }
    let (ticks, decimals) = axis::ticks(values, 4);
    ticks
        .into_iter()
        .map(|v| (v, axis::label(v, decimals)))
        .collect()
}

/// The time labels under a panel (the HTML page redraws them when it zooms).
fn time_labels(out: &mut String, top: f64, time: Span) {
    let y = top + PANEL + 16.0;
    let _ = write!(out, r#"<g class="xticks" data-y="{y:.0}">"#);
    let (ticks, decimals) = axis::ticks(time, 8);
    for t in ticks {
        let _ = write!(
            out,
            r#"<text x="{:.2}" y="{y:.0}" text-anchor="middle">{}</text>"#,
            LEFT + plot_width() * time.fraction(t),
            axis::label(t, decimals)
        );
    }
    out.push_str("</g>\n");
}

/// The line through the samples in data coordinates (seconds across, [`LEVELS`] down): straight
/// between numbers, a step for an enumeration (it holds its value until the next sample).
fn path(series: &Series, time: Span, values: Span) -> String {
    let level = |v: f64| axis::label(LEVELS * (1.0 - values.fraction(v)), 2);
    let step = !series.names.is_empty();
    let mut d = String::new();
    let points = decimate(&series.samples, time.low, time.high);
    for (i, (t, v)) in points.iter().enumerate() {
        let (t, v) = (coordinate(*t), level(*v));
        match (i, step) {
            (0, _) => {
                let _ = write!(d, "M{t} {v}");
            }
            (_, true) => {
                let _ = write!(d, " H{t} V{v}");
            }
            (_, false) => {
                let _ = write!(d, " L{t} {v}");
            }
        }
    }
    if series.samples.len() == 1 {
        // A single sample: a zero-length segment, which the round line cap draws as a dot.
        d.push_str(" h0");
    }
    d
}

/// A data coordinate with fixed decimals (microseconds for time) and no `-0`.
fn coordinate(value: f64) -> String {
    axis::label(value, 6)
}

/// Text as XML character data or an attribute value.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::series::Recording;
    use proptest::prelude::*;

    fn recording(samples: &[(f64, f64)]) -> Recording {
        let mut recording = Recording::default();
        for (t, v) in samples {
            recording.push(crate::series::kinco(), "p", *t, *v);
        }
        recording
    }

    #[test]
    fn a_series_without_numbers_still_has_its_panel() {
        let svg = render(&[Series::unknown("name")]);
        assert!(svg.contains(r#"<g class="panel" data-parameter="name">"#));
        assert!(svg.contains("no numeric samples"));
        let nan = recording(&[(0.0, f64::NAN), (1.0, f64::INFINITY)]);
        assert!(render(nan.series()).contains("no numeric samples"));
    }

    #[test]
    fn one_value_near_the_limit_of_f64_gives_finite_ticks() {
        // Found by the property below: widening a flat line at -1.78e308 went past -f64::MAX.
        for value in [-1.775_761_216_070_330_2e308, f64::MAX, f64::MIN] {
            let svg = render(recording(&[(0.0, value)]).series());
            assert!(!svg.contains("inf") && !svg.contains("NaN"), "{svg}");
        }
    }

    #[test]
    fn times_too_far_apart_for_f64_give_finite_coordinates() {
        // Found by the property below: 1.66e308 s after -1.53e308 s is beyond f64 (a path to
        // `inf`); such a sample is dropped like a NaN reading.
        let samples = [
            (-1.525_309_727_150_901e308, 0.0),
            (1.659_830_503_092_046_8e308, 0.0),
        ];
        let svg = render(recording(&samples).series());
        assert!(!svg.contains("inf") && !svg.contains("NaN"), "{svg}");
    }

    proptest! {
        /// Any values, the limits of `f64` and NaN among them: a document with numbers only.
        #[test]
        fn any_samples_give_a_document_without_nan_or_inf(
            samples in proptest::collection::vec((any::<f64>(), any::<f64>()), 0..20)
        ) {
            let svg = render(recording(&samples).series());
            prop_assert!(svg.ends_with("</svg>\n"));
            prop_assert!(!svg.contains("NaN") && !svg.contains("inf"), "{}", svg);
        }
    }
}
