#include "bot_config.hpp"

namespace foresight::bots {

const char* bot_script_name(BotScript script) {
  switch (script) {
    case BotScript::kReplay: return "replay";
    case BotScript::kGoals: return "goals";
    case BotScript::kWander: return "wander";
    case BotScript::kDodge: return "dodge";
  }
  return "unknown";
}

bool bot_script_from_name(std::string_view name, BotScript& out) {
  for (BotScript s : {BotScript::kReplay, BotScript::kGoals, BotScript::kWander, BotScript::kDodge}) {
    if (name == bot_script_name(s)) {
      out = s;
      return true;
    }
  }
  return false;
}

}  // namespace foresight::bots
