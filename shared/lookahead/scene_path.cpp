#include "lookahead/scene_path.hpp"

#include "world/collision_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <queue>

namespace foresight {
namespace {

// Grids larger than this get a coarser spacing (a 500 m scene at 0.25 m is 4M points).
constexpr int64_t kMaxRoutePoints = int64_t{1} << 22;
// The radius of the thin body that joins the exact start / goal to the grid.
constexpr float kThinRadius_m = 0.05f;

bool point_free(const CollisionWorld& world, vec2 p, float clearance_m, float body_height_m,
                float& ground_m) {
  if (!ground_height_at(world, p, ground_m)) return false;
  const BodyVolume body{p, clearance_m, ground_m, ground_m + body_height_m};
  return !frame_collides(world, body, ground_m);
}

struct Grid {
  vec2 origin{0.0f};
  float spacing = kRouteGridSpacing_m;
  int nx = 0, nz = 0;
  std::vector<int8_t> state;  // -1 unknown, 0 blocked, 1 free (lazily evaluated)
  std::vector<float> ground;

  vec2 point(int i) const {
    return origin + spacing * vec2(static_cast<float>(i % nx), static_cast<float>(i / nx));
  }
};

bool grid_free(const CollisionWorld& world, Grid& g, int i, float clearance_m, float height_m) {
  int8_t& s = g.state[static_cast<size_t>(i)];
  if (s < 0) s = point_free(world, g.point(i), clearance_m, height_m, g.ground[static_cast<size_t>(i)]) ? 1 : 0;
  return s == 1;
}

// The nearest free grid point to p that a thin body can reach from p in a straight line.
int snap(const CollisionWorld& world, Grid& g, vec2 p, float clearance_m, float height_m) {
  const float reach = std::max(clearance_m, 0.5f);
  const int r = static_cast<int>(std::ceil(reach / g.spacing)) + 1;
  const int cx = static_cast<int>(std::lround((p.x - g.origin.x) / g.spacing));
  const int cz = static_cast<int>(std::lround((p.y - g.origin.y) / g.spacing));
  int best = -1;
  float best_d = std::numeric_limits<float>::max();
  for (int iz = cz - r; iz <= cz + r; ++iz)
    for (int ix = cx - r; ix <= cx + r; ++ix) {
      if (ix < 0 || iz < 0 || ix >= g.nx || iz >= g.nz) continue;
      const int i = iz * g.nx + ix;
      const float d = glm::length(g.point(i) - p);
      if (d > reach || d >= best_d) continue;
      if (!grid_free(world, g, i, clearance_m, height_m)) continue;
      if (!scene_segment_clear(world, p, g.point(i), kThinRadius_m, height_m)) continue;
      best = i;
      best_d = d;
    }
  return best;
}

}  // namespace

bool scene_segment_clear(const CollisionWorld& world, vec2 a, vec2 b, float clearance_m,
                         float body_height_m) {
  const float length = glm::length(b - a);
  if (!std::isfinite(length)) return false;
  const float step = std::clamp(0.5f * clearance_m, 0.02f, 0.1f);
  const int n = std::max(1, static_cast<int>(std::ceil(length / step)));
  float previous_ground = 0.0f;
  for (int k = 0; k <= n; ++k) {
    const vec2 p = a + (b - a) * (static_cast<float>(k) / static_cast<float>(n));
    float ground_m = 0.0f;
    if (!point_free(world, p, clearance_m, body_height_m, ground_m)) return false;
    if (k > 0 && std::abs(ground_m - previous_ground) > world.config.ground_tolerance_m) return false;
    previous_ground = ground_m;
  }
  return true;
}

bool scene_route(const CollisionWorld& world, vec2 from, vec2 to, float clearance_m,
                 float body_height_m, std::vector<vec2>& waypoints) {
  waypoints.clear();
  if (world.empty() || !std::isfinite(from.x) || !std::isfinite(from.y) || !std::isfinite(to.x) ||
      !std::isfinite(to.y) || !std::isfinite(clearance_m) || !std::isfinite(body_height_m) ||
      clearance_m < 0.0f || body_height_m <= 0.0f)
    return false;

  Grid g;
  const vec2 size = world.bounds.size_m();
  while (static_cast<int64_t>(size.x / g.spacing + 2) * static_cast<int64_t>(size.y / g.spacing + 2) >
         kMaxRoutePoints)
    g.spacing *= 2.0f;
  g.origin = vec2(std::ceil(world.bounds.min_m.x / g.spacing), std::ceil(world.bounds.min_m.y / g.spacing)) *
             g.spacing;
  g.nx = static_cast<int>(std::floor((world.bounds.max_m.x - g.origin.x) / g.spacing)) + 1;
  g.nz = static_cast<int>(std::floor((world.bounds.max_m.y - g.origin.y) / g.spacing)) + 1;
  if (g.nx <= 0 || g.nz <= 0) return false;
  const size_t n = static_cast<size_t>(g.nx) * static_cast<size_t>(g.nz);
  g.state.assign(n, -1);
  g.ground.assign(n, 0.0f);

  const int start = snap(world, g, from, clearance_m, body_height_m);
  const int goal = snap(world, g, to, clearance_m, body_height_m);
  if (start < 0 || goal < 0) return false;

  // A*, octile heuristic; ties broken by node index so the result is deterministic.
  std::vector<float> cost(n, std::numeric_limits<float>::infinity());
  std::vector<int> came_from(n, -1);
  using Entry = std::pair<float, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  const vec2 goal_p = g.point(goal);
  const auto heuristic = [&](int i) {
    const vec2 d = glm::abs(g.point(i) - goal_p);
    return std::max(d.x, d.y) + (std::sqrt(2.0f) - 1.0f) * std::min(d.x, d.y);
  };
  cost[static_cast<size_t>(start)] = 0.0f;
  open.push({heuristic(start), start});
  const float tol = world.config.ground_tolerance_m;
  bool found = false;
  while (!open.empty()) {
    const auto [f, i] = open.top();
    open.pop();
    if (i == goal) {
      found = true;
      break;
    }
    const float ci = cost[static_cast<size_t>(i)];
    if (f > ci + heuristic(i) + 1e-4f) continue;  // stale entry
    const int ix = i % g.nx, iz = i / g.nx;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dx = -1; dx <= 1; ++dx) {
        if (dx == 0 && dz == 0) continue;
        const int jx = ix + dx, jz = iz + dz;
        if (jx < 0 || jz < 0 || jx >= g.nx || jz >= g.nz) continue;
        const int j = jz * g.nx + jx;
        if (!grid_free(world, g, j, clearance_m, body_height_m)) continue;
        // No corner cutting: a diagonal needs both orthogonal neighbours.
        if (dx != 0 && dz != 0 &&
            (!grid_free(world, g, iz * g.nx + jx, clearance_m, body_height_m) ||
             !grid_free(world, g, jz * g.nx + ix, clearance_m, body_height_m)))
          continue;
        if (std::abs(g.ground[static_cast<size_t>(j)] - g.ground[static_cast<size_t>(i)]) > tol) continue;
        float mid_ground = 0.0f;
        if (!point_free(world, 0.5f * (g.point(i) + g.point(j)), clearance_m, body_height_m, mid_ground))
          continue;
        const float cj = ci + g.spacing * (dx != 0 && dz != 0 ? std::sqrt(2.0f) : 1.0f);
        if (cj < cost[static_cast<size_t>(j)]) {
          cost[static_cast<size_t>(j)] = cj;
          came_from[static_cast<size_t>(j)] = i;
          open.push({cj + heuristic(j), j});
        }
      }
  }
  if (!found) return false;

