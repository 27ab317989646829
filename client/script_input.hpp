#pragma once
// --script: the player's input read from a recording (docs/RECORDINGS.md) instead of the
// keyboard. Pure so it can be tested without a window.
#include "scripted/recording.hpp"

namespace foresight::client {

/// The scripted input `t_s` seconds after the script started: the recording's sample-and-hold
/// input (recording_input_at: its camera-space direction, camera yaw and crouch), stop
/// (ControlInput{}) before 0 and once the script has ended (after its last sample).
ControlInput script_input_at(const Recording& script, double t_s);

/// True once `t_s` is past the script's last sample.
bool script_ended(const Recording& script, double t_s);

}  // namespace foresight::client
