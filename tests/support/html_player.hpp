#pragma once
/// Whether report.html's 3D player can be checked: a build without web/'s npm packages embeds no
/// player (the page says why). Such a build skips the player's data with a warning naming the
/// fix; the test command installs the packages, and tests/web/run.sh fails without the player.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "pipeline/report/html_page.hpp"

namespace sm::test {

inline bool player_in_build(const nlohmann::json& data) {
  if (html_player_available()) return true;
  CHECK(data["player_missing"] == html_player_missing_reason());
  CHECK_FALSE(data["player"].is_object());
  WARN("report.html's player data not checked: " << html_player_missing_reason());
  return false;
}

}  // namespace sm::test
