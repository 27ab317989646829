#include "lab/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace foresight::lab {
namespace {

constexpr const char* kPalette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd",
                                    "#ff7f0e", "#8c564b", "#17becf", "#7f7f7f"};
constexpr size_t kPaletteSize = sizeof kPalette / sizeof kPalette[0];

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

/// The smallest of 1, 2, 2.5, 5 x 10^k that is >= v (v > 0).
double nice_ceiling(double v) {
  if (!(v > 0.0) || !std::isfinite(v)) return 1.0;
  const double p = std::pow(10.0, std::floor(std::log10(v)));
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (m * p >= v * (1.0 - 1e-9)) return m * p;
  return 10.0 * p;
}

std::string tick_label(double v) {
  char buf[32];
  if (std::fabs(v - std::round(v)) < 1e-9 && std::fabs(v) < 1e9)
    std::snprintf(buf, sizeof buf, "%.0f", v);
  else
    std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

std::string text(double x, double y, const std::string& s, const char* anchor = "start",
                 int size = 12, const char* extra = "") {
  return "<text x=\"" + num(x) + "\" y=\"" + num(y) + "\" font-size=\"" + std::to_string(size) +
         "\" text-anchor=\"" + anchor + "\" " + extra + ">" + svg_escape(s) + "</text>\n";
}

std::string header(double w, double h) {
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(w) + "\" height=\"" + num(h) +
         "\" viewBox=\"0 0 " + num(w) + " " + num(h) +
         "\" font-family=\"sans-serif\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
}

}  // namespace

std::string svg_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string svg_line_chart(const LineChart& chart) {
  const double width = 820, plot_w = 520, plot_h = 340;
  const double left = 80, top = 50 + 16.0 * static_cast<double>(chart.notes.size());
  const double height = top + plot_h + 70;
  double x_max = 0, y_max = 0;
  for (const LineSeries& s : chart.series)
    for (const PlotPoint& p : s.points) x_max = std::max(x_max, p.x), y_max = std::max(y_max, p.y);
  x_max = nice_ceiling(x_max);
  y_max = nice_ceiling(y_max);
  auto sx = [&](double x) { return left + plot_w * x / x_max; };
  auto sy = [&](double y) { return top + plot_h * (1.0 - y / y_max); };

  std::string out = header(width, height);
  out += text(left, 24, chart.title, "start", 16, "font-weight=\"bold\"");
  for (size_t i = 0; i < chart.notes.size(); ++i)
    out += text(left, 42 + 16.0 * static_cast<double>(i), chart.notes[i], "start", 11,
                "fill=\"#555\"");
  // Grid, ticks and labels: five steps on each axis.
  for (int i = 0; i <= 5; ++i) {
    const double fx = x_max * i / 5.0, fy = y_max * i / 5.0;
    out += "<line x1=\"" + num(sx(fx)) + "\" y1=\"" + num(top) + "\" x2=\"" + num(sx(fx)) +
           "\" y2=\"" + num(top + plot_h) + "\" stroke=\"#e5e5e5\"/>\n";
    out += "<line x1=\"" + num(left) + "\" y1=\"" + num(sy(fy)) + "\" x2=\"" + num(left + plot_w) +
           "\" y2=\"" + num(sy(fy)) + "\" stroke=\"#e5e5e5\"/>\n";
    out += text(sx(fx), top + plot_h + 18, tick_label(fx), "middle", 11);
    out += text(left - 8, sy(fy) + 4, tick_label(fy), "end", 11);
  }
  out += "<rect x=\"" + num(left) + "\" y=\"" + num(top) + "\" width=\"" + num(plot_w) +
         "\" height=\"" + num(plot_h) + "\" fill=\"none\" stroke=\"black\"/>\n";
  out += text(left + plot_w / 2, top + plot_h + 44, chart.x_label, "middle", 13);
  out += text(24, top + plot_h / 2, chart.y_label, "middle", 13,
              ("transform=\"rotate(-90 24 " + num(top + plot_h / 2) + ")\"").c_str());

  for (size_t k = 0; k < chart.series.size(); ++k) {
    const LineSeries& s = chart.series[k];
    const std::string colour = kPalette[k % kPaletteSize];
    std::string pts;
    for (const PlotPoint& p : s.points) pts += num(sx(p.x)) + "," + num(sy(p.y)) + " ";
    out += "<polyline fill=\"none\" stroke=\"" + colour + "\" stroke-width=\"2\"" +
           (s.dashed ? " stroke-dasharray=\"6 4\"" : "") + " points=\"" + pts + "\"/>\n";
    for (const PlotPoint& p : s.points)
      out += "<circle cx=\"" + num(sx(p.x)) + "\" cy=\"" + num(sy(p.y)) + "\" r=\"3.5\" fill=\"" +
             colour + "\"/>\n";
    const double ly = top + 10 + 22.0 * static_cast<double>(k);
    const double lx = left + plot_w + 20;
    out += "<line x1=\"" + num(lx) + "\" y1=\"" + num(ly) + "\" x2=\"" + num(lx + 26) + "\" y2=\"" +
           num(ly) + "\" stroke=\"" + colour + "\" stroke-width=\"2\"" +
           (s.dashed ? " stroke-dasharray=\"6 4\"" : "") + "/>\n";
    out += text(lx + 32, ly + 4, s.name, "start", 12);
  }
  return out + "</svg>\n";
}

