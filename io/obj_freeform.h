#pragma once
// Wavefront OBJ, the free-form part: rational and non-rational Bezier and B-spline curves and
// surfaces, read strictly into plain records that a later step turns into curve and surface types.
//
//   v 0 0 0 1              control points: x y z Cartesian, then the weight w (default 1)
//   v 1 0 0 0.5            ...
//   g hull                 the name of the records that follow (g or o; "" before any)
//   cstype rat bspline     basis: bezier or bspline, rational with 'rat'
//   deg 2 1                degree in u (and v, for surfaces)
//   surf 0 1 0 1 1 2 3 4 5 6     range u0 u1 v0 v1, then the control points, u fastest:
//   parm u 0 0 0 1 1 1            point i + count_u * j is P_ij, as OBJ lists them
//   parm v 0 0 1 1                parameters: knots (bspline) or breakpoints (bezier)
//   end
//
//   curv 0 1 1 2 3         a curve: range t0 t1, then its control points (vertex indices only)
//   parm u 0 1
//   end
//
// Counts. A direction of degree p with parameters b_0 .. b_m has
//   bspline: m + 1 - (p + 1) control points (knots = points + p + 1), knots non-decreasing, no
//            knot more than p + 1 times; the domain is [b_p, b_{count}];
//   bezier:  s = m segments of p + 1 points sharing their ends: s * p + 1 points; breakpoints
//            strictly increasing; the domain is [b_0, b_m]. Its B-spline knot vector repeats the
//            ends p + 1 times and each interior breakpoint p times (bspline_knots()).
// The range (u0 u1, or t0 t1) lies in the domain with u0 < u1.
//
// Reading, a ParseError with the file, the line and the column for anything else (errors in a
// statement continued with a trailing '\' name the line it starts in, and the continuation line
// of the token):
//   - control points are vertex indices, 1-based or negative (relative: -1 is the last vertex
//     read so far), in surf also v/vt/vn, v/vt or v//vn (only v is used; vt and vn must name a
//     vt or vn read so far); a vertex must be defined before the curv or surf that uses it;
//   - v has 3 finite coordinates and an optional weight, finite and > 0; a non-rational record
//     (cstype without rat) refuses a control point of weight other than 1 (it would be lost);
//   - vt (1 to 3 numbers), vn (3) and vp (1 to 3) are vertex data, checked as numbers; vp is
//     counted for nothing (it serves trimming curves, which are refused);
//   - cstype, deg before a curv or surf (a surf needs deg du dv), parm u (and v) and end inside
//     a curv/surf block, each once; degrees 1 to max_obj_freeform_degree;
//   - ctech and stech (tessellation hints for a renderer), s, usemtl, mtllib, lod, bevel,
//     c_interp, d_interp, shadow_obj, trace_obj, maplib, usemap (display attributes) are read past;
//   - refused, naming the statement: trim, hole, scrv, sp (trimming and special curves and
//     points), con (connectivity), bmat, step, cstype cardinal, taylor and bmatrix (bases the
//     tessellator has no evaluation for), curv2 (curves on a surface), mg (merging groups), call,
//     csh (other files, commands), and the polygon statements f, l, p (read_obj reads polygons;
//     a file with both is not read by either).
// Nothing is returned half built: every record is checked whole at its end, or the file fails;
// a file without any curv or surf fails too.
//
// Writing: per record its control points as 'v x y z' ('v x y z w' if rational), in the
// shortest decimal form that reads back to the same double, then g, cstype, deg, curv or surf
// with absolute indices, parm, end; the reader gives back the same document bit for bit (with
// line set to where each record's curv or surf stands). Whole or not at all; a document without
// records, or with a record validate() refuses, is refused before anything is written.

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/types.h"

