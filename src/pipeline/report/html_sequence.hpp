#pragma once
/// The data of report.html for a sequence: the player's template and frames as the run keeps
/// them (report_data/template.bin and report_data/<frame>.bin, written by HtmlReportOutput), and
/// the page assembled from them within a size budget.
///
/// On the page the positions are quantised to 16 bits per coordinate against the bounding box of
/// every kept frame (input and output), the shear (eq. 8) to 8 bits on one scale for both sides
/// (0 to the largest p95 of the input frames; 255 also for degenerate triangles), the triangles
/// and the corner texture coordinates stored once; every block in base64.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "mesh/mesh.hpp"
#include "pipeline/sequence/frame_summary.hpp"
#include "pipeline/report/html_page.hpp"

namespace sm {

/// What the player shows of the template: its triangles (m×3) and the checker's texture
/// coordinates of every corner (6m floats: u, v per corner, triangle by triangle).
struct PlayerTemplate {
  int vertices = 0;
  Triangles F;
  std::vector<float> corner_uv;
  std::string uv_source;  ///< "input" (the template's own) or "charts" (checker.hpp's chart_uv)
};
std::string encode_player_template(const PlayerTemplate& t);
/// Throws InputError naming `file` when the bytes are not a template of this format.
PlayerTemplate decode_player_template(const std::string& bytes, const std::string& file);

/// One frame: input and output positions (n×3, float32, row by row) and the shear of every
/// triangle before and after (m values, float32).
struct PlayerFrame {
  std::vector<float> in, out, shear_before, shear_after;
};
std::string encode_player_frame(const Positions& in, const Positions& out,
                                const Eigen::VectorXd& shear_before,
                                const Eigen::VectorXd& shear_after);
/// Throws InputError naming `file` unless the bytes are a frame of `vertices` and `triangles`.
PlayerFrame decode_player_frame(const std::string& bytes, int vertices, int triangles,
                                const std::string& file);

/// What the sequence's page is made of.
struct SequencePageInput {
  std::string title;
  std::string summary_csv;  ///< summary.csv's text, which the page's table and plots read
  const std::vector<FrameSummary>* frames = nullptr;  ///< every frame of the run, in order
  std::vector<std::string> warnings;
  nlohmann::json config, versions;
  double fps = 24.0;
  int checker_cells = 8;  ///< squares per unit of the texture coordinates
  /// The player's data: the template and the frames with data (their indices, in order), each
  /// read by `load(k)` (k into data_frames; called twice per kept frame); no frame: no player
  /// (player_note says why).
  std::function<PlayerTemplate()> load_template;
  std::vector<int> data_frames;
  std::function<PlayerFrame(size_t k)> load;
  std::string player_note;
  /// What the player's colours show: "shear" (eq. 8, 0 to the largest input p95) or "radius
  /// ratio" (0 to 1, the mesh jobs' quality).
  std::string colour = "shear";
  double colour_scale = 0;  ///< > 0: the colour scale's top, instead of the frames' p95
  std::string kind = "sequence";  ///< "sequence" or "mesh" (the page's plots)
  size_t budget_bytes = 50u << 20;
};

/// The page and what it left out.
struct SequencePage {
  std::string html;
  int frames_kept = 0;   ///< frames in the player
  int frames_total = 0;  ///< frames with data
  std::vector<std::string> warnings;
};

/// Reads the data files, chooses the frames that fit the budget (evenly spaced, first and last
/// kept) and renders the page; the page holds at most budget_bytes. Throws InputError for a data
/// file of another format or size.
SequencePage make_sequence_page(const SequencePageInput& input);

/// The frames kept when only `fit` of `total` fit: all, or `fit` evenly spaced indices into
/// 0..total-1 (rounded, first and last included), increasing.
std::vector<int> evenly_spaced(int total, int fit);

}  // namespace sm
