// The admin endpoint's live page (GET /?token=...): polls /status twice a second and plots the
// last minute of tick time, look-ahead budget use and tree sizes. Plain HTML, SVG and a few lines
// of script: nothing to install, nothing fetched from elsewhere.
#include "admin_http.hpp"

namespace foresight::server {

const char* admin_page_html() {
  return R"html(<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>Foresight server</title>
<style>
 body { font: 14px system-ui, sans-serif; margin: 1.5em; background: #f6f7f9; color: #222; }
 h1 { font-size: 1.3em; margin: 0 0 .3em; } .muted { color: #666; }
 .chart { background: #fff; border: 1px solid #ccd; margin: .6em 0; }
 .chart text { font-size: 11px; fill: #555; } polyline { fill: none; stroke-width: 1.5; }
 table { border-collapse: collapse; } td { padding: 1px 12px 1px 0; }
</style></head>
<body>
<h1>Foresight server <span class="muted" id="scene"></span></h1>
<div class="muted" id="state">connecting...</div>
<table>
 <tr><td>tick</td><td id="tick">-</td><td>players</td><td id="players">-</td></tr>
 <tr><td>tick ms (last / p99)</td><td id="tick-ms">-</td><td>overruns</td><td id="overruns">-</td></tr>
 <tr><td>budget use</td><td id="budget-use">-</td><td>strategy</td><td id="strategy">-</td></tr>
 <tr><td>tree size (mean)</td><td id="tree-size">-</td><td>drops</td><td id="drops">-</td></tr>
</table>
<svg id="tick-chart" class="chart" width="640" height="120" data-samples="0"></svg>
<svg id="budget-chart" class="chart" width="640" height="120" data-samples="0"></svg>
<svg id="tree-chart" class="chart" width="640" height="120" data-samples="0"></svg>
<script>
const token = new URLSearchParams(location.search).get("token") || "";
const keep = 120, series = { tick: [], budget: [], tree: [] };
function plot(id, values, colour, label, unit) {
  const svg = document.getElementById(id), w = 640, h = 120, max = Math.max(1e-9, ...values);
  const points = values.map((v, i) => `${(i / (keep - 1)) * w},${h - 18 - (v / max) * (h - 30)}`).join(" ");
  svg.innerHTML = `<text x="4" y="12">${label}: ${values.length ? values[values.length - 1].toFixed(2) : "-"} ${unit}` +
                  ` (max ${max.toFixed(2)})</text><polyline stroke="${colour}" points="${points}"/>`;
  svg.setAttribute("data-samples", values.length);
}
function push(list, v) { list.push(v); if (list.length > keep) list.shift(); }
async function poll() {
  try {
    const r = await fetch("/status", { headers: { Authorization: "Bearer " + token } });
    if (!r.ok) throw new Error("HTTP " + r.status);
    const s = await r.json();
    push(series.tick, s.tick_ms.last); push(series.budget, 100 * s.budget_use); push(series.tree, s.tree_size_mean);
    document.getElementById("state").textContent = "live, " + s.uptime_s.toFixed(0) + " s up";
    document.getElementById("scene").textContent = s.scene + " (" + s.locomotion + ")";
    document.getElementById("tick").textContent = s.tick;
    document.getElementById("players").textContent = s.players + " / " + s.max_players;
    document.getElementById("tick-ms").textContent = s.tick_ms.last.toFixed(2) + " / " + s.tick_ms.p99.toFixed(2);
    document.getElementById("overruns").textContent = s.overruns;
    document.getElementById("budget-use").textContent = (100 * s.budget_use).toFixed(0) + " % of " + s.config.budget_ms + " ms";
    document.getElementById("strategy").textContent = s.config.strategy;
    document.getElementById("tree-size").textContent = s.tree_size_mean.toFixed(0);
    document.getElementById("drops").textContent = Object.values(s.dropped).reduce((a, b) => a + b, 0);
    plot("tick-chart", series.tick, "#c0392b", "tick time", "ms");
    plot("budget-chart", series.budget, "#2471a3", "look-ahead budget use", "%");
    plot("tree-chart", series.tree, "#1e8449", "tree size (mean)", "nodes");
  } catch (e) {
    document.getElementById("state").textContent = "no answer: " + e.message;
  }
  setTimeout(poll, 500);
}
poll();
</script>
</body></html>
)html";
}

}  // namespace foresight::server
