#pragma once
// Internal: the geometry of patch edges that the patch set and the edge continuity share (the
// walking convention of surfaces/patch_set.h, degrees along and across an edge, elevation along
// it). Not installed.

#include <algorithm>
#include <vector>

#include "surfaces/bezier_patch.h"

namespace patchwork::detail {

// Whether the counter-clockwise walk runs along boundary_curve(edge) (v0, u1) or against it.
inline bool walks_forward(PatchEdge edge) { return edge == PatchEdge::v0 || edge == PatchEdge::u1; }

inline bool runs_along_u(PatchEdge edge) { return edge == PatchEdge::v0 || edge == PatchEdge::v1; }

template <int Dim>
int degree_along(const BezierPatch<Dim>& patch, PatchEdge edge) {
  return runs_along_u(edge) ? patch.degree_u() : patch.degree_v();
}

template <int Dim>
int degree_across(const BezierPatch<Dim>& patch, PatchEdge edge) {
  return runs_along_u(edge) ? patch.degree_v() : patch.degree_u();
}

// The patch elevated along `edge` to `degree`.
template <int Dim>
BezierPatch<Dim> elevated_along(const BezierPatch<Dim>& patch, PatchEdge edge, int degree) {
  const int times = degree - degree_along(patch, edge);
  return elevate_degree(patch, runs_along_u(edge) ? times : 0, runs_along_u(edge) ? 0 : times);
}

// (u, v) of the point at s in [0,1] along boundary_curve(edge).
inline Vec2 edge_parameter(PatchEdge edge, double s) {
  switch (edge) {
    case PatchEdge::v0:
      return {s, 0.0};
    case PatchEdge::u1:
      return {1.0, s};
    case PatchEdge::v1:
      return {s, 1.0};
    case PatchEdge::u0:
      return {0.0, s};
  }
  return {s, 0.0};
}

// Largest distance between corresponding points, b read backwards when reversed.
inline double max_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b, bool reversed) {
  double result = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    result = std::max(result, (a[i] - b[reversed ? b.size() - 1 - i : i]).norm());
  return result;
}

}  // namespace patchwork::detail
