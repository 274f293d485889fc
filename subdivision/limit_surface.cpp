#include "subdivision/limit_surface.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTable.h>
#include <opensubdiv/far/patchTableFactory.h>

#include "core/assert.h"
#include "core/errors.h"
#include "subdivision/osd_refiner.h"
#include "subdivision/refine.h"

namespace patchwork {

namespace osd = OpenSubdiv;

namespace {

using Point3 = detail::OsdPoint;

std::vector<Point3> cage_points(const FaceVertexMesh& mesh) {
  std::vector<Point3> points(mesh.vertex_count());
  for (std::size_t v = 0; v < points.size(); ++v) {
    for (int k = 0; k < 3; ++k) points[v].x[k] = mesh.positions()(static_cast<Eigen::Index>(v), k);
  }
  return points;
}

Vec3 unit_or_zero(const Vec3& v) {
  const double length = v.norm();
  return length > 0.0 && std::isfinite(length) ? Vec3(v / length) : Vec3::Zero();
}

// The uniform cubic B-spline segment over the middle of four control points, as a Bezier
// segment: b0 = (P0 + 4 P1 + P2)/6, b1 = (4 P1 + 2 P2)/6, b2 = (2 P1 + 4 P2)/6, b3 = (P1 + 4 P2 + P3)/6.
std::array<Vec3, 4> bspline_to_bezier(const std::array<Vec3, 4>& p) {
  return {(p[0] + 4.0 * p[1] + p[2]) / 6.0, (4.0 * p[1] + 2.0 * p[2]) / 6.0, (2.0 * p[1] + 4.0 * p[2]) / 6.0,
          (p[1] + 4.0 * p[2] + p[3]) / 6.0};
}

}  // namespace

VertexLimits limit_at_vertices(const SubdivisionCage& cage) {
  validate_limit_cage(cage, "limit_at_vertices");
  auto refiner = detail::make_refiner(cage);
  const std::vector<Point3> source = cage_points(cage.mesh);
  std::vector<Point3> position(source.size(), Point3{{0, 0, 0}});
  std::vector<Point3> du(source.size(), Point3{{0, 0, 0}});
  std::vector<Point3> dv(source.size(), Point3{{0, 0, 0}});
  const Point3* from = source.data();
  Point3* to_position = position.data();
  Point3* to_du = du.data();
  Point3* to_dv = dv.data();
  detail::PrimvarRefiner(*refiner).Limit(from, to_position, to_du, to_dv);
  VertexLimits limits;
  for (std::size_t v = 0; v < source.size(); ++v) {
    limits.positions.push_back(position[v].vec());
    limits.du.push_back(du[v].vec());
    limits.dv.push_back(dv[v].vec());
    limits.normals.push_back(unit_or_zero(du[v].vec().cross(dv[v].vec())));
  }
  return limits;
}

struct LimitSurface::Impl {
  SubdivisionCage base;
  int level = default_isolation_level;
  std::unique_ptr<osd::Far::TopologyRefiner> refiner;
  std::unique_ptr<osd::Far::PatchTable> table;
  std::unique_ptr<osd::Far::PatchMap> map;
  // Vertices of every refinement level, then the patch table's local points.
  std::vector<Point3> points;
  std::vector<bool> hole;
  // Catmull-Clark and bilinear: every patch as a Bezier patch, its face, its depth, and the
  // second-derivative bounds per face.
  std::vector<BezierPatch3> bezier;
  std::vector<std::uint32_t> bezier_face;
  std::vector<SecondDerivativeBounds> face_bounds;

  bool loop() const { return base.options.scheme == SubdivisionScheme::loop; }
  bool bilinear() const { return base.options.scheme == SubdivisionScheme::bilinear; }

  void check_face(std::size_t f, double u, double v) const {
    if (f >= base.mesh.face_count()) {
      throw InvalidInput(detail::message("LimitSurface: face ", f, " of ", base.mesh.face_count()));
    }
    if (hole[f]) throw InvalidInput(detail::message("LimitSurface: face ", f, " is a hole"));
    const bool inside = u >= 0.0 && v >= 0.0 && u <= 1.0 && v <= 1.0 && (!loop() || u + v <= 1.0 + 1e-15);
    if (!inside) {
      throw InvalidInput(detail::message("LimitSurface: (", u, ", ", v, ") is outside the domain of face ", f));
    }
  }

