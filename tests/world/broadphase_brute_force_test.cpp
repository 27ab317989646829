// The grid, the ground ranges and the sweep early-out give exactly the answers of a brute-force loop
// over every box and the scene's own terrain, on many random placements. This is the test that
// proves the broadphase right.
#include "world_test_util.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace foresight {
namespace {

using Rng = std::mt19937_64;

float uniform(Rng& rng, float lo, float hi) {
  return std::uniform_real_distribution<float>(lo, hi)(rng);
}

/// A deliberately awkward scene: off-origin non-square bounds, boxes of every size and height
/// (some poking out of the bounds, some thin), a height field with holes over part of it, steps
/// (one bridging holes), a raised floor.
Scene random_scene(std::uint64_t seed) {
  Rng rng(seed);
  Scene s;
  s.name = "random";
  s.bounds = {{-5.3f, -2.7f}, {14.9f, 11.1f}};
  s.terrain.floor_y_m = 0.05f;
  for (int i = 0; i < 120; ++i) {
    const vec2 c(uniform(rng, -7.0f, 17.0f), uniform(rng, -5.0f, 13.0f));
    const vec2 half(uniform(rng, 0.02f, 1.0f), uniform(rng, 0.02f, 1.0f));
    const float y0 = uniform(rng, -0.5f, 2.0f);
    const float y1 = y0 + uniform(rng, 0.01f, 2.0f);
    s.boxes.push_back({"", static_cast<BoxKind>(i % 7), {c.x - half.x, y0, c.y - half.y},
                       {c.x + half.x, y1, c.y + half.y}});
  }
  HeightField& f = s.terrain.height_field;
  f.origin_m = {-1.13f, 0.37f};
  f.cell_m = 0.23f;
  f.count_x = 37;
  f.count_z = 29;
  for (int i = 0; i < f.count_x * f.count_z; ++i)
    f.heights_m.push_back(uniform(rng, 0.0f, 1.0f) < 0.1f ? NAN : uniform(rng, -0.3f, 0.3f));
  for (int i = 0; i < 20; ++i) {
    const vec2 c(uniform(rng, -5.0f, 15.0f), uniform(rng, -3.0f, 11.0f));
    const vec2 half(uniform(rng, 0.1f, 1.2f), uniform(rng, 0.1f, 1.2f));
    s.terrain.steps.push_back({"", {c.x - half.x, -1.0f, c.y - half.y},
                               {c.x + half.x, uniform(rng, 0.0f, 0.5f), c.y + half.y}});
  }
  s.terrain.steps.push_back({"bridge", {0.0f, -1.0f, 2.0f}, {4.0f, 0.1f, 2.6f}});
  s.spawns.push_back({"s", {0, 0}, 0});
  return s;
}

/// Random volumes around and beyond the bounds: discs and capsules, radii from 0 to well past the fast radius, y
/// ranges from crouching to tall, ground references at or near the local ground.
void compare_frames(const Scene& scene, const CollisionWorld& world, std::uint64_t seed, int n) {
  Rng rng(seed);
  const GroundRect& b = scene.bounds;
  const float tol = world.config.ground_tolerance_m;
  int hits = 0, mismatches = 0;
  for (int i = 0; i < n; ++i) {
    BodyVolume v;
    v.center_m = {uniform(rng, b.min_m.x - 1.0f, b.max_m.x + 1.0f),
                  uniform(rng, b.min_m.y - 1.0f, b.max_m.y + 1.0f)};
    const float pick = uniform(rng, 0.0f, 1.0f);
    v.radius_m = pick < 0.05f ? 0.0f : pick < 0.85f ? uniform(rng, 0.05f, 0.6f) : uniform(rng, 0.6f, 2.5f);
    // Half the volumes are capsules, long axes of any direction.
    if (uniform(rng, 0.0f, 1.0f) < 0.5f) {
      const float a = uniform(rng, -kPi, kPi);
      v.half_axis_m = uniform(rng, 0.0f, 0.7f) * vec2(std::cos(a), std::sin(a));
    }
    float g = 0.0f;
    const bool has_ground = terrain_height_at(scene.terrain, v.center_m, g);
    const float ref = has_ground && pick < 0.7f ? g : uniform(rng, -0.5f, 0.8f);
    v.y_min_m = ref + uniform(rng, -0.1f, 0.3f);
    v.y_max_m = v.y_min_m + uniform(rng, 0.5f, 2.0f);
    const bool expected = test::brute_frame_collides(scene, v, ref, tol);
    const bool got = frame_collides(world, v, ref);
    hits += expected;
    if (got != expected && ++mismatches <= 5)
      ADD_FAILURE() << "frame " << i << " at (" << v.center_m.x << ", " << v.center_m.y
                    << ") r=" << v.radius_m << " half axis (" << v.half_axis_m.x << ", " << v.half_axis_m.y << ") y=" << v.y_min_m << ".." << v.y_max_m
                    << " ref=" << ref << ": grid " << got << ", brute " << expected;
  }
  EXPECT_EQ(mismatches, 0);
  // Both answers must be common, or the comparison proves little.
  EXPECT_GT(hits, n / 10);
  EXPECT_LT(hits, n - n / 10);
}

std::vector<SegmentCollisionShape> random_shapes(Rng& rng, FrameOrder order) {
  std::vector<SegmentCollisionShape> shapes;
  for (int i = 0; i < 24; ++i) {
    SyntheticSweepSpec spec;
    spec.frames = 1 + static_cast<int>(uniform(rng, 0.0f, 40.0f));
    spec.forward_m = uniform(rng, 0.0f, 3.0f);
    spec.turn_rad = uniform(rng, -2.0f, 2.0f) * (i % 3 == 0 ? 0.0f : 1.0f);
    spec.sideways_m = i % 5 == 0 ? uniform(rng, -0.8f, 0.8f) : 0.0f;
    spec.radius_m = i % 7 == 0 ? uniform(rng, 0.6f, 1.2f) : uniform(rng, 0.1f, 0.5f);
    spec.half_length_m = i % 2 == 0 ? uniform(rng, 0.0f, 0.5f) : 0.0f;
    spec.y_max_m = uniform(rng, 0.9f, 2.0f);
    shapes.push_back(make_segment_shape(synthetic_sweep(spec), order, 1 + i % 6));
  }
  return shapes;
}

void compare_segments(const Scene& scene, const CollisionWorld& world, std::uint64_t seed, int n) {
  Rng rng(seed);
  const float tol = world.config.ground_tolerance_m;
  const GroundRect& b = scene.bounds;
  std::vector<std::vector<SegmentCollisionShape>> by_order;
  for (FrameOrder order : {FrameOrder::kSequential, FrameOrder::kLastFirst, FrameOrder::kCoarseToFine}) {
    Rng shape_rng(seed + 1);  // Same shapes, different orders.
    by_order.push_back(random_shapes(shape_rng, order));
  }
  CheckStats stats;
  int feasible = 0, mismatches = 0;
  for (int i = 0; i < n; ++i) {
    const std::size_t k = static_cast<std::size_t>(uniform(rng, 0.0f, 23.999f));
    const Placement p{{uniform(rng, b.min_m.x - 0.5f, b.max_m.x + 0.5f),
                       uniform(rng, b.min_m.y - 0.5f, b.max_m.y + 0.5f)},
                      uniform(rng, -kPi, kPi)};
    const int expected = test::brute_first_collision(scene, by_order[0][k].frames, p, tol);
    feasible += expected < 0;
    for (const auto& shapes : by_order) {
      const bool got = segment_feasible(world, shapes[k], p, &stats);
      const int first = segment_first_collision(world, shapes[k], p);
      if ((got != (expected < 0) || first != expected) && ++mismatches <= 5)
        ADD_FAILURE() << "segment " << k << " order " << static_cast<int>(shapes[k].order)
                      << " at (" << p.pos_m.x << ", " << p.pos_m.y << ") heading " << p.heading_rad
                      << ": feasible " << got << " first " << first << ", brute first " << expected;
    }
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(feasible, n / 20);
  EXPECT_LT(feasible, n - n / 20);
  EXPECT_EQ(stats.clip_checks, 3u * n);
  EXPECT_GE(stats.feasible_clips, stats.sweep_early_outs);
}

TEST(BroadphaseBruteForce, RandomSceneFrames) {
  const Scene scene = random_scene(7);
  compare_frames(scene, test::build_world(scene), 11, 100000);
}

TEST(BroadphaseBruteForce, RandomSceneFramesOtherGrids) {
  // Odd cell sizes and fast radii, so the wide-disc path and cell boundaries get exercised.
  const Scene scene = random_scene(8);
  for (float cell : {0.37f, 1.3f}) {
    for (float fast : {0.0f, 0.25f, 0.9f}) {
      SCOPED_TRACE(testing::Message() << "cell " << cell << " fast radius " << fast);
      CollisionWorldConfig config;
      config.cell_m = cell;
      config.fast_radius_m = fast;
      config.ground_tolerance_m = 0.2f;
      compare_frames(scene, test::build_world(scene, config), 12, 20000);
    }
  }
}

TEST(BroadphaseBruteForce, RandomSceneSegments) {
  const Scene scene = random_scene(9);
  compare_segments(scene, test::build_world(scene), 13, 20000);
}

TEST(BroadphaseBruteForce, OpenSceneSegmentsUseTheEarlyOut) {
  // Few boxes and a small field: the early-out decides many clips and must agree.
  Scene scene = random_scene(10);
  scene.boxes.resize(12);
  scene.terrain.height_field.count_x = 5;
  scene.terrain.height_field.count_z = 5;
  scene.terrain.height_field.heights_m.resize(25);
  scene.terrain.steps.resize(3);
  const CollisionWorld world = test::build_world(scene);
  compare_segments(scene, world, 14, 20000);
  CheckStats stats;
  Rng rng(15);
  const auto shapes = random_shapes(rng, kDefaultFrameOrder);
  for (int i = 0; i < 2000; ++i)
    segment_feasible(world, shapes[i % shapes.size()],
                     {{uniform(rng, -5.0f, 14.0f), uniform(rng, -2.0f, 11.0f)}, uniform(rng, -3.0f, 3.0f)},
                     &stats);
  EXPECT_GT(stats.sweep_early_outs, 100u);
}

TEST(BroadphaseBruteForce, BuiltinScenes) {
  std::uint64_t seed = 20;
  for (const char* name : {"maze", "obstacles", "terrain", "arena"}) {
    SCOPED_TRACE(name);
    const Scene scene = test::load_builtin_scene(name);
    const CollisionWorld world = test::build_world(scene);
    compare_frames(scene, world, ++seed, 25000);
    compare_segments(scene, world, ++seed, 5000);
  }
}

TEST(BroadphaseBruteForce, GroundQueriesMatchTheTerrain) {
  const Scene scene = random_scene(16);
  const CollisionWorld world = test::build_world(scene);
  Rng rng(17);
  int holes = 0;
  for (int i = 0; i < 100000; ++i) {
    const vec2 p(uniform(rng, scene.bounds.min_m.x, scene.bounds.max_m.x),
                 uniform(rng, scene.bounds.min_m.y, scene.bounds.max_m.y));
    float a = -1.0f, b = -1.0f;
    const bool ha = terrain_height_at(scene.terrain, p, a);
    const bool hb = ground_height_at(world, p, b);
    ASSERT_EQ(ha, hb) << p.x << ", " << p.y;
    if (ha) {
      ASSERT_EQ(a, b) << p.x << ", " << p.y;
    }
    holes += !ha;
  }
  EXPECT_GT(holes, 100);
}

}  // namespace
}  // namespace foresight
