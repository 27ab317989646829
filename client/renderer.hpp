#pragma once
// Draws the world with OpenGL 3.3 core (through libepoxy), instanced: the scene, markers and
// overlay lines are shaded unit cubes, avatars' limbs lit capsules (round caps whatever the length:
// the vertex shader moves each cap along the bone), and under every foot a soft contact shadow
// multiplied into the ground, darkest while the foot is planted. Four draw calls a frame whatever
// the number of avatars. The floor carries a grid drawn in the fragment shader.
// Needs a current GL context for every call but the constructor.
#include "library/motion_library.hpp"
#include "library/playback.hpp"
#include "world/scene.hpp"

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include <span>
#include <string>
#include <vector>

namespace foresight::client {

/// How an avatar's bones are drawn: solid, or as a ghost (the tree overlay's poses of clips the
/// avatar may play next): lit, but every other pixel left out (screen-door translucency, so
/// nothing needs sorting and the pass stays one draw call).
enum class AvatarStyle { kSolid, kGhost };

class Renderer {
 public:
  Renderer() = default;
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Compiles the shaders and creates the buffers. False with a reason.
  bool init(std::string& error);
  /// Rebuilds the static instances (floor, boxes, steps, height field) for `scene`.
  void set_scene(const Scene& scene);

  /// Starts a frame's dynamic instances (avatars).
  void begin_frame();
  /// Adds one avatar as the interpolation buffer shows it: the pose of `state` (a box per bone,
  /// FK), its joints lerped `frame_alpha` of the way to the next frame's (fractional frames).
  void add_avatar(const MotionLibrary& library, const PlaybackState& state, float frame_alpha, vec3 colour,
                  AvatarStyle style = AvatarStyle::kSolid);
  /// Adds a skeleton already posed in world space (the pose stage's output, NPC fighters on their
  /// own morphology's skeleton): a capsule per bone from parent to child (limb radii of the
  /// canonical skeleton: torso, head, thighs, shins, arms) and a contact shadow under each foot
  /// on the scene's ground; `scale` multiplies the radii (smaller characters, thinner limbs).
  void add_skeleton(std::span<const int16_t> parents, std::span<const vec3> global_pos_m, vec3 colour,
                    float scale = 1.0f);
  /// Adds an unlit cube of side `size_m` centred on `centre` (strike markers).
  void add_marker(vec3 centre, float size_m, vec3 colour);
  /// Adds an overlay line from `a` to `b`: a thin unlit box (the exact `colour` from every side,
  /// so overlays read on any background).
  void add_line(vec3 a, vec3 b, float thickness_m, vec3 colour);
  /// Clears the viewport (width x height pixels) and draws the scene and the frame's avatars.
  void draw(int width, int height, const glm::mat4& view, const glm::mat4& projection);

  /// Limbs, markers and lines added this frame.
  size_t avatar_instances() const { return limbs_.instances.size() + dynamic_.instances.size(); }
  size_t shadow_instances() const { return shadows_.instances.size(); }

 private:
  struct Instance {
    /// Boxes: the affine model matrix. Capsules: columns 0-2 the radii's axes (2: along the
    /// bone), column 3 the centre with the length in w.
    glm::mat4 model;
    /// a = 1: plain; a = 2: floor grid; a = 3: unlit (overlay lines); a = 4: ghost (screen door);
    /// a = 5: contact shadow (r: its strength).
    glm::vec4 colour;
  };
  /// One instanced draw: its instances and the GPU objects they go up in.
  struct InstanceList {
    std::vector<Instance> instances;
    unsigned vao = 0, vbo = 0;
    size_t capacity = 0;  ///< Instances the GPU buffer holds.
  };
  void add_bones(std::span<const int16_t> parents, std::span<const vec3> global_pos_m, glm::vec4 colour,
                 float scale);
  void add_avatar(const MotionLibrary& library, const Pose& pose, glm::vec4 colour);
  void add_avatar(const MotionLibrary& library, const Pose& pose, const Pose& next, float alpha,
                  glm::vec4 colour);
  void add_foot_shadow(vec3 ankle, vec3 toe_end, float scale);
  void upload_and_draw(InstanceList& list, int vertices);

  unsigned program_ = 0;
  int loc_view_proj_ = -1, loc_capsules_ = -1;
  unsigned cube_vbo_ = 0, capsule_vbo_ = 0;
  int capsule_vertices_ = 0;
  bool static_dirty_ = false;
  InstanceList static_;   ///< The scene (boxes), uploaded once per scene.
  InstanceList dynamic_;  ///< Markers and overlay lines (boxes).
  InstanceList limbs_;    ///< Avatars' limbs (capsules).
  InstanceList shadows_;  ///< Contact shadows (flat ellipsoids, multiplied in).
  Terrain terrain_;       ///< The scene's ground, for the shadows.
  // FK scratch, sized once per library (no allocation per frame).
  std::vector<vec3> global_pos_, global_pos_next_;
  std::vector<quat> global_rot_;
  Pose pose_, next_pose_;  ///< Sampled poses (sized by playback_pose once).
};

/// Model matrix of a unit cube (centred, side 1) stretched into the axis-aligned box [min, max].
glm::mat4 box_matrix(vec3 min_m, vec3 max_m);
/// Model matrix of a bone from `a` to `b` with the given thickness (identity-free: any direction).
glm::mat4 bone_matrix(vec3 a, vec3 b, float thickness_m);

}  // namespace foresight::client