  // The patch of face f at (u, v), its weights and control points.
  template <class Visit>
  void visit_basis(std::size_t f, double u, double v, bool derivatives, const Visit& visit) const {
    const auto* handle = map->FindPatch(static_cast<int>(f), u, v);
    if (handle == nullptr) throw InvalidInput(detail::message("LimitSurface: face ", f, " has no patch"));
    std::array<double, 20> w{};
    std::array<double, 20> wu{};
    std::array<double, 20> wv{};
    table->EvaluateBasis(*handle, u, v, w.data(), derivatives ? wu.data() : nullptr,
                         derivatives ? wv.data() : nullptr);
    const auto cvs = table->GetPatchVertices(*handle);
    for (int k = 0; k < cvs.size(); ++k) visit(points[static_cast<std::size_t>(cvs[k])].vec(), w[k], wu[k], wv[k]);
  }

  void build_bilinear() {
    // The limit of the bilinear scheme on quads is the bilinear interpolation of each face.
    for (std::size_t f = 0; f < base.mesh.face_count(); ++f) {
      const auto face = base.mesh.face(f);
      face_bounds.push_back({0, 0, 0});
      if (hole[f]) continue;
      const std::vector<Vec3> corners = {base.mesh.position(face[0]), base.mesh.position(face[1]),
                                         base.mesh.position(face[3]), base.mesh.position(face[2])};
      bezier.emplace_back(1, 1, corners);
      bezier_face.push_back(static_cast<std::uint32_t>(f));
      face_bounds.back() = second_derivative_bounds(bezier.back());
    }
  }

  void build_patch_table() {
    refiner = detail::make_refiner(base);
    osd::Far::PatchTableFactory::Options options(static_cast<unsigned>(level));
    options.SetEndCapType(loop() ? osd::Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS
                                 : osd::Far::PatchTableFactory::Options::ENDCAP_BSPLINE_BASIS);
    options.useInfSharpPatch = true;
    options.generateVaryingTables = false;
    options.SetPatchPrecision<double>();
    refiner->RefineAdaptive(options.GetRefineAdaptiveOptions());
    table.reset(osd::Far::PatchTableFactory::Create(*refiner, options));
    map = std::make_unique<osd::Far::PatchMap>(*table);

    const int refined = refiner->GetNumVerticesTotal();
    points = cage_points(base.mesh);
    points.resize(static_cast<std::size_t>(refined + table->GetNumLocalPoints()));
    const detail::PrimvarRefiner primvars(*refiner);
    Point3* source = points.data();
    for (int l = 1; l <= refiner->GetMaxLevel(); ++l) {
      Point3* target = source + refiner->GetLevel(l - 1).GetNumVertices();
      primvars.Interpolate(l, source, target);
      source = target;
    }
    if (const auto* stencils = table->GetLocalPointStencilTable<double>()) {
      stencils->UpdateValues(points.data(), points.data() + refined);
    }
    if (!loop()) build_bezier();
  }

