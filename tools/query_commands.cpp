#include "tools/query_commands.h"

#include <nlohmann/json.hpp>
#include <ostream>

#include "core/errors.h"
#include "queries/closest_point.h"
#include "queries/patch_bvh.h"
#include "queries/ray_cast.h"
#include "tools/patch_input.h"

namespace patchwork::tools {
namespace {

nlohmann::json array_of(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

// "x y z" in the shortest form that reads back to the same doubles.
std::string text_of(const Vec3& p) { return detail::message(p.x(), " ", p.y(), " ", p.z()); }

Vec3 vector_of(const std::vector<double>& values, const char* name) {
  if (values.size() != 3)
    throw InvalidInput(detail::message("raycast: --", name, " takes three numbers X,Y,Z, not ", values.size()));
  return {values[0], values[1], values[2]};
}

}  // namespace

void run_closest(std::ostream& out, const std::string& path, const std::array<double, 3>& point, bool json) {
  const PatchSet set = read_patch_set(path);
  const Vec3 q(point[0], point[1], point[2]);
  const SurfaceClosestPoint result = closest_point(set, q);
  if (json) {
    out << nlohmann::json{{"distance", result.distance},
                          {"point", array_of(result.point)},
                          {"patch", result.patch},
                          {"u", result.u},
                          {"v", result.v},
                          {"bound", {result.lower_bound, result.distance}},
                          {"attained_more_than_once", result.attained_more_than_once}}
               .dump()
        << "\n";
    return;
  }
  out << detail::message("distance ", result.distance, " (certified: the true distance is in [", result.lower_bound, ", ",
                         result.distance, "])\n", "point ", text_of(result.point), "\n", "patch ", result.patch, " u ",
                         result.u, " v ", result.v, "\n");
  if (result.attained_more_than_once) out << "the distance is attained at more than one point; this is one of them\n";
}

void run_raycast(std::ostream& out, const std::string& path, const std::vector<double>& origin,
                 const std::vector<double>& direction, bool json) {
  const Vec3 o = vector_of(origin, "origin"), d = vector_of(direction, "direction");
  const PatchSet set = read_patch_set(path);
  const RayHits result = ray_cast(set, o, d);
  if (json) {
    nlohmann::json hits = nlohmann::json::array();
    for (const RayHit& hit : result.hits)
      hits.push_back({{"t", hit.t},
                      {"patch", hit.patch},
                      {"u", hit.u},
                      {"v", hit.v},
                      {"point", array_of(hit.point)},
                      {"normal", array_of(hit.normal)},
                      {"grazing", hit.grazing}});
    out << nlohmann::json{{"hits", hits}}.dump() << "\n";
    return;
  }
  out << result.hits.size() << (result.hits.size() == 1 ? " hit\n" : " hits\n");
  for (const RayHit& hit : result.hits)
    out << detail::message("t ", hit.t, " patch ", hit.patch, " u ", hit.u, " v ", hit.v, " point ", text_of(hit.point),
                           " normal ", text_of(hit.normal), hit.grazing ? " grazing" : "", "\n");
}

}  // namespace patchwork::tools
