#pragma once
/// A self-contained HTML page (report.html): the page's data as JSON and base64 blocks inside
/// non-executed script elements, one inline script (the page's code, with the 3D player where the
/// build bundled it) and one style element, under a Content-Security-Policy that allows no network
/// and no script or style but those two (by their SHA-256). Everything a string from the input or
/// the config reaches is escaped for where it lands.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace sm {

/// `text` for HTML text and quoted attribute values: & < > " ' as character references.
std::string html_escape(std::string_view text);

/// `value` as JSON text for a <script type="application/json"> element: invalid UTF-8 replaced,
/// and < > & written as \u003c \u003e \u0026, so that neither "</script>" nor "<!--" can end or
/// change the element.
std::string script_json(const nlohmann::json& value);

/// Standard base64 (RFC 4648, with padding) of `bytes`; its length is base64_size(bytes.size()).
std::string base64_encode(std::string_view bytes);
constexpr size_t base64_size(size_t bytes) { return (bytes + 2) / 3 * 4; }

/// The bytes the page spends on one base64 block of `bytes` bytes with an id of `id_size`
/// characters (the element around it included).
size_t html_block_size(size_t id_size, size_t bytes);

struct HtmlPage {
  std::string title;    ///< shown in the title bar (escaped)
  nlohmann::json data;  ///< read by the page's script from the element "sm-data"
  /// Binary blocks (id, bytes): base64 in elements "b-<id>"; ids are [a-z0-9-] only.
  std::vector<std::pair<std::string, std::string>> blocks;
};

/// The whole page. data."player_missing" is set when the build has no 3D player.
std::string render_html_page(HtmlPage page);

/// Whether this build embeds the 3D player (three.js, bundled from web/ at build time), and if not,
/// why (for the page and the dry run).
bool html_player_available();
std::string html_player_missing_reason();

}  // namespace sm
