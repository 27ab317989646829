#include "protocol/input_packet.hpp"

#include "protocol/quantize.hpp"

#include <cmath>

namespace foresight::protocol {

wire::InputCommand input_command_from(const ControlInput& input, uint32_t sequence) {
  const wire::Buttons buttons = input.crouch ? wire::Buttons::Crouch : wire::Buttons::NONE;
  return wire::InputCommand(sequence, quantize_angle(input.camera_yaw_rad),
                            quantize_unit(input.camera_dir.x), quantize_unit(input.camera_dir.y),
                            buttons);
}

ControlInput control_input_from_command(const wire::InputCommand& command) {
  ControlInput out;
  out.camera_yaw_rad = dequantize_angle(command.camera_yaw());
  out.camera_dir = vec2(dequantize_unit(command.dir_x()), dequantize_unit(command.dir_y()));
  // (127, 127) decodes to length 1.414: a peer may send any byte pair, and rounding of a unit
  // diagonal can land a hair above 1.
  const float len2 = glm::dot(out.camera_dir, out.camera_dir);
  if (len2 > 1.0f) out.camera_dir /= std::sqrt(len2);
  out.crouch = (command.buttons() & wire::Buttons::Crouch) != wire::Buttons::NONE;
  return out;
}

std::span<const uint8_t> write_input(PacketWriter& w, uint32_t session, uint32_t ack_snapshot,
                                     uint32_t client_time_ms,
                                     std::span<const wire::InputCommand> commands) {
  if (commands.size() > static_cast<size_t>(kInputRedundancy)) {
    commands = commands.subspan(commands.size() - static_cast<size_t>(kInputRedundancy));
  }
  auto& fbb = w.begin();
  const auto cmds = fbb.CreateVectorOfStructs(commands.data(), commands.size());
  return w.finish(wire::CreateInput(fbb, session, ack_snapshot, client_time_ms, cmds));
}

}  // namespace foresight::protocol
