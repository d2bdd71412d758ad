// The output registry (pipeline/outputs/frame_output.hpp) against what the job really does: the
// files each output predicts are the files on disk after a run, every registered output is
// exercised, a stopped-and-resumed run and a sharded-and-merged one write the bytes of a whole
// run, and every output's --help names config keys that exist in the options table.
#include <catch2/catch.hpp>

#include <atomic>
#include <map>
#include <regex>
#include <set>

#include "io/atomic_file.hpp"
#include "pipeline/cluster/frame_record.hpp"
#include "pipeline/cluster/merge.hpp"
#include "pipeline/sequence/shard.hpp"
#include "pipeline/outputs/frame_output.hpp"
#include "pipeline/run/sequence_job.hpp"
#include "support/gltf_models.hpp"
#include "support/sequence_fixture.hpp"
#include "support/temp_dir.hpp"

using namespace sm;
namespace fs = std::filesystem;

namespace {

// `c` with every output that does not depend on output.format on.
SequenceJobOptions registry_all_on(SequenceJobOptions c) {
  c.output.per_triangle_csv = true;
  c.output.displacement_csv = true;
  c.output.colored.enabled = true;
  c.output.checker.enabled = true;
  c.output.iterations.enabled = true;
  c.output.html = true;
  c.output.timings = false;  // every byte reproducible
  return c;
}

// A drifted tube of `frames` frames read from dir/in, every output on, writing dir/out.
SequenceJobOptions registry_tube_job(const fs::path& dir, int frames) {
  SequenceJobOptions c = registry_all_on(test::tube_job(dir, test::small_tube(frames)));
  c.massage.iterations = 4;
  return c;
}

// The skinned strip as a GLB at dir/strip.glb (1 s of animation at `fps`), every output on.
SequenceJobOptions registry_gltf_job(const fs::path& dir, double fps) {
  fs::create_directories(dir);
  test::skinned_strip().save(dir / "strip.glb", true);
  SequenceJobOptions c;
  c.input.gltf = GltfInputOptions{dir / "strip.glb", "", "", fps};
  c.output.dir = dir / "out";
  c.massage.iterations = 3;
  c.threads = 2;
  c.checks.max_folded_fraction.reset();  // the strip folds at its sharpest bend (gltf tests)
  return registry_all_on(c);
}

// What the plan says a run writes, relative to output.dir: every enabled output's files() for
// the run's frames, and what the job itself writes for every run (as check_outputs in
// sequence_plan.cpp lists it): the summary, the report (a shard's, and the merged ones) and one
// record per frame.
std::set<std::string> registry_predicted(const SequencePlan& plan) {
  const SequenceJobOptions& c = plan.config;
  std::set<std::string> files;
  const auto add = [&](const fs::path& file) {
    INFO(file);
    const fs::path rel = file.lexically_relative(c.output.dir);
    CHECK_FALSE(rel.empty());
    CHECK(*rel.begin() != "..");  // predicted outside output.dir
    files.insert(rel.generic_string());
  };
  for (const auto& output : plan.outputs)
    for (const fs::path& file : output->files(plan.run_frames)) add(file);
  add(c.output.dir / summary_file_name(c.shard));
  add(c.output.dir / report_file_name(c.shard));
  if (c.shard.sharded()) {  // what merge writes from the shards
    add(c.output.dir / summary_file_name({}));
    add(c.output.dir / report_file_name({}));
  }
  for (int index : plan.run_frames) add(record_file(c.output.dir, plan.source->name(index)));
  return files;
}

// The regular files under output.dir after a run, relative to it. Left out: the frames a
// synthetic input generates, input/ (the frames read) and ground_truth/ (their clean frames),
// which are the input's, not an output's. Not left out: the lock files (.seqmassage*.lock,
// pipeline/cluster/output_lock.hpp), which the run removes when it ends; one left behind fails.
std::set<std::string> registry_written(const SequenceJobOptions& c) {
  std::set<std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(c.output.dir)) {
    const std::string rel = fs::relative(entry.path(), c.output.dir).generic_string();
    if (c.input.synthetic && (rel.rfind("input/", 0) == 0 || rel.rfind("ground_truth/", 0) == 0))
      continue;
    INFO(rel);
    CHECK((entry.is_regular_file() || entry.is_directory()));  // no link, no socket
    if (entry.is_regular_file()) files.insert(rel);
  }
  return files;
}

std::vector<std::string> registry_minus(const std::set<std::string>& a,
                                        const std::set<std::string>& b) {
  std::vector<std::string> out;
  std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

}  // namespace

