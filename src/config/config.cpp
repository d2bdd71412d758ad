#include "config/config.hpp"

#include <algorithm>

#include "io/atomic_file.hpp"
#include "pipeline/sequence/input_kinds.hpp"

namespace sm {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

bool has(const json& object, const std::string& key) {
  return object.is_object() && object.contains(key);
}

const json& member(const json& object, const std::string& key) {
  static const json absent;
  return has(object, key) ? object.at(key) : absent;
}

// Checks the keys of `object` at `path` against those of `options` (a single-mesh job's); a key
// that only the sequence job's S has is refused with `note` ("only for "job": "sequence"; ...").
template <class S, class T>
void refuse_sequence_keys(const json& object, const std::string& path, T options,
                          const std::string& note) {
  S sequence;
  const std::vector<std::string> own = keys_of(entries_of(options));
  std::vector<std::string> known = own, refused;
  for (const std::string& key : keys_of(entries_of(sequence)))
    if (std::find(own.begin(), own.end(), key) == own.end()) refused.push_back(key);
  known.insert(known.end(), refused.begin(), refused.end());
  check_keys(object, path, known);
  for (const std::string& key : refused)
    if (has(object, key)) fail_at(path + "." + key, "only for \"job\": \"sequence\"; " + note);
}

void validate_input(const json& input, const InputOptions& in) {
  if (in.synthetic) check_synthetic_options(*in.synthetic);
  const std::optional<PointCacheInput> cache = in.point_cache();
  GltfInputOptions gltf_keys;
  if (!has(input, "gltf"))
    for (const std::string& key : keys_of(entries_of(gltf_keys)))
      if (has(input, key) && !(cache && key == "mesh"))
        fail_at(
            "input." + key,
            "only applies to a glTF input (\"gltf\": a .gltf or .glb animation file)" +
                std::string(key == "mesh" ? "; or the mesh of a \"pc2\" or \"mdd\" cache" : ""));
  int given = 0;
  std::string keys;  // "frames", "synthetic", ... and "mdd"
  const std::vector<InputKind>& kinds = input_kinds();
  for (size_t k = 0; k < kinds.size(); ++k) {
    given += int(has(input, kinds[k].key));
    keys += std::string(k == 0 ? "" : k + 1 == kinds.size() ? " and " : ", ") + "\"" +
            kinds[k].key + "\"";
  }
  if (given == 0) fail_at("input", "missing (" + input_kinds_text() + ")");
  if (given > 1) fail_at("input", "give only one of " + keys);
  if (cache && cache->mesh.empty())
    fail_at("input.mesh",
            std::string("missing (the mesh the ") + (in.pc2 ? "\"pc2\"" : "\"mdd\"") +
                " cache's points belong to: a .obj, .ply or .off with its vertex count)");
}

// The rules across keys of the sequence job (the tables check each key on its own).
void validate(const json& doc, const SequenceJobOptions& c) {
  validate_input(doc.at("input"), c.input);
  const json& templ = member(doc, "template");
  if (has(templ, "frame") && has(templ, "mesh"))
    fail_at("template", "give \"frame\" or \"mesh\", not both");
  const bool cache_mesh = c.input.point_cache() && !has(templ, "frame");  // the template
  if ((has(templ, "mesh") || cache_mesh) && c.templ.optimize)
    fail_at(
        "template.optimize",
        "only applies to a template \"frame\" (with a rest \"mesh\", every frame is optimized)");
  if (c.input.synthetic) {
    if (has(templ, "mesh")) fail_at("template.mesh", "not available with input.synthetic");
    if (c.templ.frame >= c.input.synthetic->frames)
      fail_at("template.frame", std::to_string(c.templ.frame) +
                                    " is out of range (input.synthetic.frames is " +
                                    std::to_string(c.input.synthetic->frames) + ")");
  }
  if (c.output.format == OutputFormat::Gltf && !c.input.gltf)
    fail_at("output.format",
            "\"gltf\" needs a glTF input (input.gltf), whose mesh, materials and textures the "
            "output keeps; use \"obj\" for OBJ frames");
  if (has(doc.at("output"), "gltf") && c.output.format != OutputFormat::Gltf)
    fail_at("output.gltf", "only applies to output.format \"gltf\"");
  if (c.output.gltf.fps)
    fail_at("output.gltf.fps",
            "only for the track job's frames; a glTF input keeps its own frame times");
  if (has(doc.at("output"), "point_cache") && !point_cache_format(c.output.format))
    fail_at("output.point_cache", "only applies to output.format \"pc2\" or \"mdd\"");
  if (c.output.format == OutputFormat::Pc2 && c.output.on_failure == OnFailure::Skip)
    fail_at("output.on_failure",
            "\"skip\" cannot go with output.format \"pc2\": a PC2 cache is sampled at equal "
            "steps, so a frame left out would shift every later one; use \"copy_input\" (or "
            "\"mdd\", which stores each frame's time)");
}

// A point cache input's mesh is the template unless "template" names a frame or a mesh.
void resolve_template(const json& doc, SequenceJobOptions& c) {
  const std::optional<PointCacheInput> cache = c.input.point_cache();
  const json& templ = member(doc, "template");
  if (cache && !has(templ, "frame") && !has(templ, "mesh")) c.templ.mesh = cache->mesh;
}

// "input" and "template" of a single-mesh job, whose meaning depends on the job.
void read_mesh_job_input(const json& doc, MeshJobOptions& c, const fs::path& base) {
  const std::string job = job_name(c.job);
  if (!has(doc, "input"))
    fail_at("input", c.job == JobKind::Remesh
                         ? "missing (\"mesh\": the remesh, and \"reference\": its source)"
                         : "missing (\"mesh\": the mesh file to optimize)");
  const json& input = doc.at("input");
  refuse_sequence_keys<InputOptions>(input, "input", c.input,
                                     "the " + job + " job reads one mesh file from \"input.mesh\"");
  read_options(input, c.input, base, "input");
  if (c.job == JobKind::Remesh && !has(input, "reference"))
    fail_at("input.reference",
            "missing (the source surface the remesh approximates (.obj, .off or .ply))");
  if (c.job != JobKind::Remesh && has(input, "reference"))
    fail_at("input.reference", "only for \"job\": \"remesh\"; the " + job +
                                   " job keeps the mesh close to itself as loaded");

  if (c.job != JobKind::Crossparam && has(doc, "template"))
    fail_at("template", c.job == JobKind::Remesh
                            ? "not used by the remesh job (the remesh is its own template)"
                            : "not used by the smooth job (it uses uniform or mean value weights "
                              "of the mesh itself)");
  if (c.job != JobKind::Crossparam) return;
  if (!has(doc, "template"))
    fail_at("template",
            "missing (an object with \"mesh\": the source mesh whose triangle shapes are copied)");
  refuse_sequence_keys<TemplateOptions>(doc.at("template"), "template", c.templ,
                                        "the crossparam template is a \"mesh\" file");
}

// The rules across keys of the track job.
void validate_track(const json& doc, const TrackJobOptions& c) {
  const json& templ = member(doc, "template");
  if (has(templ, "frame") && has(templ, "mesh"))
    fail_at("template", "give \"frame\" or \"mesh\", not both");
  const json& output = doc.at("output");
  if (has(output, "gltf") && c.output.format != OutputFormat::Gltf) fail_at("output.gltf", "only applies to output.format \"gltf\"");
  if (has(output, "point_cache") && !point_cache_format(c.output.format))
    fail_at("output.point_cache", "only applies to output.format \"pc2\" or \"mdd\"");
  if (c.output.on_failure == OnFailure::Skip)
    fail_at("output.on_failure",
            "\"skip\" is not for the track job: a lost frame is written as its best attempt and "
            "listed in report.json");
  if (has(member(doc, "massage"), "iterations") &&
      c.massage.iterations != c.track.refine_iterations)
    fail_at("massage.iterations",
            "the track job's refinement runs track.refine_iterations iterations (" +
                std::to_string(c.track.refine_iterations) + "); set that instead");
}

}  // namespace

