// Reproduces the kinds of experiment of the Mesh Massage paper's Tables 1–3 on the real data of
// ../shared/data/static (and a cross-parameterization demo), with the remesh, smooth and
// crossparam jobs, and writes the tables into docs/paper.md between the markers
// "<!-- reproduce_paper:begin -->" and "<!-- reproduce_paper:end -->". Not a test: it asserts
// nothing; it skips with a message when the data is absent.
//
//   reproduce_paper [--data DIR] [--out DIR] [--readme FILE | --no-readme] [--threads N]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cli/arguments.hpp"
#include "geometry/bvh.hpp"
#include "io/atomic_file.hpp"
#include "io/mesh_file.hpp"
#include "core/errors.hpp"
#include "mesh/primitives.hpp"
#include "core/timing.hpp"
#include "pipeline/mesh_jobs/mesh_job.hpp"

using namespace sm;
namespace fs = std::filesystem;

namespace {

const char* kBegin = "<!-- reproduce_paper:begin -->";
const char* kEnd = "<!-- reproduce_paper:end -->";

struct Run {
  std::string label;
  MeshJobOptions config;
  MeshJobResult result;
  double seconds = 0.0;
};

std::string fmt(const char* format, double x) {
  char b[64];
  std::snprintf(b, sizeof b, format, x);
  return b;
}
std::string e3(double x) {
  return fmt("%.3g", 1e3 * x);
}  // in units of 10^-3
std::string pct(double x) {
  return fmt("%+.0f%%", 100.0 * x);
}

Run run_job(const std::string& label, MeshJobOptions c, int threads) {
  c.threads = threads;
  c.output.timings = false;
  const auto t0 = Clock::now();
  Run r{label, c, run_mesh_job(plan_mesh_job(c)), 0.0};
  r.seconds = seconds_since(t0);
  const MeshMeasures& b = r.result.before;
  const MeshMeasures* a = r.result.after ? &*r.result.after : nullptr;
  std::printf(
      "  %-44s Hausdorff/diag %.3e -> %.3e, radius ratio %.4f/%.4f -> %.4f/%.4f  (%.1f s)\n",
      label.c_str(), b.hausdorff_rel, a ? a->hausdorff_rel : NAN, b.radius_ratio.min,
      b.radius_ratio.mean, a ? a->radius_ratio.min : NAN, a ? a->radius_ratio.mean : NAN,
      r.seconds);
  std::fflush(stdout);
  return r;
}

MeshJobOptions remesh_config(const fs::path& mesh, const fs::path& source, const fs::path& out) {
  MeshJobOptions c;
  c.job = JobKind::Remesh;
  c.massage = default_massage_options(c.job);
  c.input.mesh = mesh;
  c.input.reference = source;
  c.output.dir = out;
  return c;
}

std::string options_text(const MassageOptions& o) {
  std::string s = std::to_string(o.iterations) + " its, samples " +
                  (o.samples == SampleKind::Vertices ? "vertices"
                   : o.samples == SampleKind::Edges  ? "edges"
                                                     : "faces");
  s += o.mu ? ", μ " + fmt("%g", *o.mu) : ", μ auto";
  return s;
}

// Paper Tables 1 and 2: one-sided distances source -> remesh (M0 -> M1) and remesh -> source.
void remesh_table(std::ostringstream& md, const std::vector<Run>& runs) {
  md << "| remesh (M1) vs source (M0) | run | M0→M1 max | mean | RMS | M1→M0 max | mean | RMS | "
        "Hausdorff | change |\n|---|---|---|---|---|---|---|---|---|---|\n";
  std::string last;
  for (const Run& r : runs) {
    const MeshMeasures& b = r.result.before;
    if (r.label != last) {
      md << "| " << r.label << " | original | " << e3(b.from_reference.max_rel) << " | "
         << e3(b.from_reference.mean_rel) << " | " << e3(b.from_reference.rms_rel) << " | "
         << e3(b.to_reference.max_rel) << " | " << e3(b.to_reference.mean_rel) << " | "
         << e3(b.to_reference.rms_rel) << " | " << e3(b.hausdorff_rel) << " | |\n";
      last = r.label;
    }
    if (!r.result.after) {
      md << "| | " << options_text(r.config.massage) << " | failed: " << r.result.massage.failure
         << " |\n";
      continue;
    }
    const MeshMeasures& a = *r.result.after;
    md << "| | optimized, " << options_text(r.config.massage) << " | "
       << e3(a.from_reference.max_rel) << " | " << e3(a.from_reference.mean_rel) << " | "
       << e3(a.from_reference.rms_rel) << " | " << e3(a.to_reference.max_rel) << " | "
       << e3(a.to_reference.mean_rel) << " | " << e3(a.to_reference.rms_rel) << " | **"
       << e3(a.hausdorff_rel) << "** | " << pct(a.hausdorff / b.hausdorff - 1.0) << " |\n";
  }
}

// Paper Table 3: radius ratio and distance, plus how the sharp edges fared.
void smooth_table(std::ostringstream& md, const std::vector<Run>& runs) {
  const MeshMeasures& b = runs.front().result.before;
  md << "| c3d_fandisk.obj | radius ratio min | mean | Hausdorff / diag | Hausdorff (abs.) | "
        "sharp edges: max distance / diag | dihedral change mean / max | flattened |\n"
        "|---|---|---|---|---|---|---|---|\n";
  md << "| original | " << fmt("%.4f", b.radius_ratio.min) << " | "
     << fmt("%.4f", b.radius_ratio.mean) << " | | | | | 0 of " << b.features.edges << " |\n";
  md << "| paper, Mesh Massage (Table 3) | 0.3700 | 0.9434 | 1.06e-3 (?) | | | | |\n";
  for (const Run& r : runs) {
    if (!r.result.after) {
      md << "| " << r.label << " | failed: " << r.result.massage.failure << " |\n";
      continue;
    }
    const MeshMeasures& a = *r.result.after;
    const bool target = a.radius_ratio.min >= 0.37 && a.radius_ratio.mean >= 0.9434;
    md << "| " << r.label << " | " << (target ? "**" : "") << fmt("%.4f", a.radius_ratio.min)
       << " | " << fmt("%.4f", a.radius_ratio.mean) << (target ? "**" : "") << " | "
       << fmt("%.3g", a.hausdorff_rel) << " | " << fmt("%.3g", a.hausdorff) << " | "
       << fmt("%.3g", a.features.distance.max_rel) << " | "
       << fmt("%.2f°", a.features.dihedral_change_mean.value_or(NAN)) << " / "
       << fmt("%.1f°", a.features.dihedral_change_max.value_or(NAN)) << " | "
       << a.features.flattened.value_or(-1) << " |\n";
  }
}

void crossparam_table(std::ostringstream& md, const std::vector<Run>& runs) {
  md << "| target vs template | run | shear max | mean | p95 | triangles ≥ 0.1 | Hausdorff / diag "
        "| radius ratio min / mean |\n|---|---|---|---|---|---|---|---|\n";
  for (const Run& r : runs) {
    auto row = [&](const char* stage, const MeshMeasures& m) {
      int high = 0;
      const ShearMeasures& s = *m.shear;
      for (size_t i = 0; i + 1 < s.bins.size(); ++i)
        if (s.bins[i] >= 0.1) high += s.counts[i];
      md << "| " << (std::strcmp(stage, "before") == 0 ? r.label : "") << " | " << stage << " | "
         << fmt("%.3g", s.summary.max) << " | " << fmt("%.3g", s.summary.mean) << " | "
         << fmt("%.3g", s.summary.p95) << " | " << high << " of " << m.triangles << " | "
         << fmt("%.3g", m.hausdorff_rel) << " | " << fmt("%.4f", m.radius_ratio.min) << " / "
         << fmt("%.4f", m.radius_ratio.mean) << " |\n";
    };
    row("before", r.result.before);
    if (r.result.after) row("after", *r.result.after);
  }
}

// A cross-parameterization with drift: the target's vertices slid along its own surface by a
// smooth field of about `amount` mean edge lengths (then put back on the surface), so that its
// triangles no longer have the template's shapes.
TriMesh slid(const TriMesh& target, double amount) {
  TriMesh out = target;
  const double h = mean_edge_length(target);
  const double diag = bounding_box_diagonal(target.V);
  const Positions normals = vertex_normals(target);
  const TriangleBvh bvh(target);
  for (int i = 0; i < target.num_vertices(); ++i) {
    const Vec3 x = target.vertex(i) / diag * 12.0;
    Vec3 g(std::sin(x.y() + 0.5 * x.z()), std::cos(1.3 * x.z() - x.x()),
           std::sin(0.7 * x.x() + x.y()));
    const Vec3 n = normals.row(i).transpose();
    g -= g.dot(n) * n;
    out.V.row(i) = bvh.closest(target.vertex(i) + amount * h * g).point.transpose();
  }
  return out;
}

void replace_section(const fs::path& readme, const std::string& section) {
  std::string text = read_file(readme);
  const size_t b = text.find(kBegin), e = text.find(kEnd);
  const std::string block = std::string(kBegin) + "\n" + section + kEnd;
  if (b == std::string::npos || e == std::string::npos || e < b)
    text += "\n" + block + "\n";
  else
    text.replace(b, e + std::strlen(kEnd) - b, block);
  write_file_atomic(readme, text);
}

}  // namespace

