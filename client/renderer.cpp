#include "renderer.hpp"

#include "anim/canonical_skeleton.hpp"
#include "anim/fk.hpp"
#include "world/terrain.hpp"

#include <epoxy/gl.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <cmath>
#include <cstddef>

namespace foresight::client {

namespace {

constexpr const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in mat4 i_model;   // locations 2..5
layout(location = 6) in vec4 i_colour;
layout(location = 7) in float a_end;    // capsules: which end of the axis the vertex hangs off
uniform mat4 u_view_proj;
uniform int u_capsules;
out vec3 v_world;
out vec3 v_normal;
out vec3 v_local;
out vec4 v_colour;
void main() {
  mat3 shape = mat3(i_model);
  vec3 world;
  if (u_capsules != 0) {
    // A capsule (or ellipsoid): a_pos is on the unit sphere, scaled by the columns' radii and
    // moved along the axis (column 2) by half the length kept in column 3's w, so the caps stay
    // round whatever the length.
    world = i_model[3].xyz + normalize(i_model[2].xyz) * (i_model[3].w * a_end) + shape * a_pos;
  } else {
    world = (i_model * vec4(a_pos, 1.0)).xyz;
  }
  v_world = world;
  v_local = a_pos;
  // Scaled non-uniformly: normals need the inverse transpose.
  v_normal = normalize(transpose(inverse(shape)) * a_normal);
  v_colour = i_colour;
  gl_Position = u_view_proj * vec4(world, 1.0);
}
)";

constexpr const char* kFragmentShader = R"(#version 330 core
in vec3 v_world;
in vec3 v_normal;
in vec3 v_local;
in vec4 v_colour;
out vec4 o_colour;
void main() {
  if (v_colour.a > 4.5) {  // contact shadow, blended by multiplying: darkest at its centre
    float r = length(v_local.xz);
    o_colour = vec4(vec3(1.0 - v_colour.r * (1.0 - smoothstep(0.2, 1.0, r))), 1.0);
    return;
  }
  // One directional light plus ambient: faces at different angles get different brightness,
  // which is what makes depth readable.
  vec3 light = normalize(vec3(0.45, 1.0, 0.3));
  vec3 n = normalize(v_normal);
  float diffuse = max(dot(n, light), 0.0);
  // A weak fill from the opposite side keeps faces turned away from the sun from going black.
  float fill = max(dot(n, normalize(vec3(-0.45, 0.3, -0.3))), 0.0);
  vec3 c = v_colour.rgb * (0.35 + 0.6 * diffuse + 0.25 * fill);
  if (v_colour.a > 3.5) {  // ghost poses: a checkerboard of pixels left out reads as translucent
    ivec2 p = ivec2(gl_FragCoord.xy);
    if (((p.x + p.y) & 1) != 0) discard;
  } else if (v_colour.a > 2.5) {  // overlay lines: unlit, the exact colour from every side
    c = v_colour.rgb;
  } else if (v_colour.a > 1.5) {  // floor: 1 m grid lines
    vec2 f = abs(fract(v_world.xz) - 0.5);
    float line = 1.0 - smoothstep(0.47, 0.49, max(f.x, f.y));
    c *= mix(0.6, 1.0, line);
  }
  o_colour = vec4(c, 1.0);
}
)";

// A unit cube: 36 vertices of (position, normal).
void append_cube(std::vector<float>& v) {
  const float n[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const auto& face : n) {
    const vec3 normal(face[0], face[1], face[2]);
    // Two axes spanning the face, ordered so the winding is counter-clockwise seen from outside.
    const vec3 u = std::abs(normal.y) > 0.5f ? vec3(1, 0, 0) : vec3(0, 1, 0);
    const vec3 w = glm::cross(normal, u);
    const vec3 c = normal * 0.5f;
    const vec3 corners[4] = {c - 0.5f * u - 0.5f * w, c + 0.5f * u - 0.5f * w,
                             c + 0.5f * u + 0.5f * w, c - 0.5f * u + 0.5f * w};
    for (int i : {0, 1, 2, 0, 2, 3}) {
      v.insert(v.end(), {corners[i].x, corners[i].y, corners[i].z, normal.x, normal.y, normal.z});
    }
  }
}

