#include "pipeline/report/html_sequence.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "geometry/shear.hpp"
#include "io/atomic_file.hpp"
#include "core/errors.hpp"
#include "pipeline/report/report_json.hpp"

namespace sm {
using json = nlohmann::json;

namespace {

constexpr char kFrameMagic[8] = {'S', 'M', 'H', 'T', 'M', 'L', 'F', '1'};
constexpr char kTemplateMagic[8] = {'S', 'M', 'H', 'T', 'M', 'L', 'T', '1'};
constexpr int kHistogramBins = 40;

// Little-endian fields (every platform the project builds on); the files never leave the run.
template <class T>
void put(std::string& out, const T* values, size_t count) {
  out.append(reinterpret_cast<const char*>(values), count * sizeof(T));
}
void put_u32(std::string& out, uint32_t v) { put(out, &v, 1); }

struct Reader {
  const std::string& bytes;
  const std::string& file;
  size_t at = 0;
  template <class T>
  void get(T* values, size_t count) {
    const size_t size = count * sizeof(T);
    if (bytes.size() - at < size) throw InputError(file + ": truncated report data");
    std::memcpy(values, bytes.data() + at, size);
    at += size;
  }
  uint32_t u32() {
    uint32_t v = 0;
    get(&v, 1);
    return v;
  }
  void magic(const char (&expected)[8]) {
    char m[8];
    get(m, 8);
    if (std::memcmp(m, expected, 8) != 0) throw InputError(file + ": not seqmassage report data");
  }
};

void put_floats(std::string& out, const Positions& V) {
  std::vector<float> f(static_cast<size_t>(V.size()));
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    for (int k = 0; k < 3; ++k) f[size_t(i) * 3 + k] = static_cast<float>(V(i, k));
  put(out, f.data(), f.size());
}

void put_floats(std::string& out, const Eigen::VectorXd& x) {
  std::vector<float> f(static_cast<size_t>(x.size()));
  for (Eigen::Index i = 0; i < x.size(); ++i) f[size_t(i)] = static_cast<float>(x[i]);
  put(out, f.data(), f.size());
}

// The box of every finite coordinate of `p` grown to hold it: lo[0..2], hi[0..2].
void grow_box(const std::vector<float>& p, double box[6]) {
  for (size_t i = 0; i + 2 < p.size(); i += 3)
    for (int k = 0; k < 3; ++k)
      if (std::isfinite(p[i + k])) {
        box[k] = std::min(box[k], double(p[i + k]));
        box[3 + k] = std::max(box[3 + k], double(p[i + k]));
      }
}

// 16 bits per coordinate against the box (0 for a non-finite coordinate).
std::string quantise(const std::vector<float>& p, const double box[6]) {
  std::vector<uint16_t> q(p.size());
  for (size_t i = 0; i < p.size(); ++i) {
    const int k = int(i % 3);
    const double extent = box[3 + k] - box[k];
    const double t = extent > 0 && std::isfinite(p[i]) ? (p[i] - box[k]) / extent : 0.0;
    q[i] = static_cast<uint16_t>(std::lround(std::clamp(t, 0.0, 1.0) * 65535.0));
  }
  std::string out;
  put(out, q.data(), q.size());
  return out;
}

// 8 bits on [0, scale]; 255 also for a degenerate (infinite) triangle.
std::string shear_codes(const std::vector<float>& shear, double scale) {
  std::string out(shear.size(), '\0');
  for (size_t i = 0; i < shear.size(); ++i) {
    const double t = std::isfinite(shear[i]) ? shear[i] / scale : 1.0;
    out[i] = static_cast<char>(std::lround(std::clamp(t, 0.0, 1.0) * 255.0));
  }
  return out;
}

void add_histogram(const std::vector<float>& shear, const std::vector<double>& edges,
                   std::vector<long long>& counts) {
  Eigen::VectorXd x(static_cast<Eigen::Index>(shear.size()));
  for (size_t i = 0; i < shear.size(); ++i) x[Eigen::Index(i)] = shear[i];
  const std::vector<int> c = histogram(x, edges);
  for (size_t i = 0; i < c.size(); ++i) counts[i] += c[i];
}

// The colour scale of the shear: the largest p95 of the input frames (1 if there is none).
double shear_scale(const std::vector<FrameSummary>& frames) {
  double s = 0;
  for (const FrameSummary& f : frames)
    if (std::isfinite(f.shear_before.p95)) s = std::max(s, f.shear_before.p95);
  return s > 0 ? s : 1.0;
}

std::vector<json> summary_failures(const std::vector<FrameSummary>& frames) {
  std::vector<json> out;
  for (const FrameSummary& f : frames)
    if (f.status == FrameStatus::Failed)
      out.push_back({{"frame", f.frame}, {"file", f.file}, {"reason", f.failure}});
  return out;
}

}  // namespace

std::string encode_player_template(const PlayerTemplate& t) {
  std::string out(kTemplateMagic, 8);
  put_u32(out, uint32_t(t.vertices));
  put_u32(out, uint32_t(t.F.rows()));
  put_u32(out, uint32_t(t.uv_source.size()));
  out += t.uv_source;
  std::vector<uint32_t> f(static_cast<size_t>(t.F.size()));
  for (Eigen::Index i = 0; i < t.F.size(); ++i) f[size_t(i)] = uint32_t(t.F.data()[i]);
  put(out, f.data(), f.size());
  put(out, t.corner_uv.data(), t.corner_uv.size());
  return out;
}

PlayerTemplate decode_player_template(const std::string& bytes, const std::string& file) {
  Reader r{bytes, file};
  r.magic(kTemplateMagic);
  PlayerTemplate t;
  t.vertices = int(r.u32());
  const uint32_t m = r.u32(), name = r.u32();
  if (name > 64 || size_t(m) * 36 > bytes.size()) throw InputError(file + ": bad report data");
  t.uv_source.resize(name);
  r.get(t.uv_source.data(), name);
  std::vector<uint32_t> f(size_t(m) * 3);
  r.get(f.data(), f.size());
  t.F.resize(m, 3);
  for (size_t i = 0; i < f.size(); ++i) {
    if (f[i] >= uint32_t(t.vertices)) throw InputError(file + ": triangle corner out of range");
    t.F.data()[i] = int(f[i]);
  }
  t.corner_uv.resize(size_t(m) * 6);
  r.get(t.corner_uv.data(), t.corner_uv.size());
  return t;
}

std::string encode_player_frame(const Positions& in, const Positions& out,
                                const Eigen::VectorXd& shear_before,
                                const Eigen::VectorXd& shear_after) {
  std::string bytes(kFrameMagic, 8);
  put_u32(bytes, uint32_t(in.rows()));
  put_u32(bytes, uint32_t(shear_before.size()));
  put_floats(bytes, in);
  put_floats(bytes, out);
  put_floats(bytes, shear_before);
  put_floats(bytes, shear_after);
  return bytes;
}

PlayerFrame decode_player_frame(const std::string& bytes, int vertices, int triangles,
                                const std::string& file) {
  Reader r{bytes, file};
  r.magic(kFrameMagic);
  if (r.u32() != uint32_t(vertices) || r.u32() != uint32_t(triangles))
    throw InputError(file + ": report data of another mesh (vertex or triangle count)");
  PlayerFrame f;
  for (auto* v : {&f.in, &f.out}) {
    v->resize(size_t(vertices) * 3);
    r.get(v->data(), v->size());
  }
  for (auto* v : {&f.shear_before, &f.shear_after}) {
    v->resize(size_t(triangles));
    r.get(v->data(), v->size());
  }
  return f;
}

std::vector<int> evenly_spaced(int total, int fit) {
  std::vector<int> out;
  if (fit >= total) {
    for (int i = 0; i < total; ++i) out.push_back(i);
  } else if (fit == 1) {
    out.push_back(0);
  } else if (fit > 1) {
    for (int i = 0; i < fit; ++i)
      out.push_back(int(std::lround(double(i) * (total - 1) / (fit - 1))));
  }
  return out;
}

SequencePage make_sequence_page(const SequencePageInput& in) {
  const std::vector<FrameSummary>& frames = *in.frames;
  SequencePage page;
  HtmlPage html;
  html.title = in.title;
  json& d = html.data;
  d["kind"] = in.kind;
  d["title"] = in.title;
  d["summary_csv"] = in.summary_csv;
  d["failures"] = summary_failures(frames);
  d["warnings"] = in.warnings;
  d["config"] = in.config;
  d["versions"] = in.versions;
  d["fps"] = in.fps;
  const bool ratio = in.colour == "radius ratio";
  const double scale =
      ratio ? 1.0 : in.colour_scale > 0 ? in.colour_scale : shear_scale(frames);
  std::vector<double> edges;
  for (int i = 0; i <= kHistogramBins; ++i) edges.push_back(scale * (ratio ? 1 : 2) * i / kHistogramBins);
  edges.push_back(std::numeric_limits<double>::infinity());
  std::vector<long long> before(edges.size() - 1), after(edges.size() - 1);

  const int total = static_cast<int>(in.data_frames.size());
  page.frames_total = total;
  std::string player_note = in.player_note;
  PlayerTemplate t;
  double box[6] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                   std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                   -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  if (total > 0) {
    t = in.load_template();
    // Pass 1: the box of every frame and the histogram of every triangle.
    for (int k = 0; k < total; ++k) {
      const PlayerFrame p = in.load(size_t(k));
      grow_box(p.in, box);
      grow_box(p.out, box);
      add_histogram(p.shear_before, edges, before);
      add_histogram(p.shear_after, edges, after);
    }
  }
  edges.back() = -1;  // JSON has no infinity: the last bin is "and above" (degenerate included)
  d["histogram"] = {{"edges", edges}, {"before", before}, {"after", after}};
  d["player"] = nullptr;
  if (total == 0 && player_note.empty()) player_note = "no frame has data for the player";
  d["player_note"] = player_note;

  if (total > 0) {
    const size_t n = size_t(t.vertices), m = size_t(t.F.rows());
    // The page without frames, then as many frames as fit.
    const size_t fixed = render_html_page(html).size() + html_block_size(3, m * 12) +
                         html_block_size(2, m * 24) + 4096 + size_t(total) * 16;
    const size_t per_frame = 2 * html_block_size(8, n * 6) + 2 * html_block_size(8, m);
    const int fit = in.budget_bytes > fixed ? int(std::min<size_t>(total, (in.budget_bytes - fixed) / per_frame)) : 0;
    const std::vector<int> kept = evenly_spaced(total, fit);
    if (kept.empty()) {
      d["player_note"] = "the player's frames do not fit in output.html_max_mb";
    } else {
      std::vector<int> indices;
      for (int k : kept) indices.push_back(in.data_frames[size_t(k)]);
      d["player"] = {{"vertices", n},
                     {"triangles", m},
                     {"box", {box[0], box[1], box[2], box[3], box[4], box[5]}},
                     {"frames", indices},
                     {"frames_total", total},
                     {"uv", t.uv_source},
                     {"checker_cells", in.checker_cells},
                     {"shear_scale", scale},
                     {"colour", in.colour}};
      std::vector<uint32_t> f(m * 3);
      for (size_t i = 0; i < f.size(); ++i) f[i] = uint32_t(t.F.data()[i]);
      html.blocks.emplace_back("tri", std::string(reinterpret_cast<const char*>(f.data()), f.size() * 4));
      html.blocks.emplace_back("uv", std::string(reinterpret_cast<const char*>(t.corner_uv.data()),
                                                 t.corner_uv.size() * 4));
      for (size_t j = 0; j < kept.size(); ++j) {
        const int k = kept[j];
        const PlayerFrame p = in.load(size_t(k));
        const std::string id = std::to_string(j);
        html.blocks.emplace_back("i" + id, quantise(p.in, box));
        html.blocks.emplace_back("o" + id, quantise(p.out, box));
        html.blocks.emplace_back("si" + id, shear_codes(p.shear_before, scale));
        html.blocks.emplace_back("so" + id, shear_codes(p.shear_after, scale));
      }
      page.frames_kept = int(kept.size());
      if (page.frames_kept < total)
        page.warnings.push_back("report.html: the player keeps " + std::to_string(kept.size()) +
                                " evenly spaced frames of " + std::to_string(total) +
                                " (output.html_max_mb)");
    }
  }
  page.html = render_html_page(html);
  if (page.html.size() > in.budget_bytes && !html.blocks.empty()) {
    html.blocks.clear();  // the estimate missed: never more than the budget
    d["player"] = nullptr;
    d["player_note"] = "the player's frames do not fit in output.html_max_mb";
    page.frames_kept = 0;
    page.html = render_html_page(html);
  }
  return page;
}

}  // namespace sm