JobKind parse_job_kind(const json& document) {
  if (!document.is_object()) fail_at("", "expected an object, got " + describe(document));
  static const FieldInfo job{"job", choice(kJobKindNames), {}, {}};
  if (!has(document, "job"))
    fail_at("job",
            "missing (the kind of job: \"sequence\", \"remesh\", \"crossparam\", \"smooth\", or "
            "\"track\")");
  JobKind kind = JobKind::Sequence;
  read_value(document.at("job"), "job", {&job, options_detail::make_ref(kind)}, {}, {});
  return kind;
}

SequenceJobOptions parse_config(const json& document, const fs::path& base_dir) {
  SequenceJobOptions c;
  read_options(document, c, fs::absolute(base_dir).lexically_normal());
  validate(document, c);
  resolve_template(document, c);
  return c;
}

MeshJobOptions parse_mesh_job_config(const json& document, const fs::path& base_dir) {
  const fs::path base = fs::absolute(base_dir).lexically_normal();
  MeshJobOptions c;
  c.job = parse_job_kind(document);
  if (c.job == JobKind::Sequence || c.job == JobKind::Track)
    fail_at("job", "\"" + job_name(c.job) + "\" is not a single-mesh job");
  c.massage = default_massage_options(c.job);
  check_keys(document, "", keys_of(entries_of(c)));
  read_mesh_job_input(document, c, base);
  read_options(document, c, base);
  return c;
}

TrackJobOptions parse_track_config(const json& document, const fs::path& base_dir) {
  TrackJobOptions c;
  read_options(document, c, fs::absolute(base_dir).lexically_normal());
  validate_track(document, c);
  c.massage.iterations = c.track.refine_iterations;  // as report.json's resolved config says
  return c;
}

AnyJobOptions parse_any_config(const json& document, const fs::path& base_dir) {
  const JobKind kind = parse_job_kind(document);
  if (kind == JobKind::Sequence) return parse_config(document, base_dir);
  if (kind == JobKind::Track) return parse_track_config(document, base_dir);
  return parse_mesh_job_config(document, base_dir);
}

SequenceJobOptions load_config(const fs::path& path) {
  SequenceJobOptions options =
      parse_config(parse_json_strict(read_file(path)), fs::absolute(path).parent_path());
  options.config_file = path;
  return options;
}

AnyJobOptions load_any_config(const fs::path& path) {
  AnyJobOptions any =
      parse_any_config(parse_json_strict(read_file(path)), fs::absolute(path).parent_path());
  std::visit([&](auto& options) { options.config_file = path; }, any);
  return any;
}

}  // namespace sm