TEST_CASE("every output predicts exactly the files a run writes") {
  test::TempDir dir("registry_files");
  std::vector<bool> exercised(output_registry().size(), false);

  struct Case {
    std::string name;
    SequenceJobOptions config;
    // What the plan names that this run does not write: for a shard, what `seqmassage merge`
    // writes from the shards (summary.csv, report.json, iterations.csv, report.html, the
    // assembled files).
    std::set<std::string> merged = {};
  };
  std::vector<Case> cases;
  cases.push_back({"obj frames and every per-frame output", registry_tube_job(dir / "obj", 4)});
  {
    SequenceJobOptions c = registry_tube_job(dir / "mdd", 4);
    c.output.format = OutputFormat::Mdd;
    cases.push_back({"mdd", c});
  }
  {
    // A synthetic input: its frames are generated under output.dir (left out above).
    SequenceJobOptions c = registry_all_on({});
    c.input.synthetic = test::small_tube(4);
    c.output.dir = dir / "pc2";
    c.massage.iterations = 4;
    c.threads = 2;
    c.output.format = OutputFormat::Pc2;
    cases.push_back({"pc2 on a synthetic input", c});
  }
  {
    SequenceJobOptions c = registry_gltf_job(dir / "gltf", 4.0);
    c.output.format = OutputFormat::Gltf;
    cases.push_back({"gltf", c});
  }
  {
    SequenceJobOptions c = registry_tube_job(dir / "shard", 4);
    c.shard = {0, 2};
    const std::set<std::string> merged = {"summary.csv", "report.json", "iterations.csv",
                                          "report.html"};
    cases.push_back({"shard 1/2, obj and every per-frame output", c, merged});
    c.output.format = OutputFormat::Pc2;
    c.output.dir = dir / "shard" / "out_pc2";
    std::set<std::string> merged_pc2 = merged;
    merged_pc2.insert({"sequence.pc2", "rest.obj"});
    cases.push_back({"shard 1/2, pc2", c, merged_pc2});
  }

  for (const Case& k : cases) {
    INFO("run: " << k.name);
    const SequencePlan plan = plan_sequence_job(k.config);
    for (size_t i = 0; i < output_registry().size(); ++i)
      if (output_registry()[i].enabled(k.config)) exercised[i] = true;
    const SequenceResult r = run_sequence_job(plan);
    REQUIRE_FALSE(r.interrupted);
    REQUIRE(r.failed == 0);
    const std::set<std::string> predicted = registry_predicted(plan);
    const std::set<std::string> written = registry_written(k.config);
    CHECK(written.size() > plan.run_frames.size() * 5);  // the outputs did write
    const std::vector<std::string> none;
    CHECK(registry_minus(written, predicted) == none);  // nothing written unpredicted
    const std::vector<std::string> merged(k.merged.begin(), k.merged.end());
    CHECK(registry_minus(predicted, written) == merged);  // nothing predicted missing
  }

  // A registered output that no case above turns on fails here: add a run that enables it.
  for (size_t i = 0; i < output_registry().size(); ++i) {
    INFO("registry entry " << i << ":\n" << output_registry()[i].help());
    CHECK(exercised[i]);
  }
}

namespace {

// Runs `c` whole (into `whole`), stopped after `stop_after` frames and resumed (into `resumed`),
// and as shards 1/2 and 2/2 merged (into output.dir); checks that the three folders hold the same
// files with the same bytes, the shards' own files aside.
void registry_resume_and_merge(SequenceJobOptions c, int stop_after) {
  c.frames_in_flight = 2;  // few frames in flight when the run is stopped (not in the records)
  const fs::path out = c.output.dir, whole = out.parent_path() / "whole",
                 resumed = out.parent_path() / "resumed";
  // One path for every run: report.json names output.dir.
  const SequenceResult first = run_sequence_job(plan_sequence_job(c));
  REQUIRE_FALSE(first.interrupted);
  REQUIRE(first.failed == 0);
  fs::rename(out, whole);

  std::atomic<bool> cancel{false};
  RunHooks hooks;
  hooks.cancel = &cancel;
  hooks.progress = [&](const FrameSummary&, int done, int, double) {
    if (done == stop_after) cancel = true;
  };
  const SequenceResult stopped = run_sequence_job(plan_sequence_job(c), hooks);
  REQUIRE(stopped.interrupted);
  CHECK(stopped.frames.size() < first.frames.size());
  c.resume = true;
  const SequenceResult again = run_sequence_job(plan_sequence_job(c));
  CHECK_FALSE(again.interrupted);
  CHECK(again.resumed == int(stopped.frames.size()));
  fs::rename(out, resumed);

  c.resume = false;
  for (int i = 0; i < 2; ++i) {
    c.shard = {i, 2};
    REQUIRE_FALSE(run_sequence_job(plan_sequence_job(c)).interrupted);
  }
  merge_shards(out);

  // Everything compared, report.json included: with output.timings false the resumed and merged
  // reports are the whole run's, byte for byte (as in test_resume_merge.cpp).
  const auto files = test::compare_folders(whole, resumed);
  test::compare_folders(whole, out, ".shard-");
  // The comparison covered every output's files.
  std::set<std::string> names;
  for (const auto& [name, bytes] : files) names.insert(name.substr(0, name.find('/')));
  for (const char* name : {"summary.csv", "report.json", "report.html", "report_data",
                           "iterations.csv", "distortion", "displacement", "colored", "checker",
                           "records"})
    CHECK(names.count(name));
  const OutputFormat format = c.output.format;
  CHECK(names.count("frames") == (format == OutputFormat::Obj));
  CHECK(names.count("positions") == (format != OutputFormat::Obj));
  CHECK(names.count("sequence.glb") == (format == OutputFormat::Gltf));
  CHECK(names.count("sequence.pc2") == (format == OutputFormat::Pc2));
  CHECK(names.count("rest.obj") == (format == OutputFormat::Pc2));
}

}  // namespace

