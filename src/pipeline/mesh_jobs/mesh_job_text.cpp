#include "pipeline/mesh_jobs/mesh_job_text.hpp"

#include "pipeline/report/run_text.hpp"

namespace sm {

std::string mesh_job_start_text(const MeshJobPlan& plan) {
  return job_name(plan.config.job) + " " + plan.mesh_name + " (" +
         std::to_string(plan.mesh.num_vertices()) + " vertices), " +
         std::to_string(plan.config.massage.iterations) + " iterations, " +
         std::to_string(plan.threads) + " threads";
}

std::string mesh_job_end_text(const MeshJobResult& result) {
  return std::to_string(result.massage.iterations.size()) + " iterations in " +
         fixed_text(result.seconds_massage, 2) + " s (whole run " + fixed_text(result.seconds, 2) +
         " s)";
}

}  // namespace sm
