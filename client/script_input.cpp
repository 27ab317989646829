#include "script_input.hpp"

namespace foresight::client {

bool script_ended(const Recording& script, double t_s) { return t_s > script.duration_s(); }

ControlInput script_input_at(const Recording& script, double t_s) {
  if (t_s < 0.0 || script_ended(script, t_s)) return ControlInput{};
  return recording_input_at(script, t_s);
}

}  // namespace foresight::client
