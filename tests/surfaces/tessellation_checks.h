#pragma once
// GoogleTest checks on whole tessellations, for the tessellator tests.

#include <gtest/gtest.h>

#include "surfaces/tessellator.h"

namespace patchwork::testing {

/// Options for a tolerance relative to the surface's box diagonal.
inline TessellationOptions relative(double r) {
  TessellationOptions options;
  options.relative_tolerance = r;
  return options;
}

/// Options for an absolute tolerance.
inline TessellationOptions absolute(double e) {
  TessellationOptions options;
  options.tolerance = e;
  return options;
}

/// Everything a Tessellation holds is the same, bit for bit (the scratch is no part of it).
inline void expect_identical_tessellations(const Tessellation& a, const Tessellation& b) {
  EXPECT_EQ(a.mesh.indices, b.mesh.indices);
  EXPECT_EQ(a.mesh.positions, b.mesh.positions);
  EXPECT_EQ(a.mesh.normals, b.mesh.normals);
  EXPECT_EQ(a.mesh.uvs, b.mesh.uvs);
  EXPECT_EQ(a.mesh.tangents, b.mesh.tangents);
  EXPECT_EQ(a.mesh.position_ids, b.mesh.position_ids);
  EXPECT_EQ(a.triangle_patches, b.triangle_patches);
  EXPECT_EQ(a.tolerance, b.tolerance);
  EXPECT_EQ(a.error_bound, b.error_bound);
  EXPECT_EQ(a.weld_gap, b.weld_gap);
  EXPECT_EQ(a.measured_error, b.measured_error);
  EXPECT_EQ(a.culled_patches, b.culled_patches);
  EXPECT_EQ(a.culled_triangles, b.culled_triangles);
  EXPECT_EQ(a.welded_vertices, b.welded_vertices);
}

}  // namespace patchwork::testing