  void build_bezier() {
    face_bounds.assign(base.mesh.face_count(), {0, 0, 0});
    for (int a = 0; a < table->GetNumPatchArrays(); ++a) {
      const auto descriptor = table->GetPatchArrayDescriptor(a);
      PATCHWORK_ASSERT(descriptor.GetType() == osd::Far::PatchDescriptor::REGULAR,
                       "Catmull-Clark with B-spline end caps has only regular patches");
      for (int p = 0; p < table->GetNumPatches(a); ++p) {
        const auto cvs = table->GetPatchVertices(a, p);
        const auto param = table->GetPatchParam(a, p);
        // B-spline control points, P[i][j] = cvs[4 j + i] (i along u); a boundary edge has no
        // row beyond it: its phantom row is extrapolated, 2 (edge row) - (inner row).
        std::array<std::array<Vec3, 4>, 4> net;
        const int boundary = param.GetBoundary();
        for (int j = 0; j < 4; ++j) {
          for (int i = 0; i < 4; ++i) {
            const bool phantom = ((boundary & 1) && j == 0) || ((boundary & 2) && i == 3) ||
                                 ((boundary & 4) && j == 3) || ((boundary & 8) && i == 0);
            net[i][j] = phantom ? Vec3::Zero() : points[static_cast<std::size_t>(cvs[4 * j + i])].vec();
          }
        }
        const bool row0 = boundary & 1;
        const bool row3 = boundary & 4;
        for (int j = 0; j < 4; ++j) {
          if ((j == 0 && row0) || (j == 3 && row3)) continue;
          if (boundary & 8) net[0][j] = 2.0 * net[1][j] - net[2][j];
          if (boundary & 2) net[3][j] = 2.0 * net[2][j] - net[1][j];
        }
        for (int i = 0; i < 4; ++i) {
          if (row0) net[i][0] = 2.0 * net[i][1] - net[i][2];
          if (row3) net[i][3] = 2.0 * net[i][2] - net[i][1];
        }
        std::array<std::array<Vec3, 4>, 4> half;  // converted along u: half[i][j]
        for (int j = 0; j < 4; ++j) {
          const auto row = bspline_to_bezier({net[0][j], net[1][j], net[2][j], net[3][j]});
          for (int i = 0; i < 4; ++i) half[i][j] = row[i];
        }
        std::vector<Vec3> control(16);
        for (int i = 0; i < 4; ++i) {
          const auto column = bspline_to_bezier(half[i]);
          for (int j = 0; j < 4; ++j) control[static_cast<std::size_t>(i + 4 * j)] = column[j];
        }
        bezier.emplace_back(3, 3, std::move(control));
        const auto face = static_cast<std::uint32_t>(param.GetFaceId());
        bezier_face.push_back(face);
        // d/du of the face = 2^depth d/du of the patch.
        const double scale = std::ldexp(1.0, 2 * param.GetDepth());
        const SecondDerivativeBounds b = second_derivative_bounds(bezier.back(), 2);
        SecondDerivativeBounds& fb = face_bounds[face];
        fb = {std::max(fb.uu, scale * b.uu), std::max(fb.uv, scale * b.uv), std::max(fb.vv, scale * b.vv)};
      }
    }
  }
};

LimitSurface::LimitSurface(const SubdivisionCage& cage, int isolation_level) : impl_(std::make_unique<Impl>()) {
  if (isolation_level < 1 || isolation_level > 10) {
    throw InvalidInput(detail::message("LimitSurface: isolation level ", isolation_level, " is not in 1..10"));
  }
  validate_limit_cage(cage, "LimitSurface");
  Impl& impl = *impl_;
  impl.level = isolation_level;
  const auto& sizes = cage.mesh.face_sizes();
  const bool quads = std::all_of(sizes.begin(), sizes.end(), [](std::uint32_t s) { return s == 4; });
  impl.base = cage.options.scheme == SubdivisionScheme::loop || quads ? cage : refine_uniform(cage, 1).cage;
  impl.hole.assign(impl.base.mesh.face_count(), false);
  for (auto f : impl.base.holes) impl.hole[f] = true;
  if (impl.bilinear()) {
    impl.build_bilinear();
  } else {
    impl.build_patch_table();
  }
}

LimitSurface::~LimitSurface() = default;
LimitSurface::LimitSurface(LimitSurface&&) noexcept = default;
LimitSurface& LimitSurface::operator=(LimitSurface&&) noexcept = default;

const SubdivisionCage& LimitSurface::base() const noexcept { return impl_->base; }
std::size_t LimitSurface::face_count() const noexcept { return impl_->base.mesh.face_count(); }
bool LimitSurface::has_surface(std::size_t f) const { return f < face_count() && !impl_->hole[f]; }
std::size_t LimitSurface::patch_count() const noexcept {
  return impl_->table ? static_cast<std::size_t>(impl_->table->GetNumPatchesTotal()) : impl_->bezier.size();
}
int LimitSurface::isolation_level() const noexcept { return impl_->level; }

std::vector<std::size_t> LimitSurface::patches_per_depth() const {
  std::vector<std::size_t> counts(1, 0);
  const auto count = [&](int depth) {
    if (static_cast<std::size_t>(depth) >= counts.size()) counts.resize(static_cast<std::size_t>(depth) + 1, 0);
    ++counts[static_cast<std::size_t>(depth)];
  };
  const Impl& impl = *impl_;
  if (!impl.table) {
    for (std::size_t p = 0; p < impl.bezier.size(); ++p) count(0);
    return counts;
  }
  for (int a = 0; a < impl.table->GetNumPatchArrays(); ++a) {
    for (int p = 0; p < impl.table->GetNumPatches(a); ++p) count(impl.table->GetPatchParam(a, p).GetDepth());
  }
  return counts;
}

LimitPoint LimitSurface::evaluate(std::size_t f, double u, double v) const {
  const Impl& impl = *impl_;
  impl.check_face(f, u, v);
  LimitPoint point{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  if (impl.bilinear()) {
    const BezierPatch3& patch = impl.bezier[static_cast<std::size_t>(
        std::lower_bound(impl.bezier_face.begin(), impl.bezier_face.end(), f) - impl.bezier_face.begin())];
    point.position = patch.evaluate(u, v);
    point.du = (1 - v) * (patch.control_point(1, 0) - patch.control_point(0, 0)) +
               v * (patch.control_point(1, 1) - patch.control_point(0, 1));
    point.dv = (1 - u) * (patch.control_point(0, 1) - patch.control_point(0, 0)) +
               u * (patch.control_point(1, 1) - patch.control_point(1, 0));
  } else {
    impl.visit_basis(f, u, v, true, [&](const Vec3& p, double w, double wu, double wv) {
      point.position += w * p;
      point.du += wu * p;
      point.dv += wv * p;
    });
  }
  point.normal = unit_or_zero(point.du.cross(point.dv));
  return point;
}

Vec3 LimitSurface::position(std::size_t f, double u, double v) const {
  const Impl& impl = *impl_;
  if (impl.bilinear()) return evaluate(f, u, v).position;
  impl.check_face(f, u, v);
  Vec3 position = Vec3::Zero();
  impl.visit_basis(f, u, v, false, [&](const Vec3& p, double w, double, double) { position += w * p; });
  return position;
}

SecondDerivativeBounds LimitSurface::face_bounds(std::size_t f) const {
  if (impl_->loop()) throw InvalidInput("LimitSurface: Loop patches are not tensor-product polynomials");
  if (f >= face_count()) throw InvalidInput(detail::message("LimitSurface: face ", f, " of ", face_count()));
  return impl_->face_bounds[f];
}

std::vector<BezierPatch3> LimitSurface::bezier_patches() const {
  if (impl_->loop()) throw InvalidInput("LimitSurface: Loop patches have no tensor-product Bezier form");
  return impl_->bezier;
}

std::vector<std::uint32_t> LimitSurface::patch_faces() const {
  if (impl_->loop()) throw InvalidInput("LimitSurface: Loop patches have no tensor-product Bezier form");
  return impl_->bezier_face;
}

double isolation_deviation(const LimitSurface& surface) {
  const int level = surface.isolation_level();
  if (level >= 10 || surface.base().options.scheme == SubdivisionScheme::bilinear) return 0.0;
  const LimitSurface deeper(surface.base(), level + 1);
  const bool triangles = surface.base().options.scheme == SubdivisionScheme::loop;
  // End caps sit in the corners of the faces, 2^-level wide: sample 4 x 4 cell centres in the
  // corner squares of every size 2^-k, k = 0 .. level + 1, at each corner.
  double deviation = 0.0;
  for (std::size_t f = 0; f < surface.face_count(); ++f) {
    if (!surface.has_surface(f)) continue;
    for (int k = 0; k <= level + 1; ++k) {
      const double size = std::ldexp(1.0, -k);
      for (int i = 0; i < 4; ++i) {
        for (int j = 0; j < 4; ++j) {
          const double a = (i + 0.5) / 4 * size;
          const double b = (j + 0.5) / 4 * size;
          for (const auto& [u, v] : {std::pair{a, b}, std::pair{1 - a, b}, std::pair{a, 1 - b}, std::pair{1 - a, 1 - b}}) {
            if (triangles && u + v > 1.0) continue;
            deviation = std::max(deviation, (surface.position(f, u, v) - deeper.position(f, u, v)).norm());
          }
        }
      }
    }
  }
  return deviation;
}

PatchSet to_patch_set(const LimitSurface& surface) { return PatchSet(surface.bezier_patches()); }

}  // namespace patchwork