// A capsule of unit radius around the z axis: two hemispheres (a_end -0.5 and +0.5) joined by
// a cylinder. Vertices of (position = normal on the unit sphere, end); counter-clockwise outside.
void append_capsule(std::vector<float>& v) {
  constexpr int kSlices = 10, kRingsPerCap = 3;  // 420 vertices: Mesa's software GL draws a crowd at 60 fps
  struct Ring {
    float lat, end;
  };
  std::vector<Ring> rings;
  for (int k = 0; k <= kRingsPerCap; ++k) rings.push_back({-kPi / 2 + kPi / 2 * k / kRingsPerCap, -0.5f});
  for (int k = 0; k <= kRingsPerCap; ++k) rings.push_back({kPi / 2 * k / kRingsPerCap, 0.5f});
  const auto vertex = [&](const Ring& r, int slice) {
    const float lon = 2.0f * kPi * static_cast<float>(slice) / kSlices;
    const vec3 p(std::cos(r.lat) * std::cos(lon), std::cos(r.lat) * std::sin(lon), std::sin(r.lat));
    v.insert(v.end(), {p.x, p.y, p.z, p.x, p.y, p.z, r.end});
  };
  for (size_t k = 0; k + 1 < rings.size(); ++k)
    for (int i = 0; i < kSlices; ++i) {
      vertex(rings[k], i), vertex(rings[k], i + 1), vertex(rings[k + 1], i + 1);
      vertex(rings[k], i), vertex(rings[k + 1], i + 1), vertex(rings[k + 1], i);
    }
}

// Radius of the limb ending at each canonical joint (metres, for the built-in 1.75 m body):
// a torso that narrows to the neck, a round head, thighs thicker than shins and arms.
constexpr float kLimbRadius_m[kCanonJointCount] = {
    0.0f,   0.11f,  0.12f,  0.13f,  0.05f,  0.06f,  0.105f,          // hips .. head top
    0.05f,  0.055f, 0.05f,  0.04f,  0.035f,                          // left arm
    0.05f,  0.055f, 0.05f,  0.04f,  0.035f,                          // right arm
    0.09f,  0.075f, 0.055f, 0.045f, 0.035f,                          // left leg
    0.09f,  0.075f, 0.055f, 0.045f, 0.035f};                         // right leg

glm::mat4 capsule_matrix(vec3 a, vec3 b, float radius_m) {
  glm::mat4 m = bone_matrix(a, b, radius_m);
  const float length = glm::length(b - a);
  m[2] = glm::vec4(glm::normalize(length > 1e-6f ? b - a : vec3(0, 1, 0)) * radius_m, 0);
  m[3].w = length;
  return m;
}

unsigned compile(unsigned type, const char* source, std::string& error) {
  const unsigned shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  int ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    error = std::string("shader compile failed: ") + log;
    glDeleteShader(shader);
    return 0;
  }
  return shader;
}

vec3 box_colour(BoxKind kind) {
  switch (kind) {
    case BoxKind::kWall: return {0.62f, 0.60f, 0.56f};
    case BoxKind::kObstacle: return {0.55f, 0.42f, 0.30f};
    case BoxKind::kBeam: return {0.45f, 0.35f, 0.55f};
    case BoxKind::kTable: return {0.50f, 0.36f, 0.22f};
    case BoxKind::kDoorwayLintel: return {0.52f, 0.50f, 0.46f};
    case BoxKind::kShelf: return {0.40f, 0.50f, 0.45f};
    case BoxKind::kProp: return {0.35f, 0.55f, 0.35f};
  }
  return {0.5f, 0.5f, 0.5f};
}

}  // namespace

glm::mat4 box_matrix(vec3 min_m, vec3 max_m) {
  glm::mat4 m = glm::translate(glm::mat4(1.0f), 0.5f * (min_m + max_m));
  return glm::scale(m, max_m - min_m);
}

glm::mat4 bone_matrix(vec3 a, vec3 b, float thickness_m) {
  const vec3 d = b - a;
  const float length = glm::length(d);
  const vec3 z = length > 1e-6f ? d / length : vec3(0, 1, 0);
  const vec3 helper = std::abs(z.y) < 0.9f ? vec3(0, 1, 0) : vec3(1, 0, 0);
  const vec3 x = glm::normalize(glm::cross(helper, z));
  const vec3 y = glm::cross(z, x);
  glm::mat4 m(1.0f);
  m[0] = glm::vec4(x * thickness_m, 0);
  m[1] = glm::vec4(y * thickness_m, 0);
  m[2] = glm::vec4(z * std::max(length, thickness_m), 0);
  m[3] = glm::vec4(0.5f * (a + b), 1);
  return m;
}

