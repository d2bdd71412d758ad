#pragma once
/// Tracking one template through an untracked capture (frames of any connectivity): per frame,
/// the template's deformation graph is fitted to the raw frame by non-rigid ICP (graph_fit.hpp),
/// started from the previous frame's fit continued by its motion, then Mesh Massage (paper §3.3:
/// T = the template, M starts at the registered positions, N = the raw frame) puts the vertices
/// on the captured surface with the template's triangle shapes. A frame whose fit figures exceed
/// the tolerances is re-registered (from the last good frame with a wider search, then from the
/// template rigidly aligned) and marked `lost` if that fails too; the next frame then starts from
/// the last good frame, so an error is never carried forward.
#include <memory>
#include <string>
#include <vector>

#include "massage/massage.hpp"
#include "track/deformation_graph.hpp"
#include "track/graph_fit.hpp"
#include "track/track_options.hpp"

namespace sm {

enum class TrackStatus {
  Ok,         ///< within the tolerances at the first attempt
  Recovered,  ///< within the tolerances after re-registration
  Lost,       ///< beyond them even after re-registration: the best attempt is kept
};
inline constexpr EnumName<TrackStatus> kTrackStatusNames[] = {
    {"ok", TrackStatus::Ok}, {"recovered", TrackStatus::Recovered}, {"lost", TrackStatus::Lost}};

/// Distances between a tracked frame and its raw frame, in mean edge lengths of the template.
struct FitFigures {
  double to_raw_mean = 0, to_raw_p99 = 0, to_raw_max = 0;        ///< tracked vertices → raw
  double from_raw_mean = 0, from_raw_p99 = 0, from_raw_max = 0;  ///< raw vertices → tracked
  int folded = 0;           ///< tracked triangles whose normal opposes the raw surface's
  double shear_mean = 0;    ///< eq. 8 against the template, mean over finite triangles
  double shear_max = 0;
};

struct TrackFrame {
  Positions V;            ///< tracked positions (n×3, the template's vertices)
  Positions registered;   ///< after the registration only (n×3)
  FitFigures fit;         ///< of V
  FitFigures registration_fit;  ///< of `registered`
  TrackStatus status = TrackStatus::Ok;
  std::string recovery;   ///< "", "last_good" or "template": which re-registration was kept
  int iterations = 0;     ///< ICP iterations, all attempts
  bool refine_ok = true;  ///< the Mesh Massage run succeeded (else V is `registered`)
  double seconds_register = 0, seconds_refine = 0;
};

/// The figures of positions V (template connectivity) against a raw frame.
FitFigures measure_fit(const TriMesh& templ, const Positions& V, const RawFrame& raw,
                       double mean_edge);

class Tracker {
 public:
  /// `templ`: the template, welded (one vertex per surface point); its mean edge length is the
  /// unit of every length option. Throws InputError for a template without triangles, OptionError
  /// for out-of-range options (key "track.<member>" or "massage.<member>").
  Tracker(TriMesh templ, TrackOptions options,
          MassageOptions massage = refinement_massage_options());
  ~Tracker();
  Tracker(Tracker&&) noexcept;

  /// Tracks the next frame (welded mesh of any connectivity). Frames must come in order; the
  /// first is registered from the template as it is placed.
  TrackFrame track(const TriMesh& raw);
  /// Forgets the motion: the next frame starts from the template as placed.
  void reset();
  /// Starts the next frame from a given fit (e.g. a shard's neighbour), without motion.
  void restart_from(const std::vector<NodeMap>& X);
  const std::vector<NodeMap>& last_fit() const;

  const TriMesh& templ() const;
  double mean_edge() const;
  int num_nodes() const;
  const TrackOptions& options() const;

 private:
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace sm
