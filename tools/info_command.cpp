#include "tools/info_command.h"

#include <nlohmann/json.hpp>
#include <ostream>

#include "io/mesh_file.h"
#include "meshes/topology.h"

namespace patchwork::tools {

void run_info(std::ostream& out, const std::string& path, bool json) {
  const TopologyReport report = analyze(read_mesh(path));
  if (!json) {
    out << path << "\n" << report;
    return;
  }
  // The keys the CLI promises, and the non-manifold elements only when there are some.
  nlohmann::json document = {{"vertices", report.vertices},
                             {"edges", report.edges},
                             {"faces", report.faces},
                             {"components", report.components},
                             {"boundary_loops", report.boundary_loops},
                             {"closed", report.closed},
                             {"orientable", report.orientable},
                             {"manifold", report.manifold},
                             {"euler", report.euler},
                             {"genus", report.genus ? nlohmann::json(*report.genus) : nlohmann::json(nullptr)}};
  if (!report.manifold) {
    document["non_manifold_edges"] = report.non_manifold_edges;
    document["non_manifold_vertices"] = report.non_manifold_vertices;
    document["faces_repeating_a_vertex"] = report.faces_repeating_a_vertex;
  }
  out << document.dump(2) << "\n";
}

}  // namespace patchwork::tools
