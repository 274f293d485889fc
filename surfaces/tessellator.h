#pragma once
// Patch sets to render-ready triangle meshes within a guaranteed error.
//
// Rates. For a tolerance eps every patch gets the smallest grid (N_u, N_v) whose a-priori bound
// (surfaces/patch_flatness.h, Filip-Magedson-Markot, with the second-derivative bounds taken
// from the nets of 4 x 4 sub-patches) is <= eps; a shared edge gets one rate, the
// larger of its two sides, and a patch whose edge rate differs from its inner rate is stitched
// to it (surfaces/tessellation_pattern.h). The bound of every triangle, stitched ones included, is
// computed (triangle_flatness_bound) and the rates are raised until all are <= eps, so
//   |S(u, v) - L(u, v)| <= eps   on every triangle,
// L the mesh point with the same parameters: every mesh point is within eps of the surface and
// every surface point within eps of the mesh. The measured error e_par (the same distance sampled
// at each triangle's corners, edge midpoints and interior points) is reported beside it.
//
// A curved patch gets at least two segments per direction, so that coarse tolerances keep the
// topology (a tube of two patches does not flatten).
//
// Welding. Patches that share an edge (PatchSet) share its points: corners are joined through
// shared and collapsed edges, a shared edge is evaluated once, by its first patch, and a
// collapsed edge (the teapot's poles) is one point, evaluated exactly (a control point), with
// the patch's limit normal; triangles that would use it twice are not emitted. Patches that only
// touch at a point (the teapot's handle on its body) keep separate vertices there, so the mesh
// stays manifold and its topology is the patch set's.
//
// Render vertices. Normals are the exact unit normals of each patch (the limit normal where
// F_u x F_v vanishes), oriented like F_u x F_v and so like the triangles, which are
// counter-clockwise in (u, v). A welded point becomes several vertices only where its attributes
// differ between the patches around it: normals more than `crease_angle` apart, different UVs
// (patch UVs jump at every patch edge), tangents more than crease_angle apart.
// RenderMesh::position_ids keeps the welding. Indices are reordered for the vertex cache and
// vertex fetch (meshoptimizer). Work is parallel over patches; the output does not depend on the
// thread count.
//
// Culling. With a camera, each patch gets its tolerance from its nearest depth and patches
// outside the frustum are not tessellated (surfaces/view_culling.h). Patches facing away are
// left out only where no hole can open (BackFaceCulling): on an open surface such as the teapot
// the back of a patch is seen through the openings.

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "core/types.h"
#include "meshes/render_mesh.h"
#include "surfaces/patch_flatness.h"
#include "surfaces/patch_grid.h"
#include "surfaces/patch_set.h"
#include "surfaces/view_culling.h"

namespace patchwork {

/// How the UVs are made.
enum class UvMode { none, patch, atlas };

/// Which patches facing away from the camera's eye are left out.
enum class BackFaceCulling {
  /// Only where that cannot open a hole: the piece bounds a solid (SurfacePieces::solids) and
  /// the eye is outside the box of that solid's control points.
  automatic,
  /// Every back-facing patch (the caller knows the back is never seen).
  always,
  /// None (frustum culling stays).
  never
};

struct TessellationOptions {
  /// Exactly one of tolerance, relative_tolerance, segments and camera (with pixel_tolerance).
  /// Absolute tolerance, model units.
  std::optional<double> tolerance;
  /// Tolerance as a fraction of the diagonal of the surface's tight bounding box (8.2049 for the teapot).
  std::optional<double> relative_tolerance;
  /// Uniform N x N grid per patch (no error target; the bound is still computed).
  std::optional<int> segments;
  /// View-dependent tolerance and culling.
  std::optional<Camera> camera;
  /// Tolerance in pixels for the camera mode.
  double pixel_tolerance = 0.5;
  /// Back-face culling in the camera mode.
  BackFaceCulling back_face_culling = BackFaceCulling::automatic;

