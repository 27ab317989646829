#include "fighter_build/fighter_database_build.hpp"

#include "author/default_library.hpp"
#include "import/bvh_import.hpp"
#include "anim/fk.hpp"
#include "anim/root_motion.hpp"

#include <algorithm>
#include <random>
#include <system_error>

namespace foresight {
namespace {

// Height classes as shares of the actor's body size (leg + trunk bone lengths, ~0.85 of the
// standing height), measured from the take's floor: the default library's low strikes land at
// 0.37-0.46, mid at 0.72-0.77, high at 0.97-1.02; a boundary sits between each pair.
constexpr float kLowBelow = 0.58f;
constexpr float kHighFrom = 0.86f;

void grow_box(const vec3& p, vec3& lo, vec3& hi) {
  lo = glm::min(lo, p);
  hi = glm::max(hi, p);
}

void compute_box(FighterEntry& e) {
  e.hit_box_min_m = e.hit_box_max_m = e.hit_path_m.front();
  for (const vec3& p : e.hit_path_m) grow_box(p, e.hit_box_min_m, e.hit_box_max_m);
}

// Lowest ankle over the take: the floor the actor stands on (Bandai feet sit 5-12 cm above 0).
float take_floor_y(const TakeMotionView& m) {
  float y = m.pos(0, m.rig->leg[0].end).y;
  for (int f = 0; f < m.num_frames; ++f)
    for (const FighterLimb& leg : m.rig->leg) y = std::min(y, m.pos(f, leg.end).y);
  return y;
}

FighterEntry make_entry(const TakeMotionView& m, const StrikeMark& mark, int hit_joint, float floor_y) {
  FighterEntry e;
  e.hit_joint = hit_joint;
  e.kind = mark.kind;
  e.side = mark.side;
  e.start_frame = mark.start_frame;
  e.hit_frame = mark.hit_frame;
  e.end_frame = mark.end_frame;
  e.body_size_m = m.rig->body_size_m;
  const int n = e.num_frames();
  e.key_points.resize(static_cast<std::size_t>(n) * kPoseKeyPoints);
  e.root_from_start_m.resize(static_cast<std::size_t>(n));
  e.hit_path_m.resize(static_cast<std::size_t>(n));
  const Placement start_inv = m.root_track[static_cast<std::size_t>(e.start_frame)].inverse();
  const float inv_size = 1.0f / e.body_size_m;
  for (int i = 0; i < n; ++i) {
    const int f = e.start_frame + i;
    const Placement& root = m.root_track[static_cast<std::size_t>(f)];
    const std::span<const vec3> frame_pos =
        m.global_pos_m.subspan(static_cast<std::size_t>(f) * static_cast<std::size_t>(m.num_joints),
                               static_cast<std::size_t>(m.num_joints));
    const std::span<vec3, kPoseKeyPoints> kp(e.key_points.data() + static_cast<std::size_t>(i) * kPoseKeyPoints,
                                            kPoseKeyPoints);
    fighter_key_points_m(*m.rig, frame_pos, root, kp);
    for (vec3& p : kp) p *= inv_size;
    e.root_from_start_m[static_cast<std::size_t>(i)] = start_inv.compose(root);
    e.hit_path_m[static_cast<std::size_t>(i)] = start_inv.apply(m.pos(f, hit_joint));
  }
  compute_box(e);
  e.height = mark.height ? *mark.height
                         : strike_height_from_hit(m.pos(e.hit_frame, hit_joint).y - floor_y, e.body_size_m);
  return e;
}

double unit(std::mt19937_64& rng) {
  // Not std::uniform_real_distribution: its output differs between standard libraries, and the
  // synthetic database must be the same everywhere.
  return static_cast<double>(rng() >> 11) * (1.0 / 9007199254740992.0);
}
float symmetric(std::mt19937_64& rng, float half_width) {
  return static_cast<float>((2.0 * unit(rng) - 1.0) * half_width);
}

}  // namespace

StrikeHeight strike_height_from_hit(float hit_height_m, float body_size_m) {
  const float r = hit_height_m / body_size_m;
  if (r < kLowBelow) return StrikeHeight::kLow;
  if (r >= kHighFrom) return StrikeHeight::kHigh;
  return StrikeHeight::kMid;
}

bool fighter_database_add_take(FighterDatabase& db, FighterTake take, const std::vector<StrikeMark>& marks,
                               const StrikeSplitParams& split, std::string& error) {
  std::vector<vec3> global;
  fk_clip_positions(take.skeleton, take.clip, global);
  std::vector<Placement> track;
  extract_root_track(take.clip, find_forward_axis(take.skeleton, take.clip), track);
  TakeMotionView m;
  m.rig = &take.rig;
  m.global_pos_m = global;
  m.root_track = track;
  m.num_joints = take.clip.num_joints;
  m.num_frames = take.clip.num_frames;
  m.fps = take.clip.fps;
  if (m.num_frames < 2) {
    error = take.source + ": the take has fewer than 2 frames";
    return false;
  }

  std::vector<StrikeMark> resolved = marks;
  if (resolved.empty()) {
    for (const DetectedStrike& d : strike_detect(m, split)) {
      StrikeMark mark;
      mark.hit_joint = take.skeleton.joint_names[static_cast<std::size_t>(d.hit_joint)];
      mark.kind = d.kind;
      mark.side = d.side;
      mark.hit_frame = d.hit_frame;
      mark.start_frame = d.start_frame;
      mark.end_frame = d.end_frame;
      resolved.push_back(mark);
    }
  }
  const float floor_y = take_floor_y(m);
  const int take_index = static_cast<int>(db.takes.size());
  std::vector<FighterEntry> added;
  for (StrikeMark& mark : resolved) {
    const int joint = take.skeleton.find_joint(mark.hit_joint);
    if (joint < 0 || mark.hit_frame >= m.num_frames) {
      error = take.source + ": strike at frame " + std::to_string(mark.hit_frame) + " on \"" + mark.hit_joint +
              "\" does not fit the take (check the marks with strike_marks_check first)";
      return false;
    }
    strike_window(m, joint, mark.hit_frame, split, mark.start_frame, mark.end_frame);
    FighterEntry e = make_entry(m, mark, joint, floor_y);
    e.take = take_index;
    e.name = resolved.size() > 1 ? take.name + "#" + std::to_string(added.size()) : take.name;
    added.push_back(std::move(e));
  }
  db.takes.push_back(std::move(take));
  for (FighterEntry& e : added) db.entries.push_back(std::move(e));
  return true;
}

bool fighter_database_add_default_library(FighterDatabase& db, std::string& error) {
  author::DefaultLibrarySpec lib = author::build_default_library();
  FighterRig rig;
  if (!fighter_rig_from_skeleton(lib.skeleton, rig, error)) return false;
  for (author::AuthoredClip& c : lib.clips) {
    if (!c.strike) continue;
    const author::StrikeAnnotation& a = *c.strike;
    StrikeMark mark;
    mark.hit_joint = lib.skeleton.joint_names[static_cast<std::size_t>(a.hit_joint)];
    if (!strike_kind_parse(a.kind, mark.kind) || !strike_side_parse(a.side, mark.side)) {
      error = "default library: " + c.clip.name + ": unknown strike kind or side";
      return false;
    }
    StrikeHeight h{};
    if (strike_height_parse(a.height, h)) mark.height = h;
    mark.hit_frame = a.hit_frame;
    // An authored strike is the whole clip: it starts and ends in the guard stance.
    mark.start_frame = 0;
    mark.end_frame = c.clip.num_frames - 1;
    FighterTake take;
    take.name = c.clip.name;
    take.source = "default library";
    take.skeleton = lib.skeleton;
    take.rig = rig;
    take.clip = std::move(c.clip);
    if (!fighter_database_add_take(db, std::move(take), {mark}, StrikeSplitParams{}, error)) return false;
  }
  return true;
}

bool fighter_database_add_folder(FighterDatabase& db, const std::filesystem::path& folder,
                                 const std::filesystem::path& sidecar_path, const StrikeSplitParams& split,
                                 FolderLoadReport* report, std::string& error) {
  namespace fs = std::filesystem;
  FolderLoadReport local;
  FolderLoadReport& rep = report != nullptr ? *report : local;
  rep = FolderLoadReport{};
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) {
    error = folder.string() + ": not a folder";
    return false;
  }
  StrikeSidecar sidecar;
  fs::path used = sidecar_path.empty() ? folder / "strikes.json" : sidecar_path;
  if (!sidecar_path.empty() || fs::exists(used, ec)) {
    if (!strike_sidecar_load(used, sidecar, error)) return false;
    rep.sidecar = used.string();
  }
  std::vector<fs::path> files;
  for (const fs::directory_entry& d : fs::directory_iterator(folder, ec))
    if (d.is_regular_file(ec) && d.path().extension() == ".bvh") files.push_back(d.path());
  if (ec) {
    error = folder.string() + ": cannot list: " + ec.message();
    return false;
  }
  std::sort(files.begin(), files.end());

