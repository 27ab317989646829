#pragma once
// Hand-written SVG figures: a line chart (Fig. 9) and a row of map panels (Fig. 10).
// Plain data in, SVG text out; no foresight types, so it is easy to test on its own.
#include <string>
#include <vector>

namespace foresight::lab {

struct PlotPoint {
  double x = 0.0;
  double y = 0.0;
};

struct LineSeries {
  std::string name;  ///< Legend text.
  std::vector<PlotPoint> points;
  bool dashed = false;
};

struct LineChart {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<LineSeries> series;  ///< Coloured in order from a fixed palette.
  /// Extra lines under the title (e.g. the spare-time model and the machine).
  std::vector<std::string> notes;
};

/// A line chart with axes, ticks, markers and a legend. Axes start at 0 and end at a "nice" value
/// above the largest point.
std::string svg_line_chart(const LineChart& chart);

struct PlotRect {
  PlotPoint min;
  PlotPoint max;
};

struct MapLayer {
  std::string name;  ///< Panel title.
  std::vector<PlotPoint> points;
};

/// Panels side by side over the same ground view seen from above (x right, z down: not mirrored): boxes drawn filled, each panel's
/// points as dots, the avatar as a disc with its facing and the command as an arrow.
struct MapFigure {
  std::string title;
  std::vector<std::string> notes;
  PlotRect view;               ///< Ground area shown (metres).
  std::vector<PlotRect> boxes;  ///< Obstacles' ground rectangles.
  std::vector<MapLayer> panels;
  PlotPoint avatar;
  PlotPoint avatar_facing;  ///< Unit ground direction.
  PlotPoint command;        ///< Ground direction of the command (zero: none drawn).
};

std::string svg_map_panels(const MapFigure& figure);

/// Escapes &, <, > and quotes for SVG text.
std::string svg_escape(const std::string& text);

}  // namespace foresight::lab
