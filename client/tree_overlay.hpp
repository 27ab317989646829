#pragma once
// The tree overlay (key T, paper Fig. 5): the newest TreeSummary of the player's own feasible
// motion tree, drawn as root paths (a line from each sampled node's parent's end to its own end)
// with the chosen branch highlighted, plus ghost poses of the chosen branch's clips, rebuilt
// from the client's own library (the summary carries each node's segment and start heading).
#include "renderer.hpp"

#include "library/motion_library.hpp"
#include "library/playback.hpp"
#include "transport/client_connection.hpp"

#include <vector>

namespace foresight::client {

inline constexpr vec3 kTreeColour{0.10f, 0.85f, 0.85f};    ///< Cyan: the sampled tree.
inline constexpr vec3 kChosenColour{1.00f, 0.95f, 0.10f};  ///< Yellow: the branch taken now.
/// Pale yellow, lit, screen-door translucent (AvatarStyle::kGhost): the chosen branch's poses.
inline constexpr vec3 kGhostColour{1.00f, 0.90f, 0.55f};
/// Ghosts per chosen node: the middle and the last frame of its clip (fewer for 1-2 frame clips).
inline constexpr int kGhostFramesPerNode = 2;

/// The ghost poses of `tree`'s chosen branch (its nodes below the root: the root plays now and
/// the avatar itself shows it) as playback states of `library`, in branch order, written over
/// `out` (reserve it for kMaxTreeSamples * kGhostFramesPerNode and nothing is allocated). Nodes
/// whose segment `library` does not have are left out; each is entered by the graph transition
/// from its parent's segment (-1 when there is none: drawn without the entry blend).
void tree_ghost_states(const MotionLibrary& library, const protocol::TreeView& tree,
                       std::vector<PlaybackState>& out);

/// Adds the overlay to the renderer's frame: every sampled node's line (cyan; the chosen branch
/// yellow, thicker, a square outline around each of its ends, drawn after the rest so it wins
/// where they overlap), `floor_y_m` + a few cm up, then the ghost poses. `ghosts` is scratch.
void add_tree_overlay(Renderer& renderer, const MotionLibrary& library, const protocol::TreeView& tree,
                      float floor_y_m, std::vector<PlaybackState>& ghosts);

}  // namespace foresight::client
