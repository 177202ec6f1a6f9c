//! One frame of the scope: a header line (device, time, polls, running or paused, the keys) and
//! a chart per parameter, titled with its latest value and unit, its value axis in that unit.

use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Color, Modifier, Style};
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span as Text};
use ratatui::widgets::{Axis, Block, Chart, Dataset, GraphType, Paragraph};
use ratatui::Frame;

use super::{Scope, WINDOW_S};
use crate::series::axis::{self, Span};
use crate::series::Series;

/// Series colours, in turn.
const COLOURS: [Color; 6] = [
    Color::Cyan,
    Color::Yellow,
    Color::Green,
    Color::Magenta,
    Color::LightRed,
    Color::LightBlue,
];

/// Draws the whole scope.
pub fn scope(frame: &mut Frame<'_>, scope: &Scope) {
    let series = scope.series();
    let mut rows = vec![Constraint::Length(1)];
    rows.extend(series.iter().map(|_| Constraint::Fill(1)));
    let areas = Layout::vertical(rows).split(frame.area());
    frame.render_widget(header(scope), areas[0]);
    for (i, (series, latest)) in series.iter().zip(&scope.latest).enumerate() {
        chart(
            frame,
            areas[i + 1],
            scope,
            series,
            latest,
            COLOURS[i % COLOURS.len()],
        );
    }
}

/// The header line: what is watched, since when, and the keys.
fn header(scope: &Scope) -> Paragraph<'static> {
    let state = if scope.paused {
        Text::styled(" PAUSED ", Style::new().fg(Color::Black).bg(Color::Yellow))
    } else {
        Text::styled(" running ", Style::new().fg(Color::Black).bg(Color::Green))
    };
    let mut spans = vec![
        Text::styled(
            format!("{} ", scope.title),
            Style::new().add_modifier(Modifier::BOLD),
        ),
        state,
        Text::raw(format!(
            " t={:.1}s  polls={}  every {} ms  space: pause/resume  q: quit",
            scope.time,
            scope.polls,
            scope.interval.as_millis()
        )),
    ];
    if let Some(error) = &scope.error {
        spans.push(Text::styled(
            format!("  {error}"),
            Style::new().fg(Color::Red),
        ));
    }
    Paragraph::new(Line::from(spans))
}

/// One parameter's chart over the window, titled `name: latest value`.
fn chart(
    frame: &mut Frame<'_>,
    area: Rect,
    scope: &Scope,
    series: &Series,
    latest: &str,
    colour: Color,
) {
    let title = format!(" {}: {latest} ", series.parameter);
    let block = Block::bordered().title(title);
    let end = scope.time.max(WINDOW_S);
    let time = Span {
        low: end - WINDOW_S,
        high: end,
    };
    let present = Span::of(series.samples.iter().map(|p| p.1));
    let values = present.padded(0.05);
    let dataset = Dataset::default()
        .marker(Marker::Braille)
        .graph_type(GraphType::Line)
        .style(Style::new().fg(colour))
        .data(&series.samples);
    let unit = series.unit.clone().unwrap_or_default();
    let chart = Chart::new(vec![dataset])
        .block(block)
        .x_axis(Axis::default().bounds([time.low, time.high]).labels([
            axis::label(time.low, 0),
            format!("{} s", axis::label(time.high, 0)),
        ]))
        .y_axis(
            Axis::default()
                .title(unit)
                .bounds([values.low, values.high])
                .labels([
                    value_label(series, present.low, values.low),
                    value_label(series, present.high, values.high),
                ]),
        );
    frame.render_widget(chart, area);
}

/// A value axis label at an end of the axis: an enumeration's name of the value `present`
/// nearest that end, else the number `at` the end.
fn value_label(series: &Series, present: f64, at: f64) -> String {
    let named = series.names.get(&(present.round() as i64));
    named.cloned().unwrap_or_else(|| {
        let decimals = if at.abs() >= 100.0 { 0 } else { 2 };
        axis::label(at, decimals)
    })
}

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use ratatui::backend::TestBackend;
    use ratatui::Terminal;

    use super::*;
    use crate::series::Recording;

    /// The screen of a scope of Kinco's target position and mode, as text rows.
    fn screen(paused: bool) -> String {
        let device = crate::series::kinco();
        let parameters = [
            device.parameter("target_position").unwrap(),
            device.parameter("modes_of_operation").unwrap(),
        ];
        let mut recording = Recording::of(device, &parameters);
        for (t, position, mode) in [(0.0, 0.0, 1.0), (1.0, 25_000.0, 1.0), (2.0, 50_000.0, 6.0)] {
            recording.push(device, "target_position", t, position);
            recording.push(device, "modes_of_operation", t, mode);
        }
        let scope = Scope {
            title: device.device.name.clone(),
            interval: Duration::from_millis(500),
            recording,
            latest: vec!["50000 inc".into(), "homing".into()],
            error: None,
            polls: 3,
            time: 2.0,
            paused,
        };
        let mut terminal = Terminal::new(TestBackend::new(100, 30)).unwrap();
        terminal.draw(|frame| super::scope(frame, &scope)).unwrap();
        let buffer = terminal.backend().buffer();
        let cells: Vec<&str> = buffer.content().iter().map(|c| c.symbol()).collect();
        cells.chunks(100).map(|row| row.concat() + "\n").collect()
    }

    #[test]
    fn each_chart_is_titled_with_its_value_and_unit_and_the_header_says_paused() {
        let running = screen(false);
        assert!(running.contains("target_position: 50000 inc"), "{running}");
        assert!(running.contains("modes_of_operation: homing"), "{running}");
        assert!(
            running.contains("│inc"),
            "the unit on the value axis: {running}"
        );
        assert!(
            running.contains("homing") && running.contains("position"),
            "{running}"
        );
        assert!(
            running.contains(" running ") && running.contains("polls=3"),
            "{running}"
        );
        let paused = screen(true);
        assert!(
            paused.contains(" PAUSED ") && !paused.contains(" running "),
            "{paused}"
        );
    }
}
