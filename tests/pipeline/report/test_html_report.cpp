// report.html: the escaping and encodings it relies on (RFC 4648 vectors, HTML and script
// contexts), the frames it keeps under a budget, and the page of a real run: within its budget,
// byte-identical across thread counts, its data decodable back to the run's positions.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <regex>

#include "io/atomic_file.hpp"
#include "io/obj.hpp"
#include "pipeline/report/html_page.hpp"
#include "pipeline/report/html_sequence.hpp"
#include "pipeline/run/sequence_job.hpp"
#include "support/html_player.hpp"
#include "support/sequence_fixture.hpp"
#include "support/temp_dir.hpp"

using namespace sm;
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

// The text of the element with id `id` (an id="..." attribute, then its content up to </script>).
std::string element_text(const std::string& page, const std::string& id) {
  const std::string open = "id=\"" + id + "\">";
  const size_t at = page.find(open);
  if (at == std::string::npos) return "";
  const size_t start = at + open.size();
  return page.substr(start, page.find("</script>", start) - start);
}

// Base64 decoding, written here from RFC 4648 (not the code under test's inverse).
std::string base64_decode(const std::string& text) {
  std::string out;
  int bits = 0;
  uint32_t value = 0;  // unsigned, and only the bits not yet written are kept
  for (char c : text) {
    int d = -1;
    if (c >= 'A' && c <= 'Z') d = c - 'A';
    else if (c >= 'a' && c <= 'z') d = c - 'a' + 26;
    else if (c >= '0' && c <= '9') d = c - '0' + 52;
    else if (c == '+') d = 62;
    else if (c == '/') d = 63;
    if (d < 0) continue;
    value = ((value << 6) | uint32_t(d)) & 0xffffu;
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out += char((value >> bits) & 0xff);
    }
  }
  return out;
}

}  // namespace

TEST_CASE("base64 follows the RFC 4648 test vectors") {
  CHECK(base64_encode("") == "");
  CHECK(base64_encode("f") == "Zg==");
  CHECK(base64_encode("fo") == "Zm8=");
  CHECK(base64_encode("foo") == "Zm9v");
  CHECK(base64_encode("foob") == "Zm9vYg==");
  CHECK(base64_encode("fooba") == "Zm9vYmE=");
  CHECK(base64_encode("foobar") == "Zm9vYmFy");
  CHECK(base64_encode(std::string("\xff\xfe\x00", 3)) == "//4A");
  for (size_t n = 0; n < 10; ++n) CHECK(base64_encode(std::string(n, 'x')).size() == base64_size(n));
}

TEST_CASE("strings are escaped for HTML text and for a JSON script element") {
  CHECK(html_escape("<img src=x onerror=\"a('1')\">&") ==
        "&lt;img src=x onerror=&quot;a(&#39;1&#39;)&quot;&gt;&amp;");
  const json value = {{"path", "</script><script>alert(1)</script>"},
                      {"name", "<!-- <img src=x onerror=alert(1)>.obj"},
                      {"bad", std::string("a\xff" "b")}};
  const std::string text = script_json(value);
  CHECK(text.find('<') == std::string::npos);
  CHECK(text.find('>') == std::string::npos);
  CHECK(text.find('&') == std::string::npos);
  const json back = json::parse(text);
  CHECK(back["path"] == value["path"]);
  CHECK(back["name"] == value["name"]);
  CHECK(back["bad"] == "a\xef\xbf\xbd" "b");  // invalid UTF-8 replaced by U+FFFD
}

TEST_CASE("the page's policy allows only its own script and style, and no network") {
  HtmlPage page;
  page.title = "</title><script>alert(1)</script>";
  page.data = {{"x", "</script>"}};
  page.blocks.emplace_back("tri", std::string("\x01\x02\x03\x04", 4));
  const std::string html = render_html_page(page);
  const std::smatch m = [&] {
    std::smatch r;
    std::regex_search(html, r, std::regex("Content-Security-Policy\" content=\"([^\"]*)\""));
    return r;
  }();
  REQUIRE(m.size() == 2);
  const std::string csp = m[1];
  CHECK(csp.rfind("default-src 'none'; script-src 'sha256-", 0) == 0);
  CHECK(csp.find("unsafe") == std::string::npos);
  CHECK(csp.find("http") == std::string::npos);
  // Exactly one executable script (the others are data), and the title is text.
  CHECK(std::regex_search(html, std::regex("<title>&lt;/title&gt;&lt;script&gt;")));
  size_t scripts = 0;
  for (size_t at = html.find("<script"); at != std::string::npos; at = html.find("<script", at + 1))
    scripts += html.compare(at, 13, "<script type=") != 0;
  CHECK(scripts == 1);
  CHECK(base64_decode(element_text(html, "b-tri")) == std::string("\x01\x02\x03\x04", 4));
  CHECK(json::parse(element_text(html, "sm-data"))["x"] == "</script>");
}

