#pragma once
// The limit surface of a subdivision cage, through OpenSubdiv's feature-adaptive refinement and
// Far::PatchTable (seed 3.2.1).
//
// Domains. The surface is parametrised face by face: each face of the base cage over [0,1]^2
// (quads: corners (0,0), (1,0), (1,1), (0,1) at the face's vertices in order) or over the
// triangle u, v >= 0, u + v <= 1 (Loop: corners (0,0), (1,0), (0,1)). Catmull-Clark and bilinear
// cages with other polygons are refined once first (their limit surface does not change), so
// the base cage is all quads; base() returns it.
//
// Representation. Adaptive refinement isolates extraordinary vertices and semi-sharp features
// to `isolation_level`; regular regions are bicubic B-spline patches (quartic box splines for
// Loop, bilinear for the bilinear scheme), infinitely sharp creases are regular patches with
// boundary rules. For Catmull-Clark the irregular patches left at the isolation level are
// B-spline patches as well (OpenSubdiv's ENDCAP_BSPLINE_BASIS: an approximation of the true
// limit within the last isolated ring, that shrinks by 2 per level), so the whole surface is a
// set of bicubic polynomial patches: to_patch_set() converts them to Bezier patches exactly, and
// the tessellator's error bound holds on them. Loop uses Gregory end caps.

#include <cstdint>
#include <memory>
#include <vector>

#include "core/types.h"
#include "subdivision/cage.h"
#include "surfaces/patch_flatness.h"
#include "surfaces/patch_set.h"

namespace patchwork {

/// A point of the limit surface with its first derivatives in the face's parameters.
struct LimitPoint {
  Vec3 position;
  Vec3 du;
  Vec3 dv;
  /// du x dv normalised (zero where it vanishes).
  Vec3 normal;
};

/// Limit positions, derivatives and normals at the vertices of a cage.
struct VertexLimits {
  std::vector<Vec3> positions;
  std::vector<Vec3> du;
  std::vector<Vec3> dv;
  /// Unit normals (du x dv; zero where it vanishes, as at an infinitely sharp corner).
  std::vector<Vec3> normals;
};

/// The default isolation level of adaptive refinement.
inline constexpr int default_isolation_level = 4;

/// Limit positions and tangents of every vertex of `cage` (OpenSubdiv's limit masks, at level 0).
/// Vertices that no face uses, or only holes, get zeros.
/// \throws what validate_limit_cage() throws (a non-orientable cage too).
VertexLimits limit_at_vertices(const SubdivisionCage& cage);

class LimitSurface {
 public:
  /// Adaptively refines `cage` to `isolation_level` and builds its patch table.
  /// \throws what validate_limit_cage() throws (a non-orientable cage too); InvalidInput unless
  ///         1 <= isolation_level <= 10.
  explicit LimitSurface(const SubdivisionCage& cage, int isolation_level = default_isolation_level);
  ~LimitSurface();
  LimitSurface(LimitSurface&&) noexcept;
  LimitSurface& operator=(LimitSurface&&) noexcept;

  /// The cage whose faces are the parameter domains (see the file comment).
  const SubdivisionCage& base() const noexcept;
  /// The number of base faces.
  std::size_t face_count() const noexcept;
  /// Whether base face f has a surface (holes have none).
  bool has_surface(std::size_t f) const;
  /// Number of patches in the patch table.
  std::size_t patch_count() const noexcept;
  /// The isolation level used.
  int isolation_level() const noexcept;
  /// How many patches each refinement depth holds (index = depth): where the adaptive
  /// refinement went. A face with no irregular feature is one patch of depth 0.
  std::vector<std::size_t> patches_per_depth() const;

  /// The surface point of base face f at (u, v).
  /// \throws InvalidInput if f is out of range or a hole, or (u, v) is outside the face's domain.
  LimitPoint evaluate(std::size_t f, double u, double v) const;
  /// Only the position (faster). Same errors as evaluate().
  Vec3 position(std::size_t f, double u, double v) const;

  /// Bounds on the second derivatives of base face f in its own parameters, from the Bezier nets
  /// of its patches (a patch of depth d spans 1/2^d of the face: its bounds scale by 4^d).
  /// \throws InvalidInput for Loop (its patches are not tensor-product polynomials).
  SecondDerivativeBounds face_bounds(std::size_t f) const;

  /// Every patch as a Bezier patch (bicubic for Catmull-Clark, bilinear for the bilinear scheme),
  /// in patch table order, each over its own part of its face.
  /// \throws InvalidInput for Loop.
  std::vector<BezierPatch3> bezier_patches() const;
  /// The base face each of bezier_patches() belongs to.
  std::vector<std::uint32_t> patch_faces() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// How far the surface moves when isolated one level deeper: the largest distance between it and
/// the same cage's LimitSurface at isolation_level() + 1, sampled in every face's corners at every
/// scale down to the deepest patches. Only end-cap patches (around extraordinary vertices)
/// change, by a factor of about 2.4 per level on a valence-3 corner, so this estimates (it does
/// not bound) how far the representation is from the exact limit surface. 0 at level 10.
double isolation_deviation(const LimitSurface& surface);

/// The Bezier patches of the limit surface as a patch set (Catmull-Clark or bilinear).
PatchSet to_patch_set(const LimitSurface& surface);

}  // namespace patchwork
