// examples/subdivide_cage.cpp: Catmull-Clark subdivision of a cube cage, uniformly and on the limit surface.
#include <iostream>

#include "check.h"
#include "subdivision/cage.h"
#include "subdivision/limit_surface.h"
#include "subdivision/refine.h"

int main() {
  using examples::check;
  using patchwork::Vec3;
  // The unit cube, six quads counter-clockwise from outside; face 0 is the bottom (z = 0).
  patchwork::Positions corners(8, 3);
  corners << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1;
  patchwork::SubdivisionCage cage;
  cage.mesh = patchwork::FaceVertexMesh::uniform(
      corners, 4, {0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 1, 2, 6, 5, 2, 3, 7, 6, 3, 0, 4, 7});
  cage.options.scheme = patchwork::SubdivisionScheme::catmull_clark;

  // Level 1 has V + E + F = 26 vertices, 2E + C = 48 edges and C = 24 quads (C corners);
  // level 2: 98, 192, 96. Subdivision keeps chi = 2 and the genus.
  const patchwork::UniformRefinement level2 = patchwork::refine_uniform(cage, 2);
  const patchwork::TopologyReport& refined = level2.topology;
  std::cout << "level 2: V " << refined.vertices << ", E " << refined.edges << ", F " << refined.faces << ", chi "
            << refined.euler << '\n';
  check(refined.vertices == 98 && refined.edges == 192 && refined.faces == 96, "V = 98, E = 192, F = 96");
  check(refined.closed && refined.euler == 2 && refined.genus == 0, "closed, chi = 2, genus 0");
  const patchwork::Positions& points = level2.cage.mesh.positions();
  check(points.minCoeff() >= 0.0 && points.maxCoeff() <= 1.0, "refined points inside the cube (convex hull)");

  // Closed forms of the limit surface (Halstead et al. 1993: a vertex of valence n goes to
  // (n^2 v + 4 sum of edge neighbours + sum of diagonal neighbours) / (n (n + 5))):
  // - a cube corner, n = 3: (9 (0,0,0) + 4 (1,1,1) + (2,2,2)) / 24 = (1/4, 1/4, 1/4);
  // - a face centre: after one step the face point (1/2, 1/2, 0) has n = 4, edge neighbours at
  //   height 1/8 and diagonal ones (the corners' new points) at 2/9, so its limit height is
  //   (4 * 4/8 + 4 * 2/9) / 36 = 13/162 above the face.
  const patchwork::VertexLimits vertex_limits = patchwork::limit_at_vertices(cage);
  std::cout << "limit of corner 0: (" << vertex_limits.positions[0].transpose() << ")\n";
  check((vertex_limits.positions[0] - Vec3(0.25, 0.25, 0.25)).norm() < 1e-12, "corner 0 goes to (1/4, 1/4, 1/4)");

  const patchwork::LimitSurface surface(cage);
  const patchwork::LimitPoint centre = surface.evaluate(0, 0.5, 0.5);
  std::cout << surface.patch_count() << " patches; bottom centre (" << centre.position.transpose() << "), normal ("
            << centre.normal.transpose() << ")\n";
  check((centre.position - Vec3(0.5, 0.5, 13.0 / 162.0)).norm() < 1e-12, "bottom centre at height 13/162");
  check((centre.normal - Vec3(0, 0, -1)).norm() < 1e-12, "its normal points out of the cube, -z");
  return examples::exit_code();
}
