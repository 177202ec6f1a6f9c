//! A plot as a self-contained HTML page: the SVG document inline and a small script of our own
//! that zooms the shared time axis (wheel), pans it (drag) and resets it (double click). No
//! network: nothing is loaded from anywhere.

use super::svg;
use super::Series;

/// The page of `series`, titled `title`.
pub fn render(title: &str, series: &[Series]) -> String {
    let title = svg::escape(title);
    let names: Vec<String> = series.iter().map(|s| svg::escape(&s.title())).collect();
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>{title}</title>\n\
         <style>body{{margin:16px;font-family:sans-serif}}p{{color:#555;font-size:13px}}</style>\n\
         </head>\n<body>\n<h1 style=\"font-size:16px\">{title}</h1>\n\
         <p>{}. Wheel: zoom in time; drag: pan; double click: everything.</p>\n{}<script>\n{SCRIPT}</script>\n</body>\n</html>\n",
        names.join(", "),
        svg::render(series)
    )
}

/// Zoom and pan: every panel's `svg.plot` shows `[t0, t1]` through its viewBox, and the time
/// labels under each panel are written again for that range. The page marks itself
/// `data-plot-ready` once the script has run, `data-plot-error` if anything threw.
const SCRIPT: &str = r#"(function () {
  "use strict";
  window.addEventListener("error", function (e) {
    document.documentElement.setAttribute("data-plot-error", String(e.message));
  });
  var root = document.querySelector("svg.drivegen-plot");
  if (!root) { return; }
  var full = [parseFloat(root.dataset.t0), parseFloat(root.dataset.t1)];
  var left = parseFloat(root.dataset.left), width = parseFloat(root.dataset.width);
  var view = full.slice();
  var NS = "http://www.w3.org/2000/svg";

  function ticks(t0, t1) {
    var raw = (t1 - t0) / 8, power = Math.pow(10, Math.floor(Math.log10(raw)));
    var step = [1, 2, 5, 10].map(function (m) { return m * power; })
      .find(function (s) { return s >= raw * (1 - 1e-9); });
    var decimals = Math.max(0, -Math.floor(Math.log10(step)));
    var out = [];
    for (var i = Math.ceil(t0 / step - 1e-9); i <= Math.floor(t1 / step + 1e-9); i++) {
      out.push([i * step, (i * step).toFixed(decimals)]);
    }
    return out;
  }

  function draw() {
    var t0 = view[0], t1 = view[1];
    root.querySelectorAll("svg.plot").forEach(function (plot) {
      var box = plot.viewBox.baseVal;
      plot.setAttribute("viewBox", t0 + " " + box.y + " " + (t1 - t0) + " " + box.height);
    });
    root.querySelectorAll("g.xticks").forEach(function (group) {
      while (group.firstChild) { group.removeChild(group.firstChild); }
      ticks(t0, t1).forEach(function (tick) {
        var text = document.createElementNS(NS, "text");
        text.setAttribute("x", left + width * (tick[0] - t0) / (t1 - t0));
        text.setAttribute("y", group.dataset.y);
        text.setAttribute("text-anchor", "middle");
        text.textContent = tick[1];
        group.appendChild(text);
      });
    });
  }

  function timeAt(clientX) {
    var box = root.getBoundingClientRect();
    var scale = box.width / root.viewBox.baseVal.width;
    var x = (clientX - box.left) / scale;
    return view[0] + (view[1] - view[0]) * Math.min(1, Math.max(0, (x - left) / width));
  }

  root.addEventListener("wheel", function (e) {
    e.preventDefault();
    var at = timeAt(e.clientX), factor = e.deltaY > 0 ? 1.25 : 0.8;
    var t0 = at - (at - view[0]) * factor, t1 = at + (view[1] - at) * factor;
    if (t1 - t0 > 1e-6) { view = [t0, t1]; draw(); }
  }, { passive: false });

  var dragFrom = null;
  root.addEventListener("mousedown", function (e) { dragFrom = [e.clientX, view.slice()]; });
  window.addEventListener("mouseup", function () { dragFrom = null; });
  window.addEventListener("mousemove", function (e) {
    if (!dragFrom) { return; }
    var box = root.getBoundingClientRect();
    var scale = box.width / root.viewBox.baseVal.width;
    var shift = (e.clientX - dragFrom[0]) / scale / width * (dragFrom[1][1] - dragFrom[1][0]);
    view = [dragFrom[1][0] - shift, dragFrom[1][1] - shift];
    draw();
  });
  root.addEventListener("dblclick", function () { view = full.slice(); draw(); });

  draw();
  document.documentElement.setAttribute("data-plot-ready", root.querySelectorAll("path.series").length);
})();
"#;
