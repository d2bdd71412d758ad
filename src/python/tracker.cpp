/// seqmassage.Tracker: one template tracked through frames of any connectivity (track/tracker.hpp)
/// from numpy arrays. The template and every frame are welded by position first (vertices split
/// along texture seams become one); the positions come back on the template's own vertices.
#include <string>
#include <utility>
#include <vector>

#include "io/gltf/gltf_weld.hpp"
#include "io/options_json.hpp"
#include "core/errors.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"
#include "track/tracker.hpp"
#include "massage/massage_keys.hpp"

namespace sm::python {
namespace {

namespace fs = std::filesystem;

py::dict figures_dict(const FitFigures& f) {
  py::dict d;
  d["to_raw_mean"] = f.to_raw_mean;
  d["to_raw_p99"] = f.to_raw_p99;
  d["to_raw_max"] = f.to_raw_max;
  d["from_raw_mean"] = f.from_raw_mean;
  d["from_raw_p99"] = f.from_raw_p99;
  d["from_raw_max"] = f.from_raw_max;
  d["folded"] = f.folded;
  d["shear_mean"] = f.shear_mean;
  d["shear_max"] = f.shear_max;
  return d;
}

class PyTracker {
 public:
  PyTracker(const py::handle& template_vertices, const py::handle& triangles,
            const py::kwargs& kwargs) {
    py::dict keys = kwargs.attr("copy")().cast<py::dict>();
    MassageOptions massage = refinement_massage_options();
    if (keys.contains("massage")) {
      read_options(to_json(keys.attr("pop")("massage"), "massage"), massage, fs::current_path(),
                   "massage");
    }
    TrackOptions options;
    read_options(to_json(keys, "track"), options, fs::current_path(), "track");
    const Positions V = to_positions(template_vertices, "template_vertices");
    const Triangles F = to_triangles(triangles, "triangles");
    validate_mesh(TriMesh{V, F}, "template");
    weld_ = weld_by_position(V, F);
    fallback_ = V;
    py::gil_scoped_release unlocked;
    tracker_ = with_option_path(
        "", [&] { return std::make_unique<Tracker>(weld_.mesh, options, massage); });
  }

  // One dict per frame: vertices (the template's, n×3), registered, status, recovery, fit and
  // registration_fit (dicts of figures in template edge lengths), iterations, timings.
  py::list track(const py::iterable& frames) {
    py::list out;
    int index = 0;
    for (const py::handle& item : frames) {
      const std::string who = "frames[" + std::to_string(index) + "]";
      if (!py::isinstance<py::sequence>(item) || py::len(item) != 2)
        throw InputError(who + ": expected a mesh (vertices, triangles)");
      const py::sequence mesh = item.cast<py::sequence>();
      const Positions V = to_positions(mesh[0], (who + " vertices").c_str());
      const Triangles F = to_triangles(mesh[1], (who + " triangles").c_str());
      validate_mesh(TriMesh{V, F}, who.c_str());
      TrackFrame f;
      {
        py::gil_scoped_release unlocked;
        const GltfWeld raw = weld_by_position(V, F);
        if (raw.mesh.num_triangles() == 0) throw InputError(who + ": the frame has no triangles");
        f = tracker_->track(raw.mesh);
      }
      py::dict d;
      d["vertices"] = to_numpy(unweld_frame(weld_.map, f.V, fallback_));
      d["registered"] = to_numpy(unweld_frame(weld_.map, f.registered, fallback_));
      d["status"] = std::string(name_of(f.status, kTrackStatusNames));
      d["recovery"] = f.recovery;
      d["fit"] = figures_dict(f.fit);
      d["registration_fit"] = figures_dict(f.registration_fit);
      d["iterations"] = f.iterations;
      d["seconds_register"] = f.seconds_register;
      d["seconds_refine"] = f.seconds_refine;
      out.append(d);
      ++index;
    }
    return out;
  }

  void reset() { tracker_->reset(); }
  double mean_edge() const { return tracker_->mean_edge(); }
  int num_nodes() const { return tracker_->num_nodes(); }

 private:
  GltfWeld weld_;
  Positions fallback_;
  std::unique_ptr<Tracker> tracker_;
};

}  // namespace

void bind_tracker(py::module_& m) {
  py::class_<PyTracker>(m, "Tracker",
                        "Tracks one template through frames of any connectivity: a deformation "
                        "graph fitted by robust non-rigid ICP, then Mesh Massage toward each "
                        "frame. Keyword options: the config's \"track\" keys, and massage=dict "
                        "of its \"massage\" keys.")
      .def(py::init<const py::handle&, const py::handle&, const py::kwargs&>(),
           py::arg("template_vertices"), py::arg("triangles"))
      .def("track", &PyTracker::track, py::arg("frames"),
           "Tracks the frames in order, an iterable of (vertices, triangles); returns one dict "
           "per frame: vertices, registered, status ('ok', 'recovered', 'lost'), recovery, fit "
           "and registration_fit (distances both ways in template edge lengths, folded, shear), "
           "iterations, seconds_register, seconds_refine. Continues from the last call.")
      .def("reset", &PyTracker::reset, "Forget the motion: the next frame starts at the template")
      .def_property_readonly("mean_edge", &PyTracker::mean_edge,
                             "the template's mean edge length, the unit of the figures")
      .def_property_readonly("num_nodes", &PyTracker::num_nodes,
                             "nodes of the deformation graph");
}

}  // namespace sm::python
