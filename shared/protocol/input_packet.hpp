#pragma once
// The client's Input message: a held ControlInput quantised into an InputCommand (the server
// decodes it with control_input_from_command), and the packet repeating the last few commands.
// ControlInput is a header-only value type of lookahead/, the only thing this layer takes from it.
#include "world/control_input.hpp"
#include "protocol/packet.hpp"

#include <cstdint>
#include <span>

namespace foresight::protocol {

/// Quantises `input` (quantize.hpp: yaw to 1/65536 turn, each direction axis to -127..127, the
/// crouch button). The caller passes a valid input (control_input_valid); non-finite values
/// become 0 rather than undefined behaviour.
wire::InputCommand input_command_from(const ControlInput& input, uint32_t sequence);

/// What the receiver of a command holds. The direction is scaled back to length 1 when rounding
/// made it slightly longer, so the result always passes control_input_valid().
ControlInput control_input_from_command(const wire::InputCommand& command);

/// An Input packet: `commands` newest last, at most kInputRedundancy (extra older ones are cut).
std::span<const uint8_t> write_input(PacketWriter& w, uint32_t session, uint32_t ack_snapshot,
                                     uint32_t client_time_ms,
                                     std::span<const wire::InputCommand> commands);

}  // namespace foresight::protocol
