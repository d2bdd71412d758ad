#include "pipeline/report/html_page.hpp"

#include "io/sha256.hpp"
#include "pipeline/report/report_assets.hpp"

namespace sm {
using json = nlohmann::json;

std::string html_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string script_json(const json& value) {
  const std::string text = value.dump(-1, ' ', false, json::error_handler_t::replace);
  std::string out;
  out.reserve(text.size() + text.size() / 16);
  // Outside strings JSON has none of these characters, so the escapes only ever land in strings.
  for (char c : text) {
    switch (c) {
      case '<': out += "\\u003c"; break;
      case '>': out += "\\u003e"; break;
      case '&': out += "\\u0026"; break;
      default: out += c;
    }
  }
  return out;
}

std::string base64_encode(std::string_view bytes) {
  static const char* const digits =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out(base64_size(bytes.size()), '=');
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
  size_t o = 0, i = 0;
  for (; i + 3 <= bytes.size(); i += 3) {
    const unsigned v = (p[i] << 16) | (p[i + 1] << 8) | p[i + 2];
    out[o++] = digits[v >> 18];
    out[o++] = digits[(v >> 12) & 63];
    out[o++] = digits[(v >> 6) & 63];
    out[o++] = digits[v & 63];
  }
  if (i < bytes.size()) {
    const bool two = i + 1 < bytes.size();
    const unsigned v = (p[i] << 16) | (two ? p[i + 1] << 8 : 0);
    out[o++] = digits[v >> 18];
    out[o++] = digits[(v >> 12) & 63];
    if (two) out[o++] = digits[(v >> 6) & 63];
  }
  return out;
}

namespace {

constexpr std::string_view kBlockOpen = "<script type=\"application/octet-stream\" id=\"b-";
constexpr std::string_view kBlockMid = "\">";
constexpr std::string_view kBlockClose = "</script>\n";

// CSP source of an inline element: 'sha256-<base64 of the digest of its text>'.
std::string csp_hash(std::string_view text) {
  const std::string hex = sha256_hex(text);
  std::string digest;
  for (size_t i = 0; i + 1 < hex.size(); i += 2)
    digest += static_cast<char>(std::stoi(hex.substr(i, 2), nullptr, 16));
  return "'sha256-" + base64_encode(digest) + "'";
}

}  // namespace

size_t html_block_size(size_t id_size, size_t bytes) {
  return kBlockOpen.size() + id_size + kBlockMid.size() + base64_size(bytes) + kBlockClose.size();
}

bool html_player_available() { return report_assets::player_js[0] != '\0'; }

std::string html_player_missing_reason() { return report_assets::player_missing; }

std::string render_html_page(HtmlPage page) {
  if (!html_player_available()) page.data["player_missing"] = html_player_missing_reason();
  // One script: the player's bundle (if any) defines window.SeqmassagePlayer, the page's code
  // draws the tables and plots and starts it.
  const std::string script = std::string(report_assets::player_js) + "\n" + report_assets::page_js;
  const std::string style = report_assets::page_css;
  std::string out;
  out += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  out += "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; script-src " +
         csp_hash(script) + "; style-src " + csp_hash(style) +
         "; base-uri 'none'; form-action 'none'\">\n";
  out += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  out += "<meta name=\"generator\" content=\"seqmassage\">\n";
  out += "<title>" + html_escape(page.title) + "</title>\n";
  out += "<style>" + style + "</style>\n</head>\n<body>\n";
  out += "<noscript><p>This report draws its tables, plots and 3D player with JavaScript; the "
         "same figures are in summary.csv and report.json beside it.</p></noscript>\n";
  out += "<div id=\"app\"></div>\n";
  out += "<script type=\"application/json\" id=\"sm-data\">" + script_json(page.data) +
         "</script>\n";
  for (const auto& [id, bytes] : page.blocks) {
    out += kBlockOpen;
    out += id;
    out += kBlockMid;
    out += base64_encode(bytes);
    out += kBlockClose;
  }
  out += "<script>" + script + "</script>\n</body>\n</html>\n";
  return out;
}

}  // namespace sm