  std::vector<vec2> path{to};
  for (int i = goal; i >= 0; i = came_from[static_cast<size_t>(i)]) path.push_back(g.point(i));
  path.push_back(from);
  std::reverse(path.begin(), path.end());

  // String pulling: from each anchor, the furthest point reachable in a straight clear line
  // (scanning forward until the first failure). The exact start / goal legs were checked with a
  // thin body only, so they are always accepted as legs.
  waypoints.push_back(from);
  size_t anchor = 0;
  while (anchor + 1 < path.size()) {
    size_t next = anchor + 1;
    for (size_t j = anchor + 2; j < path.size(); ++j) {
      if (!scene_segment_clear(world, path[anchor], path[j], clearance_m, body_height_m)) break;
      next = j;
    }
    waypoints.push_back(path[next]);
    anchor = next;
  }
  // Drop zero-length legs (from or to exactly on a grid point).
  waypoints.erase(std::unique(waypoints.begin(), waypoints.end()), waypoints.end());
  if (waypoints.size() < 2) waypoints.push_back(to);
  return true;
}

float route_length_m(const std::vector<vec2>& waypoints) {
  float length = 0.0f;
  for (size_t i = 1; i < waypoints.size(); ++i) length += glm::length(waypoints[i] - waypoints[i - 1]);
  return length;
}

}  // namespace foresight
