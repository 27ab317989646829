// The supervisor's and the admin's commands (admin_commands.hpp), run on the tick thread.
#include "player.hpp"

#include <algorithm>
#include <cstdlib>
#include <sstream>

namespace foresight::server {

namespace {

bool parse_number(const std::string& text, double lo, double hi, double& out) {
  char* end = nullptr;
  out = std::strtod(text.c_str(), &end);
  return !text.empty() && end != text.c_str() && *end == '\0' && out >= lo && out <= hi;
}

}  // namespace

std::string Server::admin_command(const std::string& line) {
  std::istringstream in(line);
  std::string verb, who, what;
  in >> verb >> who >> what;
  if (verb.empty()) return "";
  if (verb == "help")
    return "commands: fighters | order <id|all> punch|kick|any | auto on|off | set budget-ms|avatar-budget-ms|margin-ms <ms> | "
           "set strategy <name> | set resort-ticks <n> | help";
  if (verb == "set") return admin_set(who, what);
  if (verb == "fighters") {
    std::string out = std::to_string(num_fighters_) + " fighters";
    static const char* phases[] = {"rest", "follow", "strike", "recover"};
    for (const auto& f : players_) {
      if (!f->is_fighter()) continue;
      const FighterNpc& n = *f->fighter;
      out += "\n  " + std::to_string(f->avatar_id) + " " + n.name + " (" +
             morphology_specs()[static_cast<size_t>(n.morphology)].name + "): " +
             phases[static_cast<int>(n.brain.phase())] + ", target " +
             (n.target_id != 0 ? std::to_string(n.target_id) : std::string("none"));
    }
    out += "\n  strikes " + std::to_string(counters_.fighter_strikes) + ", hits " + std::to_string(counters_.fighter_hits);
    return out;
  }
  if (verb == "auto") {
    if (who != "on" && who != "off") return "usage: auto on|off";
    for (const auto& f : players_)
      if (f->is_fighter()) f->fighter->brain.set_auto_attack(who == "on");
    return std::string("fighters' own policy ") + (who == "on" ? "on" : "off");
  }
  if (verb == "order") {
    StrikeOrder order = StrikeOrder::kNone;
    if (what == "punch") order = StrikeOrder::kPunch;
    if (what == "kick") order = StrikeOrder::kKick;
    if (what == "any") order = StrikeOrder::kAny;
    if (who.empty() || order == StrikeOrder::kNone) return "usage: order <id|all> punch|kick|any";
    std::vector<uint32_t> ids = fighter_ids();
    if (who != "all") {
      char* end = nullptr;
      const unsigned long id = std::strtoul(who.c_str(), &end, 10);
      if (end == who.c_str() || *end != '\0' || std::find(ids.begin(), ids.end(), id) == ids.end())
        return "no fighter '" + who + "' (see: fighters)";
      ids = {static_cast<uint32_t>(id)};
    }
    int ordered = 0;
    for (uint32_t id : ids) ordered += order_fighter(id, order) ? 1 : 0;
    return "ordered " + what + " to " + std::to_string(ordered) + " of " + std::to_string(ids.size()) +
           " fighter(s) (a fighter without a player near has no target)";
  }
  return "unknown command '" + verb + "' (help lists them)";
}

std::string Server::admin_set(const std::string& key, const std::string& value) {
  double v = 0;
  if (key == "budget-ms" || key == "margin-ms" || key == "avatar-budget-ms") {
    if (!parse_number(value, 0.0, 1000.0, v)) return "usage: set " + key + " <0-1000>";
    (key == "budget-ms" ? config_.lookahead_budget_ms
     : key == "margin-ms" ? config_.tick_safety_margin_ms
                          : config_.lookahead_avatar_max_ms) = v;
    return key + " " + value;
  }
  if (key == "resort-ticks") {
    if (!parse_number(value, 1.0, 1000.0, v) || v != static_cast<int>(v)) return "usage: set resort-ticks <1-1000>";
    config_.resort_interval_ticks = static_cast<int>(v);
    return key + " " + value;
  }
  if (key == "strategy") {
    Strategy s;
    std::string error;
    if (!strategy_parse(value, s, error)) return error;
    config_.strategy = tree_config_.strategy = s;
    for (const auto& p : players_) {
      if (!p->avatar) continue;
      p->avatar->tree().set_strategy(s);
      p->input_changed = true;  // re-prioritise under the new strategy at the next growth
    }
    return "strategy " + std::string(strategy_name(s)) + " (trees regrow from their roots)";
  }
  return "unknown setting '" + key + "' (budget-ms, avatar-budget-ms, margin-ms, strategy, resort-ticks)";
}

}  // namespace foresight::server