  /// Normals (and tangents) further apart than this, radians, split a vertex.
  double crease_angle = 0.0174532925199432958;  // 1 degree
  UvMode uv = UvMode::patch;
  bool tangents = false;
  /// Threads; 0 = all cores.
  int threads = 0;
  /// Sample every triangle to report the measured error.
  bool measure = true;
  /// Reorder for the vertex cache and vertex fetch.
  bool optimize = true;
  /// Refuse (InvalidInput naming the count) above this many triangles.
  std::int64_t max_triangles = 100'000'000;
  /// With a tolerance (not segments, not a camera): split every patch of a set into 2 x 2 or
  /// 4 x 4 pieces when the a-priori triangle count says that saves triangles (a patch whose
  /// curvature varies then gets fine grids only where it bends; see split_surface_pieces).
  bool split_patches = true;
  /// Write the interior points, attributes and triangles with streaming stores
  /// (core/streaming_store.h): not read from memory first, not left in the caches. Unset: when
  /// the output takes at least 64 MiB (about 0.65 M vertices). The output is the same either way.
  std::optional<bool> streaming_stores;
};

namespace detail {
struct TessellatorScratch;

/// Owns the tessellator's scratch memory (per-patch patterns and attributes) between runs of
/// tessellate(set, options, result). Scratch is not part of a value: a copy starts empty, and
/// moves move it.
class TessellatorScratchHandle {
 public:
  TessellatorScratchHandle() noexcept;
  ~TessellatorScratchHandle();
  TessellatorScratchHandle(const TessellatorScratchHandle&) noexcept;
  TessellatorScratchHandle& operator=(const TessellatorScratchHandle&) noexcept;
  TessellatorScratchHandle(TessellatorScratchHandle&&) noexcept;
  TessellatorScratchHandle& operator=(TessellatorScratchHandle&&) noexcept;
  /// The scratch, made on first use.
  TessellatorScratch& get();
  /// Frees the scratch.
  void release() noexcept;

 private:
  std::unique_ptr<TessellatorScratch> scratch_;
};
}  // namespace detail

/// The barycentric weights at which the measured error samples every triangle: its corners,
/// edge midpoints, centroid and three inner points (all multiples of 1/6).
inline constexpr std::array<std::array<double, 3>, 10> measure_sample_weights = {{{1, 0, 0},
                                                                                  {0, 1, 0},
                                                                                  {0, 0, 1},
                                                                                  {0.5, 0.5, 0},
                                                                                  {0, 0.5, 0.5},
                                                                                  {0.5, 0, 0.5},
                                                                                  {1.0 / 3, 1.0 / 3, 1.0 / 3},
                                                                                  {2.0 / 3, 1.0 / 6, 1.0 / 6},
                                                                                  {1.0 / 6, 2.0 / 3, 1.0 / 6},
                                                                                  {1.0 / 6, 1.0 / 6, 2.0 / 3}}};

struct Tessellation {
  RenderMesh mesh;
  /// The patch each triangle belongs to.
  std::vector<std::uint32_t> triangle_patches;
  /// The absolute tolerance used (for a camera: the largest over the patches).
  double tolerance = 0.0;
  /// Max over triangles of the guaranteed bound on |S - L|: the pattern's bound plus the patch's
  /// weld gap.
  double error_bound = 0.0;
  /// The largest distance a welded boundary point lies from its own patch's surface point (the
  /// edges of a PatchSet are joined where their control points agree within its tolerance, and a
  /// joined point takes one side's position); part of error_bound.
  double weld_gap = 0.0;
  /// Max over triangles of the sampled |S - L| (0 if not measured).
  double measured_error = 0.0;
  /// Wall-clock seconds of the run without the measurement, and of the measurement (0 if not
  /// measured): what a caller reports as the tessellation's and the meter's time.
  double tessellation_seconds = 0.0;
  double measure_seconds = 0.0;
  /// Patches not tessellated by frustum or back-face culling.
  std::size_t culled_patches = 0;
  /// Triangles those patches would have had at their tolerance.
  std::int64_t culled_triangles = 0;
  /// Welded points (distinct position ids).
  std::size_t welded_vertices = 0;
  /// Kept by tessellate(set, options, result) for the next run (empty after the other forms).
  detail::TessellatorScratchHandle scratch;
};

/// Two piece edges that are one edge of the surface.
struct PieceJoin {
  EdgeRef first;
  EdgeRef second;
  /// The second runs against the first (in boundary_curve direction).
  bool reversed;
};

/// A surface made of pieces, each parametrised over [0,1]^2 with the edges and corners of a
/// patch: the patches of a PatchSet, or the faces of a subdivision limit surface (subdivision/).
/// The tessellator needs no more than this.
struct SurfacePieces {
  std::size_t count = 0;
  /// Edges shared by two pieces.
  std::vector<PieceJoin> shared;
  /// Edges that are one point.
  std::vector<EdgeRef> collapsed;
  /// Edges against chains of other pieces' edges (PatchSet's T-junctions): the long edge gets
  /// its parts' points end to end, so the mesh is welded across the junction by index.
  std::vector<TJunction> t_junctions;
  /// Per piece, an a-priori bound on how far welding moves its boundary points (the gaps of
  /// its joined edges), or empty for none: the piece's pattern is planned for the tolerance less
  /// this, since the measured move is added to its bound.
  std::vector<double> gaps;
  /// Bounds on the second derivatives of each piece over [0,1]^2 (the guarantee rests on them).
  std::vector<SecondDerivativeBounds> bounds;
  /// Diagonal of a box holding the surface (relative tolerances are fractions of it; the camera
  /// mode's near limit is 10^-3 of it).
  double diagonal = 0.0;
  /// Piece p at every point of the grid us x vs, into `out` (row by row as evaluate_grid stores
  /// them; tangents when out.tangents is not empty).
  std::function<void(std::uint32_t p, std::span<const double> us, std::span<const double> vs, GridSamplesView out)>
      evaluate_grid;
  /// Piece p at the parameter pairs uvs, sample k into slot k of `out` (points, normals, and
  /// tangents when out.tangents is not empty), as evaluate_grid would give them: the boundary
  /// points of a piece in one call. Null: the tessellator evaluates each side as a grid.
  std::function<void(std::uint32_t p, std::span<const Vec2> uvs, GridSamplesView out)> evaluate_samples;
  /// One point of piece p.
  std::function<Vec3(std::uint32_t p, double u, double v)> evaluate;
  /// Piece p at the points (us[k], vs[k]) into points[k]: positions only, many at a time (the
  /// measured error samples with it). Empty: the meter calls `evaluate` point by point.
  std::function<void(std::uint32_t p, std::span<const double> us, std::span<const double> vs, std::span<Vec3> points)>
      evaluate_points;
  /// The pieces' control nets, when the pieces are whole Bezier patches (the camera mode needs
  /// them; else null): each piece lies in the convex hull of its net; where `rational` says
  /// so, the piece is the rational patch of that net and its weights, else the net itself.
  const std::vector<BezierPatch3>* patches = nullptr;
  /// With `patches`, per piece whether it is rational (empty: none is; split pieces, which have
  /// no `patches`, leave it empty). The camera mode does not cull rational pieces as
  /// back-facing (view_culling.h decides that for polynomial patches).
  std::vector<bool> rational;
  /// Per piece, the solid it bounds, or -1 (empty: none does). A solid is a shell (shells() of
  /// a PatchSet) that is closed, consistently oriented and of positive enclosed volume, so that
  /// F_u x F_v points out of it. Seen from outside the shell, a ray leaves the solid only after
  /// entering it through a front-facing point of the same shell, so its back-facing pieces are
  /// hidden, whatever other shells do (BackFaceCulling::automatic relies on it; a
  /// self-intersecting shell can break that, and needs BackFaceCulling::never).
  std::vector<std::int32_t> solids;