Renderer::~Renderer() {
  // Only when init() ran (a context existed); the context must still be current.
  if (program_) glDeleteProgram(program_);
  for (unsigned b : {cube_vbo_, capsule_vbo_, static_.vbo, dynamic_.vbo, limbs_.vbo, shadows_.vbo})
    if (b) glDeleteBuffers(1, &b);
  for (unsigned a : {static_.vao, dynamic_.vao, limbs_.vao, shadows_.vao})
    if (a) glDeleteVertexArrays(1, &a);
}

bool Renderer::init(std::string& error) {
  const unsigned vs = compile(GL_VERTEX_SHADER, kVertexShader, error);
  if (!vs) return false;
  const unsigned fs = compile(GL_FRAGMENT_SHADER, kFragmentShader, error);
  if (!fs) return false;
  program_ = glCreateProgram();
  glAttachShader(program_, vs);
  glAttachShader(program_, fs);
  glLinkProgram(program_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  int ok = 0;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetProgramInfoLog(program_, sizeof log, nullptr, log);
    error = std::string("shader link failed: ") + log;
    return false;
  }
  loc_view_proj_ = glGetUniformLocation(program_, "u_view_proj");
  loc_capsules_ = glGetUniformLocation(program_, "u_capsules");

  const auto upload_mesh = [](unsigned& vbo, const std::vector<float>& v) {
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(v.size() * sizeof(float)), v.data(), GL_STATIC_DRAW);
  };
  std::vector<float> mesh;
  append_cube(mesh);
  upload_mesh(cube_vbo_, mesh);
  mesh.clear();
  append_capsule(mesh);
  capsule_vertices_ = static_cast<int>(mesh.size() / 7);
  upload_mesh(capsule_vbo_, mesh);

  // One VAO per instance list: its mesh, and its own instance buffer.
  const auto make_vao = [](InstanceList& list, unsigned mesh_vbo, bool capsule) {
    const GLsizei stride = (capsule ? 7 : 6) * sizeof(float);
    glGenVertexArrays(1, &list.vao);
    glGenBuffers(1, &list.vbo);
    glBindVertexArray(list.vao);
    glBindBuffer(GL_ARRAY_BUFFER, mesh_vbo);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(3 * sizeof(float)));
    if (capsule) {
      glEnableVertexAttribArray(7);
      glVertexAttribPointer(7, 1, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(6 * sizeof(float)));
    }
    glBindBuffer(GL_ARRAY_BUFFER, list.vbo);
    // Per instance: the model matrix as 4 column attributes, then the colour.
    for (unsigned col = 0; col < 4; ++col) {
      glEnableVertexAttribArray(2 + col);
      glVertexAttribPointer(2 + col, 4, GL_FLOAT, GL_FALSE, sizeof(Instance),
                            reinterpret_cast<const void*>(offsetof(Instance, model) + col * sizeof(glm::vec4)));
      glVertexAttribDivisor(2 + col, 1);
    }
    glEnableVertexAttribArray(6);
    glVertexAttribPointer(6, 4, GL_FLOAT, GL_FALSE, sizeof(Instance),
                          reinterpret_cast<const void*>(offsetof(Instance, colour)));
    glVertexAttribDivisor(6, 1);
  };
  make_vao(static_, cube_vbo_, false);
  make_vao(dynamic_, cube_vbo_, false);
  make_vao(limbs_, capsule_vbo_, true);
  make_vao(shadows_, capsule_vbo_, true);
  glBindVertexArray(0);
  dynamic_.instances.reserve(1024);
  limbs_.instances.reserve(4096);
  shadows_.instances.reserve(512);
  return true;
}