int main(int argc, char** argv) {
  fs::path data = fs::path(SEQMASSAGE_SOURCE_DIR) / ".." / "shared" / "data";
  fs::path out = fs::path(SEQMASSAGE_SOURCE_DIR) / "out" / "reproduce_paper";
  fs::path readme = fs::path(SEQMASSAGE_SOURCE_DIR) / "docs" / "paper.md";
  bool no_readme = false;
  int threads = 0;
  CLI::App app(
      "Usage: reproduce_paper [options]\n\n"
      "The paper's Tables 1-3 on the meshes of DIR/static: remeshes, smoothing and\n"
      "cross-parameterization, run as seqmassage's jobs; the tables go into docs/paper.md.\n",
      "reproduce_paper");
  sm::cli::set_conventions(app, 24);
  app.add_option("--data", data, "the real data (default ../shared/data)")->type_name("DIR");
  app.add_option("--out", out, "the jobs' outputs (default out/reproduce_paper)")
      ->type_name("DIR");
  CLI::Option* readme_given =
      app.add_option("--readme", readme, "the file the tables go into (default docs/paper.md)")
          ->type_name("FILE");
  app.add_flag("--no-readme", no_readme, "print the tables only")->excludes(readme_given);
  app.add_option("--threads", threads, "worker threads (0 = one per core)")
      ->type_name("N")
      ->transform(sm::cli::integer_in(0, 4096));
  if (const auto code = sm::cli::parse_or_exit(app, argc, argv)) return *code;
  const bool write_readme = !no_readme;
  const fs::path st = data / "static";
  if (!fs::is_directory(st)) {
    std::printf(
        "SKIPPED: %s not found (the real meshes of ../shared/data/static; see docs/paper.md)\n",
        st.string().c_str());
    return 0;
  }
  try {
    std::ostringstream md;
    md << "Generated by `bash tools/reproduce_paper.sh` (tools/reproduce_paper.cpp) on the meshes "
          "of `../shared/data/static`; outputs in `out/reproduce_paper/`.\n\n";

    // --- Remeshing, Tables 1 and 2 -------------------------------------------------------------
    std::printf("remesh (paper section 3.3, Tables 1 and 2)\n");
    std::vector<Run> remesh;
    struct Pair {
      const char* label;
      fs::path mesh, source;
    };
    const std::vector<Pair> pairs = {
        {"bunny uniform (8,904 v) vs pmp_bunny", st / "bunny/pmp_bunny_uniform.off",
         st / "bunny/pmp_bunny.off"},
        {"bunny adaptive (5,884 v) vs pmp_bunny", st / "bunny/pmp_bunny_adaptive.off",
         st / "bunny/pmp_bunny.off"},
        {"libigl_fandisk (7,229 v) vs c3d_fandisk", st / "fandisk/libigl_fandisk.off",
         st / "fandisk/c3d_fandisk.obj"}};
    int k = 0;
    for (const Pair& p : pairs)
      for (SampleKind samples : {SampleKind::Vertices, SampleKind::Edges}) {
        MeshJobOptions c = remesh_config(p.mesh, p.source, out / ("remesh_" + std::to_string(k++)));
        c.massage.samples = samples;
        remesh.push_back(run_job(p.label, c, threads));
      }
    md << "**Remeshing** (§3.3, like Tables 1 and 2). M0 is the source, M1 the remesh; "
          "Metro-style one-sided distances sampled on vertices, edges and faces, **in 10⁻³ of the "
          "bounding-box diagonal**; defaults: mean value weights of M1, 15 iterations, μ auto.\n\n";
    remesh_table(md, remesh);

    // --- Smoothing, Table 3 --------------------------------------------------------------------
    std::printf("smooth (paper section 4, Table 3)\n");
    std::vector<Run> smooth;
    struct Variant {
      int iterations;
      SampleKind samples;
      std::optional<double> mu;
    };
    const std::vector<Variant> variants = {
        {60, SampleKind::Edges, 0.7},   {15, SampleKind::Vertices, {}},
        {30, SampleKind::Vertices, {}}, {60, SampleKind::Vertices, {}},
        {15, SampleKind::Edges, 0.7},   {30, SampleKind::Edges, 0.7},
        {100, SampleKind::Edges, 0.7},  {60, SampleKind::Faces, 0.7},
        {60, SampleKind::Edges, {}},    {60, SampleKind::Edges, 0.65},
        {60, SampleKind::Edges, 0.8}};
    k = 0;
    for (const Variant& v : variants) {
      MeshJobOptions c;
      c.job = JobKind::Smooth;
      c.massage = default_massage_options(c.job);
      c.massage.iterations = v.iterations;
      c.massage.samples = v.samples;
      c.massage.mu = v.mu;
      c.input.mesh = st / "fandisk/c3d_fandisk.obj";
      c.output.dir = out / ("smooth_" + std::to_string(k));
      const std::string label = (k == 0 ? "smooth, defaults (" : "smooth, ") +
                                options_text(c.massage) + (k == 0 ? ")" : "");
      smooth.push_back(run_job(label, c, threads));
      ++k;
    }
    md << "\n**Smoothing the fandisk** (§4, like Table 3): uniform weights, N = the mesh as "
          "loaded. Radius ratio 2r/R (1 = equilateral); Hausdorff distance between output and "
          "input; sharp edges = the input's "
       << smooth.front().result.before.features.edges
       << " edges with a dihedral angle above 30°: the largest distance from points along them to "
          "the output surface, the change of their dihedral angle on the output (same "
          "connectivity), and how many lost more than half of it (\"flattened\"). Bold: both "
          "radius ratio targets (min ≥ 0.37, mean ≥ 0.9434) met.\n\n";
    smooth_table(md, smooth);

    // --- Cross-parameterization ----------------------------------------------------------------
    std::printf("crossparam (paper section 3.2)\n");
    std::vector<Run> cross;
    fs::create_directories(out / "crossparam_input");
    {
      // Generated: an icosphere as template, a stretched and slid copy as target.
      const TriMesh templ = make_icosphere(4, 1.0);
      TriMesh target = slid(templ, 0.6);
      target.V = (target.V.array().rowwise() * Eigen::Array<double, 1, 3>(1.3, 1.0, 0.8)).matrix();
      write_mesh(out / "crossparam_input/sphere.obj", templ);
      write_mesh(out / "crossparam_input/ellipsoid_slid.obj", target);
      MeshJobOptions c;
      c.job = JobKind::Crossparam;
      c.massage = default_massage_options(c.job);
      c.input.mesh = out / "crossparam_input/ellipsoid_slid.obj";
      c.templ.mesh = out / "crossparam_input/sphere.obj";
      c.output.dir = out / "crossparam_sphere";
      cross.push_back(run_job("generated: icosphere → slid ellipsoid", c, threads));
    }
    const fs::path horse = data / "sequences/sumner_horse_gallop";
    if (fs::is_directory(horse)) {
      const TriMesh frame6 = read_mesh(horse / "frame_0006.obj");
      write_mesh(out / "crossparam_input/horse_6_slid.obj", slid(frame6, 0.5));
      MeshJobOptions c;
      c.job = JobKind::Crossparam;
      c.massage = default_massage_options(c.job);
      c.input.mesh = out / "crossparam_input/horse_6_slid.obj";
      c.templ.mesh = horse / "frame_0000.obj";
      c.output.dir = out / "crossparam_horse_slid";
      cross.push_back(run_job("horse frame 6, slid 0.5 edge → frame 0", c, threads));
      c.input.mesh = horse / "frame_0006.obj";
      c.output.dir = out / "crossparam_horse";
      cross.push_back(run_job("horse frame 6 as is → frame 0", c, threads));
    }
    md << "\n**Cross-parameterization** (§3.2): M = target, T = template (same connectivity), N "
          "= target as loaded; defaults. Shear = eq. 8 against T.\n\n";
    crossparam_table(md, cross);

    std::printf("\n%s", md.str().c_str());
    if (write_readme) {
      replace_section(readme, md.str());
      std::printf("\nwrote the tables into %s\n", readme.string().c_str());
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "reproduce_paper: %s\n", e.what());
    return 1;
  }
  return 0;
}