std::string svg_map_panels(const MapFigure& f) {
  const double panel = 300, gap = 16, left = 16;
  const double top = 40 + 16.0 * static_cast<double>(f.notes.size());
  const size_t n = std::max<size_t>(f.panels.size(), 1);
  const double width = left + static_cast<double>(n) * (panel + gap);
  const double view_w = std::max(f.view.max.x - f.view.min.x, 1e-6);
  const double view_h = std::max(f.view.max.y - f.view.min.y, 1e-6);
  const double scale = panel / std::max(view_w, view_h);
  const double height = top + 24 + view_h * scale + 20;

  std::string out = header(width, height);
  out += text(left, 24, f.title, "start", 16, "font-weight=\"bold\"");
  for (size_t i = 0; i < f.notes.size(); ++i)
    out += text(left, 42 + 16.0 * static_cast<double>(i), f.notes[i], "start", 11,
                "fill=\"#555\"");
  for (size_t k = 0; k < f.panels.size(); ++k) {
    const double ox = left + static_cast<double>(k) * (panel + gap), oy = top + 24;
    auto sx = [&](double x) { return ox + (x - f.view.min.x) * scale; };
    auto sy = [&](double z) { return oy + (z - f.view.min.y) * scale; };
    const std::string clip = "panel" + std::to_string(k);
    out += "<clipPath id=\"" + clip + "\"><rect x=\"" + num(ox) + "\" y=\"" + num(oy) +
           "\" width=\"" + num(view_w * scale) + "\" height=\"" + num(view_h * scale) +
           "\"/></clipPath>\n";
    out += text(ox, oy - 8, f.panels[k].name, "start", 13);
    out += "<g clip-path=\"url(#" + clip + ")\">\n";
    out += "<rect x=\"" + num(ox) + "\" y=\"" + num(oy) + "\" width=\"" + num(view_w * scale) +
           "\" height=\"" + num(view_h * scale) + "\" fill=\"#fafafa\"/>\n";
    for (const PlotRect& b : f.boxes) {
      if (b.max.x < f.view.min.x || b.min.x > f.view.max.x || b.max.y < f.view.min.y ||
          b.min.y > f.view.max.y)
        continue;
      out += "<rect x=\"" + num(sx(b.min.x)) + "\" y=\"" + num(sy(b.min.y)) + "\" width=\"" +
             num((b.max.x - b.min.x) * scale) + "\" height=\"" + num((b.max.y - b.min.y) * scale) +
             "\" fill=\"#888\"/>\n";
    }
    const std::string colour = kPalette[k % kPaletteSize];
    for (const PlotPoint& p : f.panels[k].points)
      out += "<circle cx=\"" + num(sx(p.x)) + "\" cy=\"" + num(sy(p.y)) + "\" r=\"2\" fill=\"" +
             colour + "\" fill-opacity=\"0.6\"/>\n";
    // Avatar: a black disc, its facing as a short line, the command as a longer orange arrow.
    const double ax = sx(f.avatar.x), ay = sy(f.avatar.y);
    out += "<circle cx=\"" + num(ax) + "\" cy=\"" + num(ay) + "\" r=\"5\" fill=\"black\"/>\n";
    out += "<line x1=\"" + num(ax) + "\" y1=\"" + num(ay) + "\" x2=\"" +
           num(ax + 12 * f.avatar_facing.x) + "\" y2=\"" + num(ay + 12 * f.avatar_facing.y) +
           "\" stroke=\"black\" stroke-width=\"2\"/>\n";
    const double cl = std::hypot(f.command.x, f.command.y);
    if (cl > 1e-6) {
      const double ux = f.command.x / cl, uy = f.command.y / cl, len = 1.5 * scale;
      const double tx = ax + len * ux, ty = ay + len * uy;
      out += "<line x1=\"" + num(ax) + "\" y1=\"" + num(ay) + "\" x2=\"" + num(tx) + "\" y2=\"" +
             num(ty) + "\" stroke=\"#e67e00\" stroke-width=\"3\"/>\n";
      out += "<polygon fill=\"#e67e00\" points=\"" + num(tx + 8 * ux) + "," + num(ty + 8 * uy) +
             " " + num(tx - 5 * uy) + "," + num(ty + 5 * ux) + " " + num(tx + 5 * uy) + "," +
             num(ty - 5 * ux) + "\"/>\n";
    }
    out += "</g>\n<rect x=\"" + num(ox) + "\" y=\"" + num(oy) + "\" width=\"" +
           num(view_w * scale) + "\" height=\"" + num(view_h * scale) +
           "\" fill=\"none\" stroke=\"black\"/>\n";
  }
  return out + "</svg>\n";
}

}  // namespace foresight::lab