TEST_CASE("every output: a resumed run and merged shards write the bytes of a whole run") {
  test::TempDir dir("registry_resume");
  SECTION("obj frames") {
    registry_resume_and_merge(registry_tube_job(dir.path(), 7), 3);
  }
  SECTION("pc2") {
    SequenceJobOptions c = registry_tube_job(dir.path(), 7);
    c.output.format = OutputFormat::Pc2;
    registry_resume_and_merge(c, 3);
  }
  SECTION("gltf") {
    SequenceJobOptions c = registry_gltf_job(dir.path(), 8.0);  // 9 frames
    c.output.format = OutputFormat::Gltf;
    registry_resume_and_merge(c, 3);
  }
}

namespace {

// The output options table's line of `key`, or null.
const Field<OutputOptions>* registry_field(const std::string& key) {
  for (const Field<OutputOptions>& f : fields_of<OutputOptions>())
    if (f.info.key == key) return &f;
  return nullptr;
}

// Turns the on/off key `key` of `o` on or off through the options table (a bool, or an object
// with "enabled"); false if it is neither.
bool registry_toggle(OutputOptions& o, const std::string& key, bool on) {
  const Field<OutputOptions>* f = registry_field(key);
  if (!f) return false;
  ValueRef ref = f->ref(o);
  if (bool** b = std::get_if<bool*>(&ref)) {
    **b = on;
    return true;
  }
  if (ObjectRef* object = std::get_if<ObjectRef>(&ref);
      object && object->mode == ObjectRef::Mode::Toggle) {
    object->set_present(object->target, on);
    return true;
  }
  return false;
}

// Every on/off key of the output options table, off.
SequenceJobOptions registry_all_off() {
  SequenceJobOptions c;
  for (const Field<OutputOptions>& f : fields_of<OutputOptions>())
    registry_toggle(c.output, std::string(f.info.key), false);
  return c;
}

}  // namespace

TEST_CASE("every output's --help names keys of the output options, which turn it on") {
  // The format choices, from the table's "format" line.
  const Field<OutputOptions>* format = registry_field("format");
  REQUIRE(format);
  std::map<std::string, int> formats;
  for (const auto& [name, value] : format->info.spec.names) formats[std::string(name)] = value;
  REQUIRE(formats.size() >= 2);
  const auto set_format = [&](SequenceJobOptions& c, int value) {
    ValueRef ref = format->ref(c.output);
    const ChoiceRef& choice = std::get<ChoiceRef>(ref);
    choice.set(choice.value, value);
  };

  // A quoted word of the help text: "(\"colored\")", "\"format\": \"gltf\"".
  const std::regex quoted("\"([^\"]*)\"");
  const std::regex json_value(R"(:\s*["{\[0-9tfn-])");
  for (const OutputEntry& entry : output_registry()) {
    const std::string help = entry.help();
    INFO("help:\n" << help);
    std::set<std::string> keys, named_formats;
    for (auto it = std::sregex_iterator(help.begin(), help.end(), quoted);
         it != std::sregex_iterator(); ++it) {
      const std::string word = (*it)[1];
      const size_t at = size_t(it->position(0)), end = at + size_t(it->length(0));
      // A key: right after "(", or a JSON key (a colon, then a value: `"format": "gltf"`); not
      // a word before a colon of the prose (`"pc2" or "mdd": each frame's`).
      const bool key_position =
          (at > 0 && help[at - 1] == '(') ||
          std::regex_search(help.begin() + long(end), help.end(), json_value,
                            std::regex_constants::match_continuous);
      INFO("quoted: \"" << word << "\"");
      if (key_position) {
        CHECK(registry_field(word) != nullptr);  // a key of the output options
        keys.insert(word);
      } else {
        CHECK(formats.count(word));  // not a key: one of the format choices
        named_formats.insert(word);
      }
    }
    REQUIRE(keys.size() == 1);  // the key that turns the output on
    const std::string key = *keys.begin();
    if (key == "format") {
      // The formats it names are exactly those that enable it.
      REQUIRE_FALSE(named_formats.empty());
      for (const auto& [name, value] : formats) {
        INFO("output.format \"" << name << "\"");
        SequenceJobOptions c;
        set_format(c, value);
        CHECK(entry.enabled(c) == bool(named_formats.count(name)));
      }
    } else {
      CHECK(named_formats.empty());
      SequenceJobOptions c = registry_all_off();
      CHECK_FALSE(entry.enabled(c));
      REQUIRE(registry_toggle(c.output, key, true));  // an on/off key
      CHECK(entry.enabled(c));
    }
  }
}