void Renderer::set_scene(const Scene& scene) {
  terrain_ = scene.terrain;
  std::vector<Instance>& static_boxes = static_.instances;
  static_boxes.clear();
  const float floor_y = scene.terrain.floor_y_m;
  static_boxes.push_back({box_matrix(from_ground(scene.bounds.min_m, floor_y - 0.05f),
                                from_ground(scene.bounds.max_m, floor_y)),
                     glm::vec4(0.78f, 0.80f, 0.82f, 2.0f)});
  for (const SceneBox& b : scene.boxes)
    static_boxes.push_back({box_matrix(b.min_m, b.max_m), glm::vec4(box_colour(b.kind), 1.0f)});
  for (const StepBlock& s : scene.terrain.steps)
    static_boxes.push_back({box_matrix(s.min_m, s.max_m), glm::vec4(0.60f, 0.62f, 0.50f, 1.0f)});
  const HeightField& hf = scene.terrain.height_field;
  for (int iz = 0; iz < hf.count_z; ++iz) {
    for (int ix = 0; ix < hf.count_x; ++ix) {
      const float h = hf.heights_m[static_cast<size_t>(iz * hf.count_x + ix)];
      const vec2 lo = hf.origin_m + hf.cell_m * vec2(static_cast<float>(ix), static_cast<float>(iz));
      if (std::isnan(h)) {  // a hole: a dark pit over the floor plane (which lies under everything)
        static_boxes.push_back({box_matrix(from_ground(lo, floor_y - 0.05f), from_ground(lo + vec2(hf.cell_m), floor_y + 0.002f)),
                           glm::vec4(0.08f, 0.08f, 0.10f, 1.0f)});
        continue;
      }
      static_boxes.push_back({box_matrix(from_ground(lo, std::min(h, floor_y) - 0.06f),
                                    from_ground(lo + vec2(hf.cell_m), h)),
                         glm::vec4(0.70f, 0.72f, 0.64f, 2.0f)});
    }
  }
  static_dirty_ = true;
}

void Renderer::begin_frame() {
  dynamic_.instances.clear();
  limbs_.instances.clear();
  shadows_.instances.clear();
}

void Renderer::add_bones(std::span<const int16_t> parents, std::span<const vec3> global_pos_m, glm::vec4 colour,
                         float scale) {
  if (global_pos_m.empty()) return;
  const bool canonical = parents.size() == kCanonJointCount && global_pos_m.size() == kCanonJointCount;
  for (size_t j = 1; j < parents.size() && j < global_pos_m.size(); ++j) {
    const vec3 a = global_pos_m[static_cast<size_t>(parents[j])], b = global_pos_m[j];
    if (glm::length(b - a) < 0.01f) continue;
    limbs_.instances.push_back({capsule_matrix(a, b, scale * (canonical ? kLimbRadius_m[j] : 0.045f)), colour});
  }
  if (canonical && colour.w < 1.5f) {  // solid avatars cast contact shadows; ghosts do not
    add_foot_shadow(global_pos_m[kCanonLeftFoot], global_pos_m[kCanonLeftToeEnd], scale);
    add_foot_shadow(global_pos_m[kCanonRightFoot], global_pos_m[kCanonRightToeEnd], scale);
  }
}

// A soft dark ellipse on the ground under a foot, darkest while the sole is on the ground and
// fading out as the foot lifts (gone at 0.3 m): where the feet are planted reads at a glance.
void Renderer::add_foot_shadow(vec3 ankle, vec3 toe_end, float scale) {
  const vec3 mid = 0.5f * (ankle + toe_end);
  float ground_y = terrain_.floor_y_m;
  if (!terrain_height_at(terrain_, ground(mid), ground_y)) return;  // over a hole: no ground to shade
  const float sole = std::min(ankle.y - kRestAnkleHeightM * scale, toe_end.y) - ground_y;
  const float strength = 0.7f * std::clamp(1.0f - sole / 0.3f, 0.0f, 1.0f);
  if (strength < 0.01f) return;
  const vec2 d = ground(toe_end - ankle);
  const float length = glm::length(d);
  const vec2 along = length > 1e-4f ? d / length : vec2(0.0f, 1.0f);
  glm::mat4 m(1.0f);
  m[0] = glm::vec4(vec3(along.y, 0.0f, -along.x) * (0.085f * scale), 0.0f);  // across the foot
  m[1] = glm::vec4(0.0f, 0.002f, 0.0f, 0.0f);                                 // flat
  m[2] = glm::vec4(vec3(along.x, 0.0f, along.y) * (0.5f * length + 0.09f * scale), 0.0f);
  m[3] = glm::vec4(mid.x, ground_y + 0.004f, mid.z, 0.0f);                   // an ellipsoid: no length
  shadows_.instances.push_back({m, glm::vec4(strength, 0.0f, 0.0f, 5.0f)});
}

void Renderer::add_skeleton(std::span<const int16_t> parents, std::span<const vec3> global_pos_m, vec3 colour,
                            float scale) {
  add_bones(parents, global_pos_m, glm::vec4(colour, 1.0f), scale);
}

void Renderer::add_marker(vec3 centre, float size_m, vec3 colour) {
  if (size_m <= 0.0f) return;
  dynamic_.instances.push_back({box_matrix(centre - vec3(0.5f * size_m), centre + vec3(0.5f * size_m)), glm::vec4(colour, 3.0f)});
}