  /// Where a piece lies in the parametrisation the output speaks of (UVs, triangle_patches):
  /// [u0, u0 + size] x [v0, v0 + size] of patch `patch`.
  struct Domain {
    std::uint32_t patch;
    double u0;
    double v0;
    double size;
  };
  /// One per piece, or empty: piece p is the whole of patch p.
  std::vector<Domain> domains;
  /// The number of patches the domains refer to (the atlas has a cell for each).
  std::size_t patch_count = 0;
};

/// Tessellates any surface made of pieces (see the file comment).
/// \throws InvalidInput as tessellate(PatchSet) does, and for a camera without `patches`.
Tessellation tessellate(const SurfacePieces& pieces, const TessellationOptions& options);

/// The pieces of a patch set: its patches, shared and collapsed edges, bounds from 4 x 4 sub-nets.
/// `tight_diagonal`: the diagonal of the surface's tight box (relative tolerances need it; it
/// costs a box search per patch); otherwise that of the control points' box, set.size().
SurfacePieces surface_pieces(const PatchSet& set, bool tight_diagonal = true);

/// The patches of `set` split into k x k pieces each (k = 2 or 4; piece (a, b) of patch p is
/// [a/k, (a+1)/k] x [b/k, (b+1)/k], evaluated on the patch itself, so split lines are exact and
/// shared by both sides), joined inside each patch and across the set's shared edges, collapsed
/// where the patch edge is; bounds from the patch's 4 x 4 sub-nets over each piece; UVs and
/// triangle_patches still speak of the patches. \throws InvalidInput unless k is 2 or 4.
SurfacePieces split_surface_pieces(const PatchSet& set, int k, bool tight_diagonal = true);

/// Tessellates `set` (see the file comment).
/// \throws InvalidInput if the options do not name exactly one of the modes, a tolerance is not
///         positive and finite, segments < 1, the camera is malformed, or the triangle count would
///         exceed max_triangles (the message gives the count).
Tessellation tessellate(const PatchSet& set, const TessellationOptions& options);

/// tessellate(set, options) into `result`, reusing the storage of its arrays: a caller that
/// tessellates again and again (a changing view, an animation) pays for fresh memory once.
/// \throws as tessellate(set, options) does, before `result` is changed.
void tessellate(const PatchSet& set, const TessellationOptions& options, Tessellation& result);

}  // namespace patchwork
