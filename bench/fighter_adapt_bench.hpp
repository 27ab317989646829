#pragma once
// The adaptation benchmark (paper 3.4.2: 88 us / 515 us / 1240 us per frame on a 2006 PC for the
// limb alone / limb + clavicle + torso / unreachable): every default strike on every morphology,
// adapted to seeded random targets around where the retargeted strike would land, each frame timed.
//
// Targets: the hit-frame limb root R and limb length L of the retargeted (unadapted) strike give
// three classes, drawn in turn: "limb" targets within 0.97 L of R (the limb alone reaches them),
// "torso" targets between L and L + 0.12 m (punches lean the torso in, kicks tilt the pelvis), and
// "far" targets 0.5-1.5 m beyond reach. Reach error = |effector - target| at the hit frame; the
// reachable figures are over the limb and torso classes.
// Foot skate: the support foot's contact joint (ball of the foot; kicks: the standing leg,
// punches: the rear foot) path length over the strike divided by its duration, averaged.
#include <cstdint>
#include <string>

namespace foresight::bench {

struct FighterAdaptBenchOptions {
  int strikes_per_case = 12;  ///< Targets per (strike, morphology) pair; 16 strikes x 5 morphologies.
  std::uint64_t seed = 1;
};

struct FighterAdaptBenchResult {
  std::string error;  ///< Non-empty when the fighters' limb models could not be built.
  double adapt_us_per_frame_p50 = 0.0, adapt_us_per_frame_p99 = 0.0;  ///< Every frame, all classes.
  double limb_us_per_frame_p50 = 0.0;     ///< Frames the limb alone solved.
  double torso_us_per_frame_p50 = 0.0, torso_us_per_frame_p99 = 0.0;  ///< Frames that ran CCD.
  double reach_error_cm_p50 = 0.0, reach_error_cm_p99 = 0.0;  ///< Reachable targets (limb + torso).
  double reach_error_torso_cm_p99 = 0.0;  ///< The torso class alone.
  double foot_skate_cm_per_s = 0.0;       ///< Support-foot drift speed, averaged over strikes.
  double foot_drift_cm_max = 0.0;         ///< Largest support-foot distance from its first frame.
  int strikes = 0, frames = 0;
  int limb_targets = 0, torso_targets = 0, far_targets = 0;
  int torso_targets_missed = 0;           ///< Torso-class targets left more than 1 cm away ...
  int torso_kick_targets_missed = 0;      ///< ... of which kicks (the pelvis tilt reaches less).
  int non_finite = 0;                     ///< Frames with a NaN/inf anywhere (must be 0).
};

/// Deterministic targets for a seed; the timings are wall-clock on the calling thread.
FighterAdaptBenchResult run_fighter_adapt_bench(const FighterAdaptBenchOptions& options);

}  // namespace foresight::bench