TEST_CASE("frames over the budget are kept evenly spaced, first and last included") {
  CHECK(evenly_spaced(5, 10) == std::vector<int>{0, 1, 2, 3, 4});
  CHECK(evenly_spaced(5, 5) == std::vector<int>{0, 1, 2, 3, 4});
  CHECK(evenly_spaced(1000, 3) == std::vector<int>{0, 500, 999});  // round(499.5) = 500
  CHECK(evenly_spaced(10, 1) == std::vector<int>{0});
  CHECK(evenly_spaced(10, 0).empty());
  const std::vector<int> k = evenly_spaced(1000, 37);
  REQUIRE(k.size() == 37);
  CHECK(k.front() == 0);
  CHECK(k.back() == 999);
  for (size_t i = 1; i < k.size(); ++i) {
    CHECK(k[i] > k[i - 1]);
    CHECK(std::abs((k[i] - k[i - 1]) - 999.0 / 36) <= 1.0);
  }
}

TEST_CASE("a run's report.html holds its frames, within the budget, the same for any thread count") {
  test::TempDir dir("html_report");
  SequenceJobOptions c = test::tube_job(dir.path(), test::small_tube(6));
  c.output.html = true;
  c.threads = 1;
  const SequenceResult r1 = run_sequence_job(plan_sequence_job(c), {});
  const std::string page = read_file(dir / "out/report.html");
  const json data = json::parse(element_text(page, "sm-data"));
  CHECK(data["summary_csv"] == read_file(dir / "out/summary.csv"));
  if (!test::player_in_build(data)) return;
  REQUIRE(data["player"].is_object());
  CHECK(data["player"]["frames"] == std::vector<int>{0, 1, 2, 3, 4, 5});
  const int n = data["player"]["vertices"];
  // The histogram counts every triangle of every frame once per side.
  for (const char* side : {"before", "after"}) {
    const std::vector<long long> counts = data["histogram"][side];
    long long total = 0;
    for (long long k : counts) total += k;
    CHECK(total == 6 * data["player"]["triangles"].get<long long>());
  }
  // Frame 3's input positions, decoded from the page, match the input OBJ within the box's step.
  const std::string q = base64_decode(element_text(page, "b-i3"));
  REQUIRE(q.size() == size_t(n) * 6);
  const TriMesh in = read_obj(dir / "in/frame_0003.obj").mesh;
  const std::vector<double> box = data["player"]["box"];
  double worst = 0;
  for (int v = 0; v < n; ++v)
    for (int k = 0; k < 3; ++k) {
      const unsigned code = uint8_t(q[(v * 3 + k) * 2]) | (uint8_t(q[(v * 3 + k) * 2 + 1]) << 8);
      const double x = box[k] + code / 65535.0 * (box[3 + k] - box[k]);
      worst = std::max(worst, std::abs(x - in.V(v, k)) / (box[3 + k] - box[k]));
    }
  CHECK(worst <= 0.5 / 65535 + 1e-6);

  SequenceJobOptions c2 = c;
  c2.threads = 2;
  c2.output.dir = dir / "t2" / "out";  // the same folder name: the same title
  run_sequence_job(plan_sequence_job(c2), {});
  const std::string page2 = read_file(dir / "t2/out/report.html");
  // The resolved config names its own output folder and thread count; the rest is identical.
  const std::string a = std::regex_replace(page, std::regex("\"(dir|threads)\":(\"[^\"]*\"|[0-9]+)"), "");
  const std::string b = std::regex_replace(page2, std::regex("\"(dir|threads)\":(\"[^\"]*\"|[0-9]+)"), "");
  CHECK(a == b);
  CHECK(r1.frames.size() == 6);

  // A budget short of the whole page by 1.5 frames: fewer frames, evenly spaced, first and last
  // among them, within the budget (the page keeps a few KB of slack besides).
  SequenceJobOptions c3 = c;
  c3.output.dir = dir / "out3";
  const size_t frame_bytes = size_t(n) * 12 + size_t(in.num_triangles()) * 2;
  c3.output.html_max_mb = (page.size() - 2 * frame_bytes) / 1048576.0;
  const SequenceResult r3 = run_sequence_job(plan_sequence_job(c3), {});
  const std::string page3 = read_file(dir / "out3/report.html");
  CHECK(page3.size() <= size_t(c3.output.html_max_mb * 1048576));
  const json data3 = json::parse(element_text(page3, "sm-data"));
  REQUIRE(data3["player"].is_object());
  const std::vector<int> kept = data3["player"]["frames"];
  REQUIRE(kept.size() >= 2);
  CHECK(kept.size() < 6);
  CHECK(kept.front() == 0);
  CHECK(kept.back() == 5);
  bool warned = false;
  for (const std::string& w : r3.warnings) warned = warned || w.find("evenly spaced") != std::string::npos;
  CHECK(warned);
}