namespace patchwork {

/// The largest degree a free-form OBJ record may have.
inline constexpr int max_obj_freeform_degree = 64;

/// The basis of a free-form OBJ record (cstype).
enum class FreeformBasis { bezier, bspline };

/// A 'curv' record: a curve over [t0, t1].
struct FreeformCurve {
  std::string name;  ///< the current g or o name ("" before any)
  FreeformBasis basis = FreeformBasis::bspline;
  bool rational = false;  ///< cstype rat: weights from the vertices
  int degree = 1;
  std::vector<double> parameters;  ///< parm u: knots (bspline) or breakpoints (bezier)
  double t0 = 0.0;                 ///< the range, within the domain of the parameters
  double t1 = 1.0;
  std::vector<Vec3> points;     ///< control points, Cartesian
  std::vector<double> weights;  ///< one per point; all 1 when not rational
  std::int64_t line = 0;        ///< where the curv statement stands (0 if not read)
  bool operator==(const FreeformCurve&) const = default;
};

/// A 'surf' record: a tensor-product surface over [u0, u1] x [v0, v1].
struct FreeformSurface {
  std::string name;  ///< the current g or o name ("" before any)
  FreeformBasis basis = FreeformBasis::bspline;
  bool rational = false;  ///< cstype rat: weights from the vertices
  int degree_u = 1;
  int degree_v = 1;
  std::vector<double> parameters_u;  ///< parm u: knots (bspline) or breakpoints (bezier)
  std::vector<double> parameters_v;  ///< parm v
  double u0 = 0.0;                   ///< the range, within the domain of the parameters
  double u1 = 1.0;
  double v0 = 0.0;
  double v1 = 1.0;
  std::vector<Vec3> points;     ///< count_u x count_v control points, u fastest: P_ij at i + count_u * j
  std::vector<double> weights;  ///< one per point; all 1 when not rational
  std::int64_t line = 0;        ///< where the surf statement stands (0 if not read)
  bool operator==(const FreeformSurface&) const = default;
};

/// The free-form records of an OBJ file, each in file order.
struct FreeformDocument {
  std::vector<FreeformSurface> surfaces;
  std::vector<FreeformCurve> curves;
  bool operator==(const FreeformDocument&) const = default;
};

/// The control points one direction of degree `degree` with these parameters has: knots - degree
/// - 1 (bspline), segments * degree + 1 (bezier); 0 when the parameters are too few for one.
std::int64_t control_point_count(FreeformBasis basis, int degree, std::span<const double> parameters);

/// The B-spline knot vector equivalent to the parameters: bspline knots as they are; Bezier
/// breakpoints with the ends p + 1 times and interior breakpoints p times. \pre degree >= 1.
std::vector<double> bspline_knots(FreeformBasis basis, int degree, std::span<const double> parameters);

/// The number of control points in u and in v a surface's degrees and parameters imply.
std::pair<std::int64_t, std::int64_t> control_point_counts(const FreeformSurface& surface);

/// Checks a curve against every rule the reader applies. \throws InvalidInput naming the rule.
void validate(const FreeformCurve& curve);

/// Checks a surface against every rule the reader applies. \throws InvalidInput naming the rule.
void validate(const FreeformSurface& surface);

/// Parses the free-form part of OBJ text; `name` is used in error messages. \throws ParseError.
FreeformDocument parse_obj_freeform(std::string_view text, const std::string& name);

/// Whether OBJ text holds free-form geometry: some line's first word is a free-form statement
/// (cstype, deg, curv, surf, parm, end, ...). A polygon file has none (read_obj refuses them).
bool is_obj_freeform(std::string_view text);

/// Parses the free-form OBJ text a stream holds up to its end; `name` is used in error messages.
/// \throws IoError naming `name` if the stream fails, ParseError if the text is malformed.
FreeformDocument parse_obj_freeform(std::istream& in, const std::string& name);

/// Reads a free-form OBJ file. \throws IoError if it cannot be read, ParseError if it is malformed.
FreeformDocument read_obj_freeform(const std::filesystem::path& path);

/// The OBJ text of the document. \throws InvalidInput if a record fails validate() or has a
/// name that does not read back (white space other than single inner spaces, '#', '\').
std::string format_obj_freeform(const FreeformDocument& document);

/// Writes a free-form OBJ file atomically. \throws InvalidInput as format_obj_freeform (nothing
/// written), IoError.
void write_obj_freeform(const std::filesystem::path& path, const FreeformDocument& document);

}  // namespace patchwork
