/// seqmassage.shear() and seqmassage.distances(): the paper's measures on numpy meshes, through
/// the functions the jobs' reports use.
#include <filesystem>

#include "geometry/shear.hpp"
#include "io/options_json.hpp"
#include "core/errors.hpp"
#include "geometry/measure_keys.hpp"
#include "geometry/measures.hpp"
#include "pipeline/mesh_jobs/mesh_report.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"

namespace sm::python {

void bind_measures(py::module_& m) {
  m.def(
      "shear",
      [](const py::object& template_vertices, const py::object& vertices,
         const py::handle& triangles) {
        const Positions T = to_positions(template_vertices, "template_vertices");
        const Positions V = to_positions(vertices, "vertices");
        const Triangles F = to_triangles(triangles, "triangles");
        Eigen::VectorXd d;
        {
          py::gil_scoped_release unlocked;
          d = shear_distortion(T, V, F);
        }
        return to_numpy(d);
      },
      py::arg("template_vertices"), py::arg("vertices"), py::arg("triangles"),
      "shear(template_vertices, vertices, triangles) -> numpy array (m): the symmetric maximum "
      "shear distortion (eq. 8) of every triangle of (vertices, triangles) against the same "
      "triangle on template_vertices; 0 congruent, inf degenerate.");

  m.def(
      "distances",
      [](const py::object& a_vertices, const py::handle& a_triangles,
         const py::object& b_vertices, const py::handle& b_triangles,
         const py::kwargs& measures) {
        MeasureOptions options;
        read_options(to_json(measures, "measures"), options, std::filesystem::current_path(),
                     "measures");
        TriMesh a{to_positions(a_vertices, "a_vertices"), to_triangles(a_triangles, "a_triangles")};
        TriMesh b{to_positions(b_vertices, "b_vertices"), to_triangles(b_triangles, "b_triangles")};
        nlohmann::json out;
        {
          py::gil_scoped_release unlocked;
          validate_mesh(a, "mesh a");
          // As `seqmassage measure A B`: the shear against B when B has A's connectivity.
          const bool same = a.V.rows() == b.V.rows() && a.F.rows() == b.F.rows() && a.F == b.F;
          const Positions shear_template = same ? b.V : Positions();
          const MeasureReference reference(std::move(b), options, "mesh b");
          out = measures_json(with_option_path("measures", [&] {
            return measure_mesh(a, reference, same ? &shear_template : nullptr);
          }));
        }
        return from_json(out, true);
      },
      py::arg("a_vertices"), py::arg("a_triangles"), py::arg("b_vertices"),
      py::arg("b_triangles"),
      "distances(a_vertices, a_triangles, b_vertices, b_triangles, **measures) -> dict: the "
      "measures of mesh A against mesh B as `seqmassage measure` reports them (Metro-style "
      "distances both ways, Hausdorff distance, radius ratio, B's feature edges; shear when B "
      "has A's triangles). Keyword arguments: the keys of a single-mesh job's \"measures\" "
      "object (measure_keys()).");
}

}  // namespace sm::python
