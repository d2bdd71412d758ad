#pragma once
/// `seqmassage measure MESH REFERENCE`: the paper's measures of any two mesh files, the same
/// report as the single-mesh jobs write, as text, CSV and JSON.
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "geometry/measures.hpp"

namespace sm {

struct MeasureFilesRequest {
  std::filesystem::path mesh;       ///< M (.obj, .off, .ply)
  std::filesystem::path reference;  ///< N
  /// T for the shear; empty: N when it has M's connectivity, else no shear.
  std::filesystem::path templ;
  std::filesystem::path csv;   ///< write the CSV row here (empty: not written)
  std::filesystem::path json;  ///< write the JSON here (empty: not written)
  MeasureOptions options;
  int threads = 0;  ///< 0 = one per core
};

struct MeasureFilesResult {
  MeshMeasures measures;
  QualitySummary reference_quality;
  std::string table;  ///< the text report (format_measures_table)
  std::string csv;    ///< measures.csv with one row, stage "measure"
  nlohmann::json json;
};

/// Reads the files, measures M against N (and T), writes the CSV and JSON files when asked (each
/// atomically). Throws ConfigError if an output would overwrite an input, InputError for a
/// malformed mesh or a template of another connectivity, IoError for unreadable or unwritable
/// files.
MeasureFilesResult measure_files(const MeasureFilesRequest& request);

}  // namespace sm