  for (const fs::path& file : files) {
    const std::string clip_name = file.filename().string();
    ClipStrikes marks;
    std::string marks_source = rep.sidecar;
    fs::path own = file;
    own.replace_extension(".strikes.json");
    if (fs::exists(own, ec)) {
      if (!strike_clip_sidecar_load(own, clip_name, marks, error)) return false;
      marks_source = own.string();
    } else if (const ClipStrikes* c = sidecar.find(clip_name)) {
      marks = *c;
    }
    if (marks.skip) {
      ++rep.takes_skipped;
      continue;
    }
    FighterTake take;
    take.name = file.stem().string();
    take.source = file.string();
    // On the canonical skeleton, so a capture of any naming or hierarchy gives the rig its joints;
    // marks name the capture's joints and are carried over to their canonical twins.
    BvhImportOptions import;
    import.canonical = true;
    BvhImportReport imported;
    if (!clip_load_bvh(file, import, take.skeleton, take.clip, &imported, error)) return false;
    for (StrikeMark& m : marks.strikes) {
      if (take.skeleton.find_joint(m.hit_joint) >= 0) continue;
      const auto it = std::find(imported.source_joints.begin(), imported.source_joints.end(), m.hit_joint);
      const int canonical = it == imported.source_joints.end() ? -1 : imported.canonical_joint[static_cast<std::size_t>(it - imported.source_joints.begin())];
      if (canonical >= 0) m.hit_joint = take.skeleton.joint_names[static_cast<std::size_t>(canonical)];
    }
    std::string rig_error;
    if (!fighter_rig_from_skeleton(take.skeleton, take.rig, rig_error)) {
      error = file.string() + ": " + rig_error;
      return false;
    }
    if (!strike_marks_check(marks, take.skeleton, take.clip.num_frames, marks_source, error)) return false;
    const std::size_t before = db.entries.size();
    if (!fighter_database_add_take(db, std::move(take), marks.strikes, split, error)) return false;
    ++rep.takes_loaded;
    const int added = static_cast<int>(db.entries.size() - before);
    (marks.strikes.empty() ? rep.strikes_detected : rep.strikes_annotated) += added;
  }
  return true;
}

