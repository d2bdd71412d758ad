#include "pipeline/run/sequence_plan.hpp"

#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <map>
#include <set>
#include <sstream>

#include "io/csv.hpp"
#include "io/mesh_file.hpp"
#include "io/vertex_weights.hpp"
#include "geometry/sample_budget.hpp"
#include "core/errors.hpp"
#include "mesh/mesh_check.hpp"
#include "pipeline/outputs/frame_output.hpp"
#include "pipeline/run/frame_processor.hpp"
#include "pipeline/cluster/frame_record.hpp"
#include "pipeline/sequence/input_clash.hpp"
#include "pipeline/report/report.hpp"
#include "pipeline/report/run_text.hpp"
#include "pipeline/sequence/shard.hpp"
#include "pipeline/sequence/frame_sources.hpp"

// plan_sequence_job and describe_plan (sequence_plan.hpp): everything checked before a run.

namespace sm {
namespace fs = std::filesystem;

namespace {

// Reads every selected frame (a few at a time) and throws for the first one, in frame order,
// whose connectivity differs from the template's.
void check_frames(const SequencePlan& plan, tbb::task_arena& arena) {
  const FrameSource& source = *plan.source;
  std::vector<std::string> problems(plan.run_frames.size());
  arena.execute([&] {
    tbb::parallel_for(size_t{0}, plan.run_frames.size(), [&](size_t k) {
      const int index = plan.run_frames[k];
      if (index == plan.template_frame) return;
      problems[k] = plan.processor->connectivity_mismatch(
          source.label(index), source.decode(index, source.fetch(index)).mesh);
    });
  });
  for (const std::string& problem : problems)
    if (!problem.empty()) throw InputError(problem);
}

// Refuses an output file that is one of the inputs: every file the run reads (the config, the
// frames or cache and its mesh, the glTF asset with its buffers and images, the template, the
// weights) against every file it writes, by identity.
void check_outputs(const SequencePlan& plan) {
  const SequenceJobOptions& c = plan.config;
  std::vector<ReadFile> inputs = {{"the config", c.config_file},
                                  {"template.mesh", c.templ.mesh}};
  if (!c.massage.vertex_weights_file.empty())
    inputs.push_back({"massage.vertex_weights", weights_file_read(c.massage.vertex_weights_file)});
  std::vector<int> read = plan.run_frames;
  if (plan.template_frame >= 0) read.push_back(plan.template_frame);
  for (const fs::path& file : plan.source->files(read)) inputs.push_back({"the input", file});
  std::vector<fs::path> outputs;
  for (const auto& output : plan.outputs)
    for (fs::path& file : output->files(plan.run_frames)) outputs.push_back(std::move(file));
  outputs.push_back(c.output.dir / summary_file_name(c.shard));
  outputs.push_back(c.output.dir / report_file_name(c.shard));
  if (c.shard.sharded()) {  // what merge writes from the shards
    outputs.push_back(c.output.dir / summary_file_name({}));
    outputs.push_back(c.output.dir / report_file_name({}));
  }
  for (int index : plan.run_frames)
    outputs.push_back(record_file(c.output.dir, plan.source->name(index)));
  refuse_overwriting_inputs(inputs, outputs);
}

}  // namespace

// Refuses two selected frames whose outputs would have the same name, letter case aside (a.obj
// and a.OBJ both write records/a.json): one would overwrite the other, which one varying from run
// to run, on any file system, and on a case-insensitive one (macOS, Windows shares) also their
// frames/ files.
void check_output_names(const SequencePlan& plan) {
  const auto folded = [](const fs::path& p) {
    std::string s = p.generic_string();
    for (char& ch : s)
      if (ch >= 'A' && ch <= 'Z') ch = static_cast<char>(ch - 'A' + 'a');
    return s;
  };
  const auto label = [&](int i) {
    return frame_label(i, plan.source->name(i), std::nullopt);
  };
  // folded name -> (frame, exact name). Two frames' records with one folded name collide; an
  // output file collides when the folded names agree and the exact ones differ (an output's
  // file shared by every frame, such as the checker's material, has one exact name).
  std::map<std::string, std::pair<int, std::string>> writer;
  const auto claim = [&](const fs::path& file, int index, bool shared_ok) {
    const std::string exact = file.generic_string();
    const auto [at, fresh] = writer.emplace(folded(file), std::make_pair(index, exact));
    if (fresh || at->second.first == index || (shared_ok && at->second.second == exact)) return;
    throw InputError("frames " + label(at->second.first) + " and " + label(index) +
                     " would both write " + exact +
                     " (their output names differ only in letter case or extension): one "
                     "would overwrite the other; rename one of them");
  };
  for (int index : plan.selected) {
    const std::string name = plan.source->name(index);
    claim(fs::path("records") / fs::path(name).replace_extension(".json"), index, false);
    for (const auto& output : plan.outputs)
      for (const fs::path& file : output->files({index}))
        claim(file.lexically_relative(plan.config.output.dir), index, true);
  }
}

SequencePlan plan_sequence_job(const SequenceJobOptions& config) {
  SequencePlan plan;
  plan.config = config;
  const SequenceJobOptions& c = plan.config;
  plan.threads = c.threads > 0 ? c.threads : std::max(1, tbb::info::default_concurrency());
  plan.frames_in_flight = c.frames_in_flight > 0 ? c.frames_in_flight : 2 * plan.threads;

  std::shared_ptr<const GltfSequence> gltf;
  plan.source = make_frame_source(c, &gltf);
  plan.outputs = make_frame_outputs({c, plan.source, [gltf] { return gltf; }});
  const int count = plan.source->size();
  plan.selected = select_frames(c.input.range, count);
  plan.run_frames = shard_frames(plan.selected, c.shard);
  check_output_names(plan);
  for (const auto& output : plan.outputs)
    for (std::string& warning : output->check(plan.selected))
      plan.warnings.push_back(std::move(warning));

  if (c.templ.mesh.empty()) {
    if (c.templ.frame >= count)
      throw ConfigError("template.frame: " + std::to_string(c.templ.frame) +
                        " is out of range (the sequence has " + std::to_string(count) +
                        " frames, 0 to " + std::to_string(count - 1) + ")");
    plan.template_frame = c.templ.frame;
    plan.template_source = plan.source->label(plan.template_frame);
    plan.templ = plan.source->template_frame(plan.template_frame);
  } else {
    plan.template_source = c.templ.mesh.filename().string();
    plan.templ = read_mesh(c.templ.mesh);
  }
  if (!c.massage.vertex_weights_file.empty())
    plan.config.massage.vertex_weights = read_vertex_weights(
        c.massage.vertex_weights_file, plan.templ.num_vertices(), plan.template_source);
  plan.processor = std::make_shared<const FrameProcessor>(plan.templ, c, plan.template_source,
                                                          plan.template_frame);
  // Frames have the template's triangles (the Massager has validated them): a spacing beyond the
  // sampling budget on the template is refused before any frame is read.
  with_option_path("measures", [&] {
    check_distance_samples(plan.templ, c.measures, "the template, " + plan.template_source);
  });
  const Massager& massager = plan.processor->massager();
  plan.config_hash = frame_config_hash(c);
  plan.template_hash = template_hash(plan.templ);

  const MeshReport report = check_mesh(plan.templ, massager.topology());
  if (!report.ok_for_optimization())
    plan.warnings.push_back("template (" + plan.template_source + "): " + report.describe());
  if (const int fallback = massager.weights().fallback_vertices; fallback > 0)
    plan.warnings.push_back("template (" + plan.template_source + "): " + std::to_string(fallback) +
                            " vertices with degenerate corners use uniform weights");
  if (c.input.range.stop && *c.input.range.stop > count)
    plan.warnings.push_back("input.range.stop " + std::to_string(*c.input.range.stop) +
                            " is past the last frame; the sequence has " + std::to_string(count));

  if (plan.source->needs_check()) {
    tbb::task_arena arena(plan.threads);
    check_frames(plan, arena);
  }
  check_outputs(plan);
  return plan;
}

std::string describe_plan(const SequencePlan& plan) {
  const SequenceJobOptions& c = plan.config;
  std::ostringstream s;
  s << "job: sequence\n";
  s << "input: " << plan.source->describe() << "\n";
  s << "frames: " << plan.selected.size() << " selected (" << format_frame_range(c.input.range)
    << "): " << plan.source->name(plan.selected.front());
  if (plan.selected.size() > 1) s << " ... " << plan.source->name(plan.selected.back());
  s << "\n";
  if (c.shard.sharded()) {
    s << shard_label(c.shard) << ": " << plan.run_frames.size() << " frames";
    if (!plan.run_frames.empty()) {
      s << ": " << plan.source->name(plan.run_frames.front());
      if (plan.run_frames.size() > 1) s << " ... " << plan.source->name(plan.run_frames.back());
    }
    s << "\n";
  }
  if (c.resume) {
    int current = 0;  // records of this config and template (inputs and outputs checked at run)
    for (int index : plan.run_frames) {
      const auto r = read_frame_record(record_file(c.output.dir, plan.source->name(index)));
      current += r && r->config_hash == plan.config_hash && r->template_hash == plan.template_hash;
    }
    s << "resume: " << current << " of " << plan.run_frames.size()
      << " frames have a record of this config and template (skipped if their input and "
         "outputs are unchanged)\n";
  }
  s << "template: " << plan.template_source << ", " << plan.templ.num_vertices() << " vertices, "
    << plan.templ.num_triangles() << " triangles";
  if (plan.template_frame >= 0)
    s << (c.templ.optimize ? "; optimized like the others" : "; written unchanged");
  s << "\n";
  s << "massage: " << massage_text(c.massage) << "\n";
  if (c.measures.adaptive)
    s << "distances (summary.csv): adaptive, at the vertices and centroids, then"
      << (c.measures.sample_edges ? " along the edges" : "")
      << (c.measures.sample_edges && c.measures.sample_faces ? " and" : "")
      << (c.measures.sample_faces ? " inside" : "") << " the triangles above "
      << format_number(c.measures.refine_above) << " of the maximum, samples every "
      << format_number(c.measures.spacing) << " mean edge lengths\n";
  else
    s << "distances (summary.csv): samples every " << format_number(c.measures.spacing)
      << " mean edge lengths, at the vertices"
      << (c.measures.sample_edges ? ", along the edges" : "")
      << (c.measures.sample_faces ? ", inside the triangles" : "") << "\n";
  s << "threads: " << plan.threads << ", frames in flight: " << plan.frames_in_flight << "\n";
  s << "output: " << c.output.dir.string() << "\n";
  for (const auto& output : plan.outputs) s << output->describe(plan.run_frames);
  s << "  records/<name>.json (" << plan.run_frames.size() << " files)\n";
  s << "  " << summary_file_name(c.shard) << ", " << report_file_name(c.shard) << "\n";
  for (const std::string& w : plan.warnings) s << "warning: " << w << "\n";
  return s.str();
}

}  // namespace sm
