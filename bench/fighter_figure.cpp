#include "fighter_figure.hpp"

#include "fighter_build/fighter_cast.hpp"

#include <cstdio>
#include <sstream>

namespace foresight::bench {
namespace {

constexpr float kPanelM = 1.9f;    // Panel width in metres.
constexpr float kPanelTopM = 2.25f;// Highest point shown.
constexpr float kFloorGapM = 0.32f;// Room under the floor for the labels.

struct View {
  bool side;
  float ppm, x0, y0;  // Panel origin (the fighter's root) in pixels.
  // Side: forward (+Z) to the right. Front: the camera faces the fighter, whose left (+X) is on
  // the viewer's right.
  float x(vec3 p) const { return x0 + ppm * (side ? p.z : p.x); }
  float y(vec3 p) const { return y0 - ppm * p.y; }
};

void stick(std::ostringstream& svg, const View& v, const Skeleton& s, const std::vector<vec3>& pos,
           const char* colour, float width) {
  char line[200];
  for (int j = 1; j < s.num_joints(); ++j) {
    const vec3 a = pos[static_cast<size_t>(s.parents[static_cast<size_t>(j)])], b = pos[static_cast<size_t>(j)];
    std::snprintf(line, sizeof line,
                  "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" stroke-width=\"%.1f\" stroke-linecap=\"round\"/>\n",
                  v.x(a), v.y(a), v.x(b), v.y(b), colour, width);
    svg << line;
  }
}

}  // namespace

std::string fighter_adaptation_svg(const FighterFigureOptions& o) {
  const FighterCast cast;
  if (!cast.error.empty()) return {};
  const author::DefaultLibrarySpec& lib = cast.library;
  const LimbModel& source_model = cast.source_model;
  const std::vector<Morphology>& morphs = cast.morphs;
  const std::vector<LimbModel>& models = cast.models;
  std::string error;

  const float ppm = o.pixels_per_m;
  const float panel_px = kPanelM * ppm, row_px = (kPanelTopM + kFloorGapM) * ppm + 24.0f;
  const float width = panel_px * static_cast<float>(morphs.size());
  const float height = row_px * static_cast<float>(o.strikes.size()) + 10.0f;
  std::ostringstream svg;
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" viewBox=\"0 0 %.0f %.0f\" "
                "font-family=\"sans-serif\" font-size=\"13\">\n<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n",
                width, height, width, height);
  svg << buf;
  for (size_t row = 0; row < o.strikes.size(); ++row) {
    const FighterFigureStrike& st = o.strikes[row];
    const float top = 10.0f + row_px * static_cast<float>(row);
    const author::AuthoredClip* clip = nullptr;
    for (const author::AuthoredClip& c : lib.clips)
      if (c.strike && c.clip.name == st.clip) clip = &c;
    if (!clip) {
      std::snprintf(buf, sizeof buf, "<text x=\"10\" y=\"%.0f\">no default strike named %s</text>\n", top + 20.0f, st.clip.c_str());
      svg << buf;
      continue;
    }
    std::snprintf(buf, sizeof buf, "<text x=\"8\" y=\"%.0f\" font-weight=\"bold\">%s</text>\n", top + 14.0f,
                  st.clip.c_str());
    svg << buf;
    for (size_t m = 0; m < morphs.size(); ++m) {
      const View v{o.side_view, ppm, panel_px * static_cast<float>(m) + (o.side_view ? 0.45f : 0.5f * kPanelM) * ppm,
                   top + kPanelTopM * ppm};
      StrikeRequest req;
      req.source = {&lib.skeleton, &source_model};
      req.clip = &clip->clip;
      req.hit_frame = clip->strike->hit_frame;
      req.kick = clip->strike->kind == "kick";
      req.side = clip->strike->side == "left" ? kFighterLeft : kFighterRight;
      req.target_m = st.target_m;
      StrikeAdapter adapter;
      if (!adapter.begin(req, {&morphs[m].skeleton, &models[m]}, AdaptSettings{}, {}, {}, error)) continue;
      const AdaptedFrame hit = adapter.pose_frame(adapter.hit_index());
      // Floor, the unadapted strike, the adapted one, the target.
      std::snprintf(buf, sizeof buf, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#888\"/>\n",
                    panel_px * static_cast<float>(m) + 8.0f, v.y0, panel_px * static_cast<float>(m + 1) - 8.0f, v.y0);
      svg << buf;
      stick(svg, v, morphs[m].skeleton, adapter.retargeted().global_pos_m, "#c8c8c8", 3.0f);
      stick(svg, v, morphs[m].skeleton, adapter.pose().global_pos_m, "#2a7fd4", 3.5f);
      std::snprintf(buf, sizeof buf,
                    "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"%.1f\" fill=\"none\" stroke=\"#d62728\" stroke-width=\"2\"/>\n",
                    v.x(st.target_m), v.y(st.target_m), 0.06f * ppm);
      svg << buf;
      std::snprintf(buf, sizeof buf,
                    "<text x=\"%.1f\" y=\"%.1f\">%s, %.2f m</text>\n<text x=\"%.1f\" y=\"%.1f\" fill=\"#555\">"
                    "error %.1f mm%s</text>\n",
                    panel_px * static_cast<float>(m) + 8.0f, v.y0 + 16.0f, morphs[m].name.c_str(), morphs[m].height_m,
                    panel_px * static_cast<float>(m) + 8.0f, v.y0 + 32.0f,
                    1000.0f * glm::length(hit.effector_m - st.target_m), hit.ccd_iterations > 0 ? " (torso)" : "");
      svg << buf;
    }
  }
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace foresight::bench