ClipStrikes fighter_database_marks(const FighterDatabase& db, int take) {
  ClipStrikes out;
  const FighterTake& t = db.takes[static_cast<std::size_t>(take)];
  out.clip = std::filesystem::path(t.source).filename().string();
  for (const FighterEntry& e : db.entries) {
    if (e.take != take) continue;
    StrikeMark m;
    m.hit_joint = t.skeleton.joint_names[static_cast<std::size_t>(e.hit_joint)];
    m.kind = e.kind;
    m.side = e.side;
    m.height = e.height;
    m.hit_frame = e.hit_frame;
    m.start_frame = e.start_frame;
    m.end_frame = e.end_frame;
    out.strikes.push_back(m);
  }
  return out;
}

FighterDatabase fighter_database_synthetic(const FighterDatabase& seed_db, int num_entries, std::uint64_t seed) {
  FighterDatabase out;
  out.takes = seed_db.takes;
  if (seed_db.entries.empty() || num_entries <= 0) return out;
  std::mt19937_64 rng(seed);
  out.entries.reserve(static_cast<std::size_t>(num_entries));
  for (int i = 0; i < num_entries; ++i) {
    const FighterEntry& src = seed_db.entries[static_cast<std::size_t>(i) % seed_db.entries.size()];
    FighterEntry e;
    e.name = src.name + "~" + std::to_string(i);
    e.take = src.take;
    e.hit_joint = src.hit_joint;
    e.kind = src.kind;
    e.side = src.side;
    e.height = src.height;
    // A later start: up to half the approach is cut, as if the actor began the strike closer.
    const int trim = static_cast<int>(unit(rng) * 0.5 * (src.hit_frame - src.start_frame));
    e.start_frame = src.start_frame + trim;
    e.hit_frame = src.hit_frame;
    e.end_frame = src.end_frame;
    const float scale = 1.0f + symmetric(rng, 0.12f);  // Another actor's size.
    e.body_size_m = src.body_size_m * scale;
    const Placement turn{vec2(symmetric(rng, 0.05f), symmetric(rng, 0.05f)) * scale, symmetric(rng, radians(12.0f))};
    const float lift = symmetric(rng, 0.06f) * scale;
    const Placement new_start_inv = src.root_from_start_m[static_cast<std::size_t>(trim)].inverse();
    const int n = e.num_frames();
    e.key_points.assign(src.key_points.begin() + static_cast<std::ptrdiff_t>(trim) * kPoseKeyPoints, src.key_points.end());
    for (vec3& p : e.key_points) p += vec3(symmetric(rng, 0.01f), symmetric(rng, 0.01f), symmetric(rng, 0.01f));
    e.root_from_start_m.resize(static_cast<std::size_t>(n));
    e.hit_path_m.resize(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) {
      const std::size_t s = static_cast<std::size_t>(trim + k);
      Placement r = new_start_inv.compose(src.root_from_start_m[s]);
      r.pos_m *= scale;
      e.root_from_start_m[static_cast<std::size_t>(k)] = r;
      const vec3 p = new_start_inv.apply(src.hit_path_m[s]) * scale;
      e.hit_path_m[static_cast<std::size_t>(k)] = turn.apply(p) + vec3(0.0f, lift, 0.0f);
    }
    compute_box(e);
    out.entries.push_back(std::move(e));
  }
  return out;
}

}  // namespace foresight