void Renderer::add_avatar(const MotionLibrary& library, const PlaybackState& state, float frame_alpha,
                          vec3 colour, AvatarStyle style) {
  const glm::vec4 c(colour, style == AvatarStyle::kGhost ? 4.0f : 1.0f);
  playback_pose(library, state, pose_);
  if (frame_alpha <= 0.0f) {
    add_avatar(library, pose_, c);
    return;
  }
  PlaybackState next = state;
  next.frame += 1;
  playback_pose(library, next, next_pose_);
  add_avatar(library, pose_, next_pose_, frame_alpha, c);
}

void Renderer::add_avatar(const MotionLibrary& library, const Pose& pose, glm::vec4 colour) {
  const auto n = static_cast<size_t>(library.num_joints());
  global_pos_.resize(n);  // no-op once sized
  global_rot_.resize(n);
  fk_pose(library.skeleton, pose.local_pos_m, pose.local_rot, global_pos_, global_rot_);
  add_bones(library.skeleton.parents, global_pos_, colour, 1.0f);
}

void Renderer::add_avatar(const MotionLibrary& library, const Pose& pose, const Pose& next,
                          float alpha, glm::vec4 colour) {
  const auto n = static_cast<size_t>(library.num_joints());
  global_pos_.resize(n);
  global_pos_next_.resize(n);
  global_rot_.resize(n);
  fk_pose(library.skeleton, next.local_pos_m, next.local_rot, global_pos_next_, global_rot_);
  fk_pose(library.skeleton, pose.local_pos_m, pose.local_rot, global_pos_, global_rot_);
  for (size_t j = 0; j < n; ++j) global_pos_[j] += alpha * (global_pos_next_[j] - global_pos_[j]);
  add_bones(library.skeleton.parents, global_pos_, colour, 1.0f);
}

void Renderer::add_line(vec3 a, vec3 b, float thickness_m, vec3 colour) {
  if (glm::length(b - a) < 1e-3f) return;
  dynamic_.instances.push_back({bone_matrix(a, b, thickness_m), glm::vec4(colour, 3.0f)});
}

void Renderer::upload_and_draw(InstanceList& list, int vertices) {
  if (list.instances.empty()) return;
  glBindBuffer(GL_ARRAY_BUFFER, list.vbo);
  const auto bytes = static_cast<GLsizeiptr>(list.instances.size() * sizeof(Instance));
  if (list.instances.size() > list.capacity) {
    list.capacity = list.instances.capacity();
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(list.capacity * sizeof(Instance)), nullptr, GL_DYNAMIC_DRAW);
  }
  glBufferSubData(GL_ARRAY_BUFFER, 0, bytes, list.instances.data());
  glBindVertexArray(list.vao);
  glDrawArraysInstanced(GL_TRIANGLES, 0, vertices, static_cast<GLsizei>(list.instances.size()));
}

void Renderer::draw(int width, int height, const glm::mat4& view, const glm::mat4& projection) {
  glViewport(0, 0, width, height);
  glClearColor(0.55f, 0.68f, 0.82f, 1.0f);  // sky
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_CULL_FACE);
  glUseProgram(program_);
  const glm::mat4 view_proj = projection * view;
  glUniformMatrix4fv(loc_view_proj_, 1, GL_FALSE, glm::value_ptr(view_proj));
  glUniform1i(loc_capsules_, 0);
  if (static_dirty_) {
    // Static instances go up once per scene; a zero capacity forces the (re)allocation.
    static_.capacity = 0;
    static_dirty_ = false;
    upload_and_draw(static_, 36);
  } else if (!static_.instances.empty()) {
    glBindVertexArray(static_.vao);
    glDrawArraysInstanced(GL_TRIANGLES, 0, 36, static_cast<GLsizei>(static_.instances.size()));
  }
  upload_and_draw(dynamic_, 36);
  glUniform1i(loc_capsules_, 1);
  // Contact shadows darken what is under them (multiplied in, so their order does not matter),
  // over the ground and under the avatars drawn next.
  glEnable(GL_BLEND);
  glBlendFunc(GL_DST_COLOR, GL_ZERO);
  glDepthMask(GL_FALSE);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(-1.0f, -1.0f);
  upload_and_draw(shadows_, capsule_vertices_);
  glDisable(GL_POLYGON_OFFSET_FILL);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  upload_and_draw(limbs_, capsule_vertices_);
  glBindVertexArray(0);
}

}  // namespace foresight::client
