// The patch-set report (surfaces/patch_set.h): counts, continuity, loops and touching points,
// printed as text and as JSON.

#include <nlohmann/json.hpp>

#include <algorithm>
#include <ostream>
#include <string>

#include "core/errors.h"
#include "surfaces/patch_set.h"

namespace patchwork {

PatchSetReport report(const PatchSet& set) {
  PatchSetReport r{set.count(), set.shared_edges().size(), set.open_edges().size(),
                   set.collapsed_edges().size(), set.boundary_loops().size(), set.touching_points().size(),
                   set.t_junctions().size(), true, set.open_edges().empty(),
                   set.shared_edges().empty() ? -1 : 1 << 30, 0, set.tolerance(), &set, set.rational_count()};
  for (const TJunction& t : set.t_junctions()) r.consistently_oriented = r.consistently_oriented && t.consistently_oriented;
  for (const SharedEdge& s : set.shared_edges()) {
    r.consistently_oriented = r.consistently_oriented && s.consistently_oriented;
    r.min_ck = std::min(r.min_ck, s.continuity.ck);
    if (s.continuity.g1) ++r.g1_edges;
  }
  return r;
}

namespace {

std::string edge_label(EdgeRef e) { return detail::message("patch ", e.patch, " ", edge_name(e.edge)); }

}  // namespace

std::ostream& operator<<(std::ostream& out, const PatchSetReport& r) {
  out << "patch set: " << r.patches << " patches";
  if (r.rational_patches > 0) out << " (" << r.rational_patches << " rational)";
  out << ", " << r.shared_edges << " shared edges, " << r.open_edges
      << " open edges, " << r.collapsed_edges << " collapsed edges, " << r.boundary_loops << " boundary loops, "
      << r.touching_points << " touching points, " << r.t_junctions << " T-junctions\n"
      << "  closed: " << (r.closed ? "yes" : "no") << ", consistently oriented: " << (r.consistently_oriented ? "yes" : "no")
      << ", lowest C^k: " << r.min_ck << ", G^1 edges: " << r.g1_edges << " of " << r.shared_edges
      << ", tolerance: " << r.tolerance << "\n";
  for (const SharedEdge& s : r.set->shared_edges()) {
    out << "  shared " << edge_label(s.first) << " ~ " << edge_label(s.second) << (s.reversed ? " (reversed)" : "")
        << ": gap " << s.continuity.gap << ", C^" << s.continuity.ck << ", " << (s.continuity.g1 ? "G^1" : "not G^1")
        << " (max normal angle " << s.continuity.max_normal_angle << " rad)" << (s.consistently_oriented ? "" : ", orientation flips") << "\n";
  }
  for (const TJunction& t : r.set->t_junctions()) {
    out << "  T-junction " << edge_label(t.edge) << " ~";
    for (std::size_t k = 0; k < t.parts.size(); ++k) {
      out << " [" << edge_label(t.parts[k]) << (t.reversed[k] ? " reversed" : "") << " to " << t.breaks[k] << "]";
    }
    out << ": gap " << t.gap << (t.consistently_oriented ? "" : ", orientation flips") << "\n";
  }
  for (const EdgeRef& e : r.set->collapsed_edges()) out << "  collapsed " << edge_label(e) << "\n";
  for (const BoundaryLoop& loop : r.set->boundary_loops()) {
    out << "  boundary loop (" << (loop.closed ? "closed" : "open chain") << "):";
    for (const EdgeRef& e : loop.edges) out << " [" << edge_label(e) << "]";
    out << "\n";
  }
  for (const TouchingPoint& t : r.set->touching_points()) {
    out << "  touching point (" << t.point.x() << ", " << t.point.y() << ", " << t.point.z() << "):";
    for (const auto& group : t.groups) {
      out << " {";
      for (std::size_t i = 0; i < group.size(); ++i) out << (i ? " " : "") << group[i];
      out << "}";
    }
    out << "\n";
  }
  return out;
}

std::string to_json(const PatchSetReport& r) {
  using nlohmann::json;
  const auto edge_json = [](EdgeRef e) { return json{{"patch", e.patch}, {"edge", edge_name(e.edge)}}; };
  json shared = json::array();
  for (const SharedEdge& s : r.set->shared_edges()) {
    shared.push_back({{"first", edge_json(s.first)}, {"second", edge_json(s.second)}, {"reversed", s.reversed},
                      {"consistently_oriented", s.consistently_oriented}, {"gap", s.continuity.gap},
                      {"ck", s.continuity.ck}, {"g1", s.continuity.g1}, {"max_normal_angle", s.continuity.max_normal_angle}});
  }
  json t_junctions = json::array();
  for (const TJunction& t : r.set->t_junctions()) {
    json parts = json::array();
    for (std::size_t k = 0; k < t.parts.size(); ++k) {
      json part = edge_json(t.parts[k]);
      part["to"] = t.breaks[k];
      part["reversed"] = static_cast<bool>(t.reversed[k]);
      parts.push_back(part);
    }
    t_junctions.push_back({{"edge", edge_json(t.edge)}, {"parts", parts}, {"gap", t.gap},
                           {"consistently_oriented", t.consistently_oriented}});
  }
  json open = json::array();
  for (const EdgeRef& e : r.set->open_edges()) open.push_back(edge_json(e));
  json collapsed = json::array();
  for (const EdgeRef& e : r.set->collapsed_edges()) collapsed.push_back(edge_json(e));
  json loops = json::array();
  for (const BoundaryLoop& loop : r.set->boundary_loops()) {
    json edges = json::array();
    for (const EdgeRef& e : loop.edges) edges.push_back(edge_json(e));
    loops.push_back({{"closed", loop.closed}, {"edges", edges}});
  }
  json touching = json::array();
  for (const TouchingPoint& t : r.set->touching_points()) {
    touching.push_back({{"point", {t.point.x(), t.point.y(), t.point.z()}}, {"groups", t.groups}});
  }
  const json document = {{"patches", r.patches},
                         {"rational_patches", r.rational_patches},
                         {"shared_edges", r.shared_edges},
                         {"open_edges", r.open_edges},
                         {"collapsed_edges", r.collapsed_edges},
                         {"boundary_loops", r.boundary_loops},
                         {"touching_points", r.touching_points},
                         {"t_junctions", r.t_junctions},
                         {"consistently_oriented", r.consistently_oriented},
                         {"closed", r.closed},
                         {"min_ck", r.min_ck},
                         {"g1_edges", r.g1_edges},
                         {"tolerance", r.tolerance},
                         {"shared", shared},
                         {"junctions", t_junctions},
                         {"open", open},
                         {"collapsed", collapsed},
                         {"loops", loops},
                         {"touching", touching}};
  return document.dump(2);
}

}  // namespace patchwork
