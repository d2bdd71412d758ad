// CSV formatting and the tables and report of a sequence job.
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <sstream>
#include <limits>

#include "io/csv.hpp"
#include "pipeline/outputs/output_distortion.hpp"
#include "pipeline/report/report.hpp"

using namespace sm;

TEST_CASE("numbers are written in their shortest exact form") {
  CHECK(format_number(0.1) == "0.1");
  CHECK(format_number(12.0) == "12");
  CHECK(format_number(-2.5) == "-2.5");
  CHECK(format_number(1e-7) == "1e-07");
  CHECK(format_number(0.0) == "0");
  CHECK(format_number(-0.0) == "0");
  CHECK(format_number(std::numeric_limits<double>::infinity()) == "inf");
  CHECK(format_number(-std::numeric_limits<double>::infinity()) == "-inf");
  CHECK(format_number(std::nan("")) == "nan");
  for (double x : {M_PI, 1.0 / 3.0, 123456.789e-300, 6.02214076e23})
    CHECK(std::stod(format_number(x)) == x);
}

TEST_CASE("CSV fields are quoted only when needed") {
  CHECK(csv_field("plain") == "plain");
  CHECK(csv_field("a,b") == "\"a,b\"");
  CHECK(csv_field("say \"hi\"") == "\"say \"\"hi\"\"\"");
  CHECK(csv_field("two\nlines") == "\"two\nlines\"");
  CsvWriter csv({"a", "b", "c"});
  csv.cell(1).cell(0.5).cell("x,y").end_row();
  csv.cell(int64_t{2}).end_row();  // missing cells are empty
  CHECK(csv.str() == "a,b,c\n1,0.5,\"x,y\"\n2,,\n");
  CHECK(csv.rows() == 2);
}

namespace {

// The comma-separated list that docs/outputs.md gives, in backticks, after `marker` on the
// summary.csv row: the documentation is the contract the columns are checked against.
std::vector<std::string> documented_columns(const std::string& marker) {
  std::ifstream in(std::string(SEQMASSAGE_TEST_DIR) + "/../docs/outputs.md");
  REQUIRE(in);
  std::string line;
  while (std::getline(in, line) && line.rfind("| `summary.csv` |", 0) != 0) {
  }
  const size_t at = line.find(marker);
  REQUIRE(at != std::string::npos);
  const size_t open = line.find('`', at + marker.size());
  const size_t close = line.find('`', open + 1);
  REQUIRE(close != std::string::npos);
  std::vector<std::string> columns;
  std::stringstream list(line.substr(open + 1, close - open - 1));
  for (std::string c; std::getline(list, c, ',');) columns.push_back(c);
  return columns;
}

}  // namespace

TEST_CASE("summary.csv has the documented columns, in order") {
  const std::vector<std::string> documented = documented_columns("one row per frame:");
  REQUIRE(documented.size() >= 20);
  CHECK(summary_columns() == documented);
  // With a ground truth (generated input), the documented truth columns follow.
  std::vector<std::string> truth = documented;
  for (const std::string& c : documented_columns("the columns")) truth.push_back(c);
  REQUIRE(truth.size() > documented.size());
  CHECK(summary_columns(true) == truth);
}

TEST_CASE("summary rows: failures with their reason, non-finite values, timings") {
  FrameSummary ok;
  ok.frame = 3;
  ok.file = "frame_0003.obj";
  ok.vertices = 10;
  ok.triangles = 16;
  ok.shear_before = {0.5, 0.25, 0.4, 0};
  ok.shear_after = {std::numeric_limits<double>::infinity(), 0.125, 0.2, 1};
  ok.out_to_in.max = 0.01;
  ok.out_to_in.rms = 0.005;
  ok.in_to_out.max = 0.02;
  ok.in_to_out.rms = 0.0025;
  ok.iterations = 15;
  ok.seconds = 1.5;
  FrameSummary failed = ok;
  failed.frame = 4;
  failed.file = "frame,4.obj";
  failed.status = FrameStatus::Failed;
  failed.failure = "iteration 2: the solution contains NaN";
  failed.time = 0.125;  // a glTF frame's time; empty for frames without one
  failed.folded_triangles = 7;
  const std::string header =
      "frame,file,vertices,triangles,shear_max_before,shear_mean_before,shear_p95_before,"
      "shear_max_after,shear_mean_after,shear_p95_after,dist_out_to_in_max,dist_out_to_in_rms,"
      "dist_in_to_out_max,dist_in_to_out_rms,iterations,seconds,status,failure,time,"
      "folded_triangles\n";
  CHECK(format_summary_csv({ok, failed}, true) ==
        header +
            "3,frame_0003.obj,10,16,0.5,0.25,0.4,inf,0.125,0.2,0.01,0.005,0.02,0.0025,15,1.5,"
            "optimized,,,0\n"
            "4,\"frame,4.obj\",10,16,0.5,0.25,0.4,inf,0.125,0.2,0.01,0.005,0.02,0.0025,15,1.5,"
            "failed,iteration 2: the solution contains NaN,0.125,7\n");
  const std::string untimed = format_summary_csv({ok}, false);
  CHECK(untimed.find(",15,0,optimized,") != std::string::npos);
}

TEST_CASE("per-triangle distortion tables") {
  Eigen::VectorXd before(3), after(3);
  before << 0.5, 0.0, std::numeric_limits<double>::infinity();
  after << 0.25, 0.0, 1.0;
  CHECK(format_distortion_csv(before, after) ==
        "triangle,shear_before,shear_after\n0,0.5,0.25\n1,0,0\n2,inf,1\n");
}

TEST_CASE("versions name the libraries") {
  const nlohmann::json v = version_info();
  for (const char* key : {"seqmassage", "eigen", "onetbb", "nlohmann_json", "compiler"})
    CHECK(v.contains(key));
  CHECK(v["eigen"].get<std::string>().rfind("3.", 0) == 0);
}
