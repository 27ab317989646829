// The supervisor's and the admin's commands (admin_commands.hpp), run on the tick thread.
#include "server.hpp"

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <vector>

namespace foresight::server {

namespace {

bool parse_number(const std::string& text, double lo, double hi, double& out) {
  char* end = nullptr;
  out = std::strtod(text.c_str(), &end);
  return !text.empty() && end != text.c_str() && *end == '\0' && out >= lo && out <= hi;
}

}  // namespace

AdminReply Server::admin_command(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  if (words.empty()) return {200, ""};
  const std::string& verb = words[0];
  // Each command's words, exactly: a word too many is a mistake, not something to ignore
  // (`set budget-ms 8 extra words` used to apply 8).
  const auto usage = [&](size_t arguments, const char* text) -> std::optional<AdminReply> {
    if (words.size() == arguments + 1) return std::nullopt;
    return AdminReply{400, std::string("usage: ") + text};
  };
  const std::string who = words.size() > 1 ? words[1] : "", what = words.size() > 2 ? words[2] : "";
  if (verb == "help") {
    if (auto u = usage(0, "help")) return *u;
    return {200, "commands: fighters | order <id|all> punch|kick|any | auto on|off | "
                 "set budget-ms|avatar-budget-ms|margin-ms <ms> | set strategy <name> | set resort-ticks <n> | help"};
  }
  if (verb == "set") {
    if (auto u = usage(2, "set <setting> <value> (help lists them)")) return *u;
    return admin_set(who, what);
  }
  if (verb == "fighters") {
    if (auto u = usage(0, "fighters")) return *u;
    std::string out = std::to_string(num_fighters_) + " fighters";
    static const char* phases[] = {"rest", "follow", "strike", "recover"};
    for (const Fighter& f : fighters_.items()) {
      const FighterNpc& n = *f.npc;
      out += "\n  " + std::to_string(f.id) + " " + n.name + " (" +
             morphology_specs()[static_cast<size_t>(n.morphology)].name + "): " +
             phases[static_cast<int>(n.brain.phase())] + ", target " +
             (n.target_id != 0 ? std::to_string(n.target_id) : std::string("none"));
    }
    out += "\n  strikes " + std::to_string(counters_.fighter_strikes) + ", hits " + std::to_string(counters_.fighter_hits);
    return {200, out};
  }
  if (verb == "auto") {
    if (auto u = usage(1, "auto on|off")) return *u;
    if (who != "on" && who != "off") return {400, "usage: auto on|off"};
    for (const Fighter& f : fighters_.items()) f.npc->brain.set_auto_attack(who == "on");
    return {200, std::string("fighters' own policy ") + (who == "on" ? "on" : "off")};
  }
  if (verb == "order") {
    if (auto u = usage(2, "order <id|all> punch|kick|any")) return *u;
    StrikeOrder order = StrikeOrder::kNone;
    if (what == "punch") order = StrikeOrder::kPunch;
    if (what == "kick") order = StrikeOrder::kKick;
    if (what == "any") order = StrikeOrder::kAny;
    if (order == StrikeOrder::kNone) return {400, "usage: order <id|all> punch|kick|any"};
    std::vector<uint32_t> ids = fighter_ids();
    if (who != "all") {
      char* end = nullptr;
      const unsigned long id = std::strtoul(who.c_str(), &end, 10);
      if (end == who.c_str() || *end != '\0' || std::find(ids.begin(), ids.end(), id) == ids.end())
        return {404, "no fighter '" + who + "' (see: fighters)"};
      ids = {static_cast<uint32_t>(id)};
    }
    int ordered = 0;
    for (uint32_t id : ids) ordered += order_fighter(id, order) ? 1 : 0;
    return {200, "ordered " + what + " to " + std::to_string(ordered) + " of " + std::to_string(ids.size()) +
                     " fighter(s) (a fighter without a player near has no target)"};
  }
  return {404, "unknown command '" + verb + "' (help lists them)"};
}

AdminReply Server::admin_set(const std::string& key, const std::string& value) {
  double v = 0;
  if (key == "budget-ms" || key == "margin-ms" || key == "avatar-budget-ms") {
    if (!parse_number(value, 0.0, 1000.0, v)) return {400, "usage: set " + key + " <0-1000>"};
    (key == "budget-ms" ? config_.lookahead_budget_ms
     : key == "margin-ms" ? config_.tick_safety_margin_ms
                          : config_.lookahead_avatar_max_ms) = v;
    return {200, key + " " + value};
  }
  if (key == "resort-ticks") {
    if (!parse_number(value, 1.0, 1000.0, v) || v != static_cast<int>(v))
      return {400, "usage: set resort-ticks <1-1000>"};
    config_.resort_interval_ticks = static_cast<int>(v);
    return {200, key + " " + value};
  }
  if (key == "strategy") {
    Strategy s;
    std::string error;
    if (!strategy_parse(value, s, error)) return {400, error};
    config_.strategy = tree_config_.strategy = s;
    for (GraphAvatar& g : graph_avatars_.items()) {
      g.avatar->tree().set_strategy(s);
      g.input_changed = true;  // re-prioritise under the new strategy at the next growth
    }
    return {200, "strategy " + std::string(strategy_name(s)) + " (trees regrow from their roots)"};
  }
  return {404, "unknown setting '" + key + "' (budget-ms, avatar-budget-ms, margin-ms, strategy, resort-ticks)"};
}

}  // namespace foresight::server
