// Every example config in configs/ passes `seqmassage --dry-run` (the config and every input
// checked, the plan printed, nothing written). The examples that read ../shared/data are skipped
// with a message when that folder is absent, and so is configs/pc2_example.json until
// tools/make_pc2_example.sh has generated its input; configs/demo.json needs nothing from outside.
#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "config/config.hpp"
#include "io/atomic_file.hpp"
#include "support/cli_process.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;

TEST_CASE("every config in configs/ passes seqmassage --dry-run and writes nothing") {
  const fs::path configs = fs::path(SEQMASSAGE_TEST_DIR).parent_path() / "configs";
  const bool shared_data = fs::is_directory(SEQMASSAGE_SHARED_DATA_DIR);
  const sm::test::TempDir cwd("configs_dry_run");  // stdout and stderr go here, not configs/
  int checked = 0, skipped = 0;
  for (const auto& entry : fs::directory_iterator(configs)) {
    if (entry.path().extension() != ".json") continue;
    const std::string text = sm::read_file(entry.path());
    INFO(entry.path().string());
    if (!shared_data && text.find("shared/data") != std::string::npos) {
      WARN("skipped " << entry.path().filename().string()
                      << ": it reads ../shared/data, which is absent");
      ++skipped;
      continue;
    }
    const sm::AnyJobOptions any = sm::load_any_config(entry.path());
    if (const auto* sequence = std::get_if<sm::SequenceJobOptions>(&any)) {
      const auto cache = sequence->input.point_cache();
      if (cache && !fs::exists(cache->file)) {  // configs/pc2_example.json: generated input
        WARN("skipped " << entry.path().filename().string() << ": its input "
                        << cache->file.string()
                        << " is absent (tools/make_pc2_example.sh generates it)");
        ++skipped;
        continue;
      }
    }
    const fs::path out = std::visit([](const auto& job) { return job.output.dir; }, any);
    const bool existed = fs::exists(out);
    const sm::test::CliRun run =
        sm::test::run_cli(cwd.path(), "--dry-run " + sm::test::shell_quote(entry.path().string()));
    INFO(run.err);
    CHECK(run.code == 0);
    CHECK(run.out.find("dry run: nothing written") != std::string::npos);
    if (!existed) CHECK_FALSE(fs::exists(out));
    ++checked;
  }
  CHECK(checked + skipped >= 7);
  CHECK(checked >= 1);  // demo.json at least
}
