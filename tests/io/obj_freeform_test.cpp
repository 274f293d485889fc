// Free-form OBJ (io/obj_freeform.h): hand-written files read to their exact records, the
// Bezier-basis knot vectors against evaluation, bit-exact round trips over random documents,
// every malformed and every refused statement as a ParseError at its place, and writes that
// leave nothing behind when they fail.

#include "io/obj_freeform.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors.h"
#include "tests/support/extreme_doubles.h"
#include "tests/support/parse_errors.h"
#include "tests/support/temporary_directory.h"

namespace patchwork {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// Helpers

struct TemporaryDirectory : testing::TemporaryDirectory {
  TemporaryDirectory() : testing::TemporaryDirectory("patchwork_io_freeform_test") {}
};

void put_file(const fs::path& path, const std::string& content) {
  std::ofstream out(path, std::ios::binary);
  out << content;
}

bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (!same_bits(a[k], b[k])) return false;
  }
  return true;
}

bool same_bits(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k) {
    for (int c = 0; c < 3; ++c) {
      if (!same_bits(a[k][c], b[k][c])) return false;
    }
  }
  return true;
}

// Equal bit for bit in every field but `line` (operator== calls -0 and +0 equal).
bool same_bits(const FreeformSurface& a, const FreeformSurface& b) {
  return a.name == b.name && a.basis == b.basis && a.rational == b.rational && a.degree_u == b.degree_u &&
         a.degree_v == b.degree_v && same_bits(a.parameters_u, b.parameters_u) &&
         same_bits(a.parameters_v, b.parameters_v) && same_bits(a.u0, b.u0) && same_bits(a.u1, b.u1) &&
         same_bits(a.v0, b.v0) && same_bits(a.v1, b.v1) && same_bits(a.points, b.points) &&
         same_bits(a.weights, b.weights);
}

bool same_bits(const FreeformCurve& a, const FreeformCurve& b) {
  return a.name == b.name && a.basis == b.basis && a.rational == b.rational && a.degree == b.degree &&
         same_bits(a.parameters, b.parameters) && same_bits(a.t0, b.t0) && same_bits(a.t1, b.t1) &&
         same_bits(a.points, b.points) && same_bits(a.weights, b.weights);
}

bool same_bits(const FreeformDocument& a, const FreeformDocument& b) {
  if (a.surfaces.size() != b.surfaces.size() || a.curves.size() != b.curves.size()) return false;
  for (std::size_t k = 0; k < a.surfaces.size(); ++k) {
    if (!same_bits(a.surfaces[k], b.surfaces[k])) return false;
  }
  for (std::size_t k = 0; k < a.curves.size(); ++k) {
    if (!same_bits(a.curves[k], b.curves[k])) return false;
  }
  return true;
}

// The lines joined with '\n', line `line` (1-based) replaced (by a blank line if empty, so that
// the line numbers after it stay).
std::string with_line(const std::vector<std::string>& lines, std::size_t line, const std::string& replacement) {
  std::string text;
  for (std::size_t k = 0; k < lines.size(); ++k) text += (k + 1 == line ? replacement : lines[k]) + "\n";
  return text;
}

std::string joined(const std::vector<std::string>& lines) { return with_line(lines, 0, ""); }

using testing::Malformed;

// The ParseError that parsing `text` throws, or nothing (then the test has failed).
std::optional<ParseError> parse_error(const std::string& text) {
  return testing::parse_error_of([&] { parse_obj_freeform(text, "bad.obj"); });
}

void expect_malformed(const std::vector<Malformed>& cases) {
  testing::expect_parse_errors(
      cases, "bad.obj", [](const std::string& text, const std::string& name) { parse_obj_freeform(text, name); });
}

// A bspline patch of degrees (2, 1): knots u 0 0 0 1 1 1 (3 points), v 0 0 1 1 (2 points).
const std::vector<std::string> bspline_lines = {
    "# a bspline patch of degrees 2 and 1",  // 1
    "v 0 0 0",                               // 2
    "v 1 0 0",                               // 3
    "v 2 0 0",                               // 4
    "v 0 1 0",                               // 5
    "v 1 1 0",                               // 6
    "v 2 1 1",                               // 7
    "cstype bspline",                        // 8
    "deg 2 1",                               // 9
    "surf 0 1 0 1 1 2 3 4 5 6",              // 10
    "parm u 0 0 0 1 1 1",                    // 11
    "parm v 0 0 1 1",                        // 12
    "end",                                   // 13
};

FreeformSurface bspline_patch() {
  FreeformSurface s;
  s.basis = FreeformBasis::bspline;
  s.degree_u = 2;
  s.degree_v = 1;
  s.parameters_u = {0, 0, 0, 1, 1, 1};
  s.parameters_v = {0, 0, 1, 1};
  s.u0 = 0;
  s.u1 = 1;
  s.v0 = 0;
  s.v1 = 1;
  s.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0), Vec3(2, 1, 1)};
  s.weights = {1, 1, 1, 1, 1, 1};
  s.line = 10;
  return s;
}

// ---------------------------------------------------------------------------------------------
// Hand-written files, read to the exact records

TEST(ObjFreeform, ReadsAHandWrittenBsplineSurface) {
  const std::string text =
      "# a hull panel\n"
      "mtllib hull.mtl\n"
      "v -1.5 0 0\nv 0 0 0.25\nv 1.5 0 0\nv 3 0 0\n"
      "v -1.5 1 0\nv 0 1 0.5\nv 1.5 1 0\nv 3 1 0.125\n"
      "vt 0 0\nvn 0 0 1\n"
      "g hull\nusemtl steel\n"
      "cstype bspline\n"
      "deg 2 1\n"
      "ctech cparm 1\nstech cparma 1 1\n"
      "surf 0.25 1 0 1 1 2 3 4 5 6 7 8\n"
      "parm u 0 0 0 0.5 1 1 1   # one interior knot\n"
      "parm v 0 0 1 1\n"
      "end\n";
  const FreeformDocument document = parse_obj_freeform(text, "hull.obj");
  ASSERT_EQ(document.surfaces.size(), 1u);
  EXPECT_TRUE(document.curves.empty());
  FreeformSurface expected;
  expected.name = "hull";
  expected.basis = FreeformBasis::bspline;
  expected.rational = false;
  expected.degree_u = 2;
  expected.degree_v = 1;
  expected.parameters_u = {0, 0, 0, 0.5, 1, 1, 1};
  expected.parameters_v = {0, 0, 1, 1};
  expected.u0 = 0.25;
  expected.u1 = 1;
  expected.v0 = 0;
  expected.v1 = 1;
  expected.points = {Vec3(-1.5, 0, 0), Vec3(0, 0, 0.25), Vec3(1.5, 0, 0), Vec3(3, 0, 0),
                     Vec3(-1.5, 1, 0), Vec3(0, 1, 0.5),  Vec3(1.5, 1, 0), Vec3(3, 1, 0.125)};
  expected.weights = std::vector<double>(8, 1.0);
  expected.line = 19;
  EXPECT_EQ(document.surfaces[0], expected);
  EXPECT_EQ(control_point_counts(document.surfaces[0]), (std::pair<std::int64_t, std::int64_t>{4, 2}));
}

TEST(ObjFreeform, ReadsARationalBezierSurface) {
  // A quarter cylinder of radius 1 and height 2 as a rational Bezier patch: degree 2 around
  // (two segments: two eighth arcs, weight cos(pi/8) at their middle points), 1 along z.
  const double w = 0.92387953251128674;  // cos(pi / 8), as printed
  const double t = 0.41421356237309503;  // tan(pi / 8)
  const std::string text =
      "o quarter\n"
      "v 1 0 0\nv 1 0.41421356237309503 0 0.92387953251128674\nv 0.70710678118654757 0.70710678118654757 0\n"
      "v 0.41421356237309503 1 0 0.92387953251128674\nv 0 1 0\n"
      "v 1 0 2\nv 1 0.41421356237309503 2 0.92387953251128674\nv 0.70710678118654757 0.70710678118654757 2\n"
      "v 0.41421356237309503 1 2 0.92387953251128674\nv 0 1 2\n"
      "cstype rat bezier\n"
      "deg 2 1\n"
      "surf 0 2 0 1 1 2 3 4 5 6 7 8 9 10\n"
      "parm u 0 1 2\n"
      "parm v 0 1\n"
      "end\n";
  const FreeformDocument document = parse_obj_freeform(text, "quarter.obj");
  ASSERT_EQ(document.surfaces.size(), 1u);
  const FreeformSurface& s = document.surfaces[0];
  const double r = 0.70710678118654757;
  FreeformSurface expected;
  expected.name = "quarter";
  expected.basis = FreeformBasis::bezier;
  expected.rational = true;
  expected.degree_u = 2;
  expected.degree_v = 1;
  expected.parameters_u = {0, 1, 2};
  expected.parameters_v = {0, 1};
  expected.u0 = 0;
  expected.u1 = 2;
  expected.v0 = 0;
  expected.v1 = 1;
  expected.points = {Vec3(1, 0, 0), Vec3(1, t, 0), Vec3(r, r, 0), Vec3(t, 1, 0), Vec3(0, 1, 0),
                     Vec3(1, 0, 2), Vec3(1, t, 2), Vec3(r, r, 2), Vec3(t, 1, 2), Vec3(0, 1, 2)};
  expected.weights = {1, w, 1, w, 1, 1, w, 1, w, 1};
  expected.line = 14;
  EXPECT_EQ(s, expected);
  EXPECT_TRUE(same_bits(s, expected));
  // Two segments of degree 2 in u: 5 points; one of degree 1 in v: 2.
  EXPECT_EQ(control_point_counts(s), (std::pair<std::int64_t, std::int64_t>{5, 2}));
  EXPECT_EQ(bspline_knots(s.basis, s.degree_u, s.parameters_u), (std::vector<double>{0, 0, 0, 1, 1, 2, 2, 2}));
}

TEST(ObjFreeform, ReadsFromAStreamAsFromAString) {
  std::istringstream in(joined(bspline_lines));
  const FreeformDocument document = parse_obj_freeform(in, "stream.obj");
  ASSERT_EQ(document.surfaces.size(), 1u);
  EXPECT_EQ(document.surfaces[0], bspline_patch());
  std::istringstream bad(with_line(bspline_lines, 11, "parm u 0 0 1 0.5 1 1"));
  const auto error = testing::parse_error_of([&] { parse_obj_freeform(bad, "stream.obj"); });
  ASSERT_TRUE(error);
  EXPECT_EQ(std::string(error->what()).rfind("stream.obj:11:14: ", 0), 0u) << error->what();
}

TEST(ObjFreeform, RelativeIndicesEqualAbsoluteOnes) {
  const FreeformDocument absolute = parse_obj_freeform(joined(bspline_lines), "a.obj");
  const FreeformDocument relative =
      parse_obj_freeform(with_line(bspline_lines, 10, "surf 0 1 0 1 -6 -5 -4 -3 -2 -1"), "r.obj");
  const FreeformDocument mixed =
      parse_obj_freeform(with_line(bspline_lines, 10, "surf 0 1 0 1 1 -5 3 -3 5 -1"), "m.obj");
  ASSERT_EQ(absolute.surfaces.size(), 1u);
  EXPECT_EQ(absolute.surfaces[0], bspline_patch());
  EXPECT_EQ(relative, absolute);
  EXPECT_EQ(mixed, absolute);
  // Relative indices count back from the vertices read so far, not from the end of the file.
  std::vector<std::string> later = bspline_lines;
  later.push_back("v 9 9 9");
  later[9] = "surf 0 1 0 1 -6 -5 -4 -3 -2 -1";
  EXPECT_EQ(parse_obj_freeform(joined(later), "later.obj"), absolute);
}

TEST(ObjFreeform, VertexTextureNormalTriplesUseTheVertex) {
  std::vector<std::string> lines = bspline_lines;
  lines[0] = "vt 0 0\nvt 1 0\nvn 0 0 1";  // three lines in place of the comment: numbers shift by 2
  lines[9] = "surf 0 1 0 1 1/1/1 2/2/1 3//1 4/1 -2/-1/-1 6/2";
  const FreeformDocument document = parse_obj_freeform(joined(lines), "triples.obj");
  FreeformSurface expected = bspline_patch();
  expected.line = 12;
  ASSERT_EQ(document.surfaces.size(), 1u);
  EXPECT_EQ(document.surfaces[0], expected);
  // The vt and vn parts are checked against what was read before the surf.
  lines[9] = "surf 0 1 0 1 1/3 2 3 4 5 6";
  const auto texture = parse_error(joined(lines));
  ASSERT_TRUE(texture);
  EXPECT_EQ(texture->line(), 12);
  EXPECT_EQ(texture->column(), 14);
  EXPECT_NE(std::string(texture->what()).find("texture coordinate 3 but only 2"), std::string::npos) << texture->what();
  lines[9] = "surf 0 1 0 1 1 2 3 4 5 6//2";
  const auto normal = parse_error(joined(lines));
  ASSERT_TRUE(normal);
  EXPECT_EQ(normal->column(), 24);
  EXPECT_NE(std::string(normal->what()).find("normal 2 but only 1"), std::string::npos) << normal->what();
}

TEST(ObjFreeform, ContinuationLinesJoinIntoTheStatementWhereTheyStart) {
  std::vector<std::string> lines = bspline_lines;
  lines[9] = "surf 0 1 0 1 \\\n  1 2 3 \\   # a comment after the backslash hides nothing\n  4 5 6";
  lines[10] = "parm u 0 0 0\\\n1 1 1";  // the backslash ends the token: "0" and "1" stay apart
  const FreeformDocument document = parse_obj_freeform(joined(lines), "continued.obj");
  ASSERT_EQ(document.surfaces.size(), 1u);
  EXPECT_EQ(document.surfaces[0], bspline_patch());  // line 10: where the surf starts
  // Errors in a continuation line name the statement's line, the token's column in its own
  // line, and the continuation line.
  lines[9] = "surf 0 1 0 1 \\\n  1 2 3 \\\n  4 5 0";
  const auto error = parse_error(joined(lines));
  ASSERT_TRUE(error);
  EXPECT_EQ(error->line(), 10);
  EXPECT_EQ(error->column(), 7);
  EXPECT_NE(std::string(error->what()).find("(in continuation line 12)"), std::string::npos) << error->what();
}

TEST(ObjFreeform, SeveralSurfacesAndCurvesTakeTheirGroupNames) {
  std::vector<std::string> lines = bspline_lines;
  lines[0] = "g left wing";  // 1
  lines.insert(lines.end(), {
                                "g right",                       // 14
                                "surf 0 0.5 0.5 1 1 2 3 4 5 6",  // 15
                                "parm u 0 0 0 1 1 1",            // 16
                                "parm v 0 0 1 1",                // 17
                                "end",                           // 18
                                "o edge",                        // 19
                                "cstype rat bezier",             // 20
                                "v 0 0 0 2",                     // 21
                                "curv 0.5 1 1 -1 3",             // 22
                                "parm u 0 1",                    // 23
                                "end",                           // 24
                                "g",                             // 25
                                "surf 0 1 0 1 1 2 3 4 5 6",      // 26: bezier now, 3 x 2 points
                                "parm u 0 1",                    // 27
                                "parm v 0 1",                    // 28
                                "end",                           // 29
                            });
  lines[8] = "deg 2 1";
  const FreeformDocument document = parse_obj_freeform(joined(lines), "wings.obj");
  ASSERT_EQ(document.surfaces.size(), 3u);
  ASSERT_EQ(document.curves.size(), 1u);
  EXPECT_EQ(document.surfaces[0].name, "left wing");
  EXPECT_EQ(document.surfaces[0].line, 10);
  EXPECT_EQ(document.surfaces[1].name, "right");
  EXPECT_EQ(document.surfaces[1].line, 15);
  EXPECT_EQ(document.surfaces[1].u1, 0.5);
  EXPECT_EQ(document.surfaces[1].v0, 0.5);
  EXPECT_EQ(document.surfaces[2].name, "");
  EXPECT_EQ(document.surfaces[2].basis, FreeformBasis::bezier);
  EXPECT_TRUE(document.surfaces[2].rational);
  EXPECT_EQ(document.surfaces[2].line, 26);
  const FreeformCurve& curve = document.curves[0];
  EXPECT_EQ(curve.name, "edge");
  EXPECT_EQ(curve.line, 22);
  EXPECT_EQ(curve.basis, FreeformBasis::bezier);
  EXPECT_TRUE(curve.rational);
  EXPECT_EQ(curve.degree, 2);  // deg 2 1: a curve takes du
  EXPECT_EQ(curve.parameters, (std::vector<double>{0, 1}));
  EXPECT_EQ(curve.t0, 0.5);
  EXPECT_EQ(curve.t1, 1);
  EXPECT_EQ(curve.points, (std::vector<Vec3>{Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(2, 0, 0)}));
  EXPECT_EQ(curve.weights, (std::vector<double>{1, 2, 1}));
}

// ---------------------------------------------------------------------------------------------
// The Bezier basis as a B-spline

TEST(ObjFreeform, BezierBreakpointsBecomeClampedKnots) {
  const std::vector<double> breakpoints = {0, 1, 2.5};
  EXPECT_EQ(bspline_knots(FreeformBasis::bezier, 3, breakpoints),
            (std::vector<double>{0, 0, 0, 0, 1, 1, 1, 2.5, 2.5, 2.5, 2.5}));
  EXPECT_EQ(bspline_knots(FreeformBasis::bezier, 1, std::vector<double>{-1, 4}), (std::vector<double>{-1, -1, 4, 4}));
  EXPECT_EQ(bspline_knots(FreeformBasis::bspline, 3, breakpoints), breakpoints);
  // Two segments of degree 3: 7 points, as many as the equivalent knot vector gives a bspline.
  EXPECT_EQ(control_point_count(FreeformBasis::bezier, 3, breakpoints), 7);
  EXPECT_EQ(control_point_count(FreeformBasis::bspline, 3, bspline_knots(FreeformBasis::bezier, 3, breakpoints)), 7);
  EXPECT_EQ(control_point_count(FreeformBasis::bezier, 2, std::vector<double>{0}), 0);
  EXPECT_EQ(control_point_count(FreeformBasis::bspline, 2, std::vector<double>{0, 0, 0, 1, 1}), 0);
  EXPECT_EQ(control_point_count(FreeformBasis::bspline, 2, std::vector<double>{0, 0, 0, 1, 1, 1}), 3);
}

// de Boor's algorithm (Piegl and Tiller, The NURBS Book, A2.1 and A3.1) on scalar control values.
double de_boor(const std::vector<double>& knots, int p, const std::vector<double>& values, double t) {
  const auto n = static_cast<int>(values.size()) - 1;
  int span = p;
  while (span < n && t >= knots[static_cast<std::size_t>(span + 1)]) ++span;
  std::vector<double> d(static_cast<std::size_t>(p + 1));
  for (int j = 0; j <= p; ++j) d[static_cast<std::size_t>(j)] = values[static_cast<std::size_t>(span - p + j)];
  for (int r = 1; r <= p; ++r) {
    for (int j = p; j >= r; --j) {
      const double left = knots[static_cast<std::size_t>(span - p + j)];
      const double right = knots[static_cast<std::size_t>(span + 1 + j - r)];
      const double alpha = (t - left) / (right - left);
      d[static_cast<std::size_t>(j)] =
          (1 - alpha) * d[static_cast<std::size_t>(j - 1)] + alpha * d[static_cast<std::size_t>(j)];
    }
  }
  return d[static_cast<std::size_t>(p)];
}

// A piecewise Bezier function: segment k uses points k p .. k p + p over [b_k, b_k+1].
double piecewise_bezier(const std::vector<double>& breakpoints, int p, const std::vector<double>& values, double t) {
  std::size_t segment = 0;
  while (segment + 2 < breakpoints.size() && t >= breakpoints[segment + 1]) ++segment;
  const double s = (t - breakpoints[segment]) / (breakpoints[segment + 1] - breakpoints[segment]);
  double sum = 0;
  for (int i = 0; i <= p; ++i) {
    const double binomial = std::tgamma(p + 1) / (std::tgamma(i + 1) * std::tgamma(p - i + 1));
    sum += binomial * std::pow(s, i) * std::pow(1 - s, p - i) *
           values[segment * static_cast<std::size_t>(p) + static_cast<std::size_t>(i)];
  }
  return sum;
}

// The knot vector bspline_knots gives a Bezier record describes the same function.
RC_GTEST_PROP(ObjFreeform, BezierKnotsEvaluateLikeTheBezierSegments, ()) {
  const int p = *rc::gen::inRange(1, 6);
  const int segments = *rc::gen::inRange(1, 4);
  std::vector<double> breakpoints = {*rc::gen::inRange(-4, 4) / 2.0};
  for (int k = 0; k < segments; ++k) breakpoints.push_back(breakpoints.back() + *rc::gen::inRange(1, 9) / 4.0);
  std::vector<double> values;
  for (int k = 0; k < segments * p + 1; ++k) values.push_back(*rc::gen::inRange(-100, 101) / 10.0);
  const std::vector<double> knots = bspline_knots(FreeformBasis::bezier, p, breakpoints);
  RC_ASSERT(control_point_count(FreeformBasis::bspline, p, knots) == static_cast<std::int64_t>(values.size()));
  for (int step = 0; step <= 16; ++step) {
    const double t = breakpoints.front() + (breakpoints.back() - breakpoints.front()) * step / 16.0;
    const double expected = piecewise_bezier(breakpoints, p, values, t);
    RC_ASSERT(std::abs(de_boor(knots, p, values, t) - expected) <= 1e-9 * (1 + std::abs(expected)));
  }
}

// ---------------------------------------------------------------------------------------------
// Round trips

rc::Gen<double> finite_double() {
  const rc::Gen<double> from_bits =
      rc::gen::map(rc::gen::suchThat(rc::gen::arbitrary<std::uint64_t>(),
                                     [](std::uint64_t b) { return std::isfinite(std::bit_cast<double>(b)); }),
                   [](std::uint64_t b) { return std::bit_cast<double>(b); });
  const rc::Gen<double> decimal = rc::gen::map(rc::gen::inRange(-100000, 100001), [](int k) { return k / 1000.0; });
  return rc::gen::oneOf(from_bits, rc::gen::elementOf(testing::extreme_doubles()), decimal);
}

rc::Gen<double> positive_weight() {
  return rc::gen::map(rc::gen::suchThat(finite_double(), [](double w) { return w != 0.0; }),
                      [](double w) { return std::abs(w); });
}

// A direction of a valid record: degree, parameters and a range inside their domain.
struct RandomDirection {
  int degree;
  std::vector<double> parameters;
  double start;
  double end;
  std::int64_t count;
};

RandomDirection random_direction(FreeformBasis basis) {
  RandomDirection d;
  d.degree = *rc::gen::inRange(1, 5);
  const double origin = *rc::gen::element(0.0, -1.0, 0.1, 1e-300, 12345.678);
  const double scale = *rc::gen::element(1.0, 0.1, 1.0 / 3.0, 1e6);
  if (basis == FreeformBasis::bezier) {
    const int segments = *rc::gen::inRange(1, 4);
    d.parameters.push_back(origin);
    for (int k = 0; k < segments; ++k) d.parameters.push_back(d.parameters.back() + *rc::gen::inRange(1, 5) * scale);
  } else {
    // Non-decreasing knots, no run longer than degree + 1 (gaps of 0 at most `degree` in a row).
    const int points = *rc::gen::inRange(d.degree + 1, d.degree + 5);
    d.parameters.push_back(origin);
    int run = 1;
    for (int k = 1; k < points + d.degree + 1; ++k) {
      const bool repeat = run <= d.degree && *rc::gen::inRange(0, 3) == 0;
      d.parameters.push_back(repeat ? d.parameters.back() : d.parameters.back() + *rc::gen::inRange(1, 5) * scale);
      run = repeat ? run + 1 : 1;
    }
  }
  d.count = control_point_count(basis, d.degree, d.parameters);
  const std::vector<double> knots = bspline_knots(basis, d.degree, d.parameters);
  const double low = knots[static_cast<std::size_t>(d.degree)];
  const double high = knots[static_cast<std::size_t>(d.count)];
  d.start = *rc::gen::element(low, low + (high - low) / 3);
  d.end = *rc::gen::element(high, low + (high - low) / 2);
  return d;
}

template <class Record>
bool record_is_valid(const Record& record) {
  try {
    validate(record);
    return true;
  } catch (const InvalidInput&) {
    return false;
  }
}

template <class Record>
void random_points(Record& record, std::int64_t count) {
  for (std::int64_t k = 0; k < count; ++k) {
    record.points.emplace_back(*finite_double(), *finite_double(), *finite_double());
    record.weights.push_back(record.rational ? *positive_weight() : 1.0);
  }
}

FreeformDocument random_document() {
  FreeformDocument document;
  const std::vector<std::string> names = {"", "a", "hull part", "x_1", "n\xc3\xa4me"};
  const int surfaces = *rc::gen::inRange(0, 3);
  const int curves = *rc::gen::inRange(surfaces == 0 ? 1 : 0, 3);
  for (int k = 0; k < surfaces; ++k) {
    FreeformSurface s;
    s.name = *rc::gen::elementOf(names);
    s.basis = *rc::gen::element(FreeformBasis::bezier, FreeformBasis::bspline);
    s.rational = *rc::gen::arbitrary<bool>();
    const RandomDirection u = random_direction(s.basis);
    const RandomDirection v = random_direction(s.basis);
    s.degree_u = u.degree;
    s.degree_v = v.degree;
    s.parameters_u = u.parameters;
    s.parameters_v = v.parameters;
    s.u0 = u.start;
    s.u1 = u.end;
    s.v0 = v.start;
    s.v1 = v.end;
    random_points(s, u.count * v.count);
    document.surfaces.push_back(std::move(s));
  }
  for (int k = 0; k < curves; ++k) {
    FreeformCurve c;
    c.name = *rc::gen::elementOf(names);
    c.basis = *rc::gen::element(FreeformBasis::bezier, FreeformBasis::bspline);
    c.rational = *rc::gen::arbitrary<bool>();
    const RandomDirection t = random_direction(c.basis);
    c.degree = t.degree;
    c.parameters = t.parameters;
    c.t0 = t.start;
    c.t1 = t.end;
    random_points(c, t.count);
    document.curves.push_back(std::move(c));
  }
  return document;
}

// The 1-based numbers of the lines of `text` that start with `keyword` and a space.
std::vector<std::int64_t> lines_starting_with(const std::string& text, const std::string& keyword) {
  std::vector<std::int64_t> lines;
  std::int64_t line = 1;
  for (std::size_t start = 0; start < text.size(); ++line) {
    if (text.compare(start, keyword.size() + 1, keyword + " ") == 0) lines.push_back(line);
    start = text.find('\n', start) + 1;
    if (start == 0) break;
  }
  return lines;
}

RC_GTEST_PROP(ObjFreeform, WriteThenReadIsBitExact, ()) {
  const FreeformDocument document = random_document();
  // Rounding in the range (low + (high - low) / 3) may reach past the domain: such ranges are
  // not valid documents.
  for (const FreeformSurface& s : document.surfaces) RC_PRE(record_is_valid(s));
  for (const FreeformCurve& c : document.curves) RC_PRE(record_is_valid(c));
  const std::string text = format_obj_freeform(document);
  const FreeformDocument back = parse_obj_freeform(text, "back.obj");
  RC_ASSERT(same_bits(back, document));
  // Each record's line is where its surf or curv statement stands.
  const std::vector<std::int64_t> surf_lines = lines_starting_with(text, "surf");
  const std::vector<std::int64_t> curv_lines = lines_starting_with(text, "curv");
  RC_ASSERT(surf_lines.size() == back.surfaces.size());
  RC_ASSERT(curv_lines.size() == back.curves.size());
  for (std::size_t k = 0; k < surf_lines.size(); ++k) RC_ASSERT(back.surfaces[k].line == surf_lines[k]);
  for (std::size_t k = 0; k < curv_lines.size(); ++k) RC_ASSERT(back.curves[k].line == curv_lines[k]);
  RC_ASSERT(format_obj_freeform(back) == text);
}

TEST(ObjFreeform, WritesTheExpectedText) {
  FreeformDocument document;
  document.surfaces.push_back(bspline_patch());
  FreeformCurve curve;
  curve.name = "rim";
  curve.basis = FreeformBasis::bezier;
  curve.rational = true;
  curve.degree = 2;
  curve.parameters = {0, 1};
  curve.t0 = 0.25;
  curve.t1 = 1;
  curve.points = {Vec3(0.1, 0, 0), Vec3(1, 1, -0.0), Vec3(2, 0, 1e300)};
  curve.weights = {1, 0.5, 1.0 / 3.0};
  document.curves.push_back(curve);
  const std::string expected =
      "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 1\n"
      "cstype bspline\ndeg 2 1\nsurf 0 1 0 1 1 2 3 4 5 6\nparm u 0 0 0 1 1 1\nparm v 0 0 1 1\nend\n"
      "g rim\n"
      "v 0.1 0 0 1\nv 1 1 -0 0.5\nv 2 0 1e+300 0.3333333333333333\n"
      "cstype rat bezier\ndeg 2\ncurv 0.25 1 7 8 9\nparm u 0 1\nend\n";
  EXPECT_EQ(format_obj_freeform(document), expected);
  const FreeformDocument back = parse_obj_freeform(expected, "written.obj");
  EXPECT_TRUE(same_bits(back, document));
}

TEST(ObjFreeform, WriteToAFileAndReadItBack) {
  const TemporaryDirectory folder;
  FreeformDocument document;
  document.surfaces.push_back(bspline_patch());
  const fs::path path = folder.path() / "patch.obj";
  write_obj_freeform(path, document);
  FreeformDocument expected = document;
  expected.surfaces[0].line = 9;  // after the six v lines, cstype and deg
  EXPECT_EQ(read_obj_freeform(path), expected);
  EXPECT_EQ(folder.entries(), std::vector<std::string>{"patch.obj"});  // no temporary left
}

// ---------------------------------------------------------------------------------------------
// Malformed files: each a ParseError at its place, naming what was wrong

TEST(ObjFreeform, MalformedRecordsAreAParseErrorAtTheRightPlace) {
  const auto edit = [](std::size_t line, const std::string& replacement) {
    return with_line(bspline_lines, line, replacement);
  };
  std::vector<std::string> appended = bspline_lines;
  appended.emplace_back("PLACEHOLDER");
  const auto after_end = [&](const std::string& line14) { return with_line(appended, 14, line14); };
  std::vector<std::string> bezier = bspline_lines;
  bezier[7] = "cstype bezier";
  bezier[10] = "parm u 0 1";
  bezier[11] = "parm v 0 1";
  const auto bezier_edit = [&](std::size_t line, const std::string& replacement) {
    return with_line(bezier, line, replacement);
  };
  EXPECT_NO_THROW(parse_obj_freeform(joined(bezier), "bezier.obj"));
  expect_malformed({
      // Knots, breakpoints and counts
      {"knots decrease", edit(11, "parm u 0 0 0.5 0.25 1 1"), 11, 16, {"parm u", "must not decrease", "0.5 then 0.25"}},
      {"knot repeated past degree + 1",
       edit(11, "parm u 0 0 0 0 1 1 1"),
       11,
       14,
       {"knot 0", "more than degree + 1 = 3"}},
      {"knots too many for the points",
       edit(11, "parm u 0 0 0 0.5 1 1 1"),
       10,
       1,
       {"make 4 x 2 = 8 control points", "knots = points + degree + 1", "surf lists 6"}},
      {"knots too few for the degree",
       edit(11, "parm u 0 0 1 1"),
       11,
       6,
       {"gives 4 knots", "at least 2 * (degree + 1) = 6"}},
      {"empty knot domain", edit(12, "parm v 0 1 1 2"), 12, 6, {"parm v", "domain [1, 1] is empty"}},
      {"nan knot", edit(11, "parm u 0 0 nan 1 1 1"), 11, 12, {"finite parameter", "'nan'"}},
      {"knot a word", edit(12, "parm v 0 0 one 1"), 12, 12, {"finite parameter", "'one'"}},
      {"bezier points not segments * degree + 1",
       bezier_edit(11, "parm u 0 1 2"),
       10,
       1,
       {"5 x 2 = 10", "points = segments * degree + 1", "surf lists 6"}},
      {"bezier breakpoints repeat", bezier_edit(11, "parm u 0 1 1"), 11, 12, {"increase strictly", "1 then 1"}},
      {"bezier breakpoints decrease", bezier_edit(12, "parm v 1 0"), 12, 10, {"increase strictly", "1 then 0"}},
      {"bezier single breakpoint", bezier_edit(12, "parm v 0"), 12, 6, {"gives 1 breakpoints", "at least 2"}},
      // Ranges
      {"range past the domain", edit(10, "surf 0 2 0 1 1 2 3 4 5 6"), 10, 8, {"u range ends at 2", "domain [0, 1]"}},
      {"range before the domain", edit(10, "surf -0.5 1 0 1 1 2 3 4 5 6"), 10, 6, {"u range starts at -0.5"}},
      {"empty u range", edit(10, "surf 0.5 0.5 0 1 1 2 3 4 5 6"), 10, 10, {"u range [0.5, 0.5] is empty"}},
      {"reversed v range", edit(10, "surf 0 1 1 0 1 2 3 4 5 6"), 10, 12, {"v range [1, 0] is empty"}},
      {"range not finite", edit(10, "surf 0 inf 0 1 1 2 3 4 5 6"), 10, 8, {"finite parameter", "'inf'"}},
      {"range cut short", edit(10, "surf 0 1 0"), 10, 11, {"'surf u0 u1 v0 v1'"}},
      // Vertices and weights
      {"weight 0", edit(5, "v 0 1 0 0"), 5, 9, {"weight > 0", "'0'"}},
      {"negative weight", edit(5, "v 0 1 0 -1"), 5, 9, {"weight > 0", "'-1'"}},
      {"nan weight", edit(5, "v 0 1 0 nan"), 5, 9, {"finite weight", "'nan'"}},
      {"infinite weight", edit(5, "v 0 1 0 inf"), 5, 9, {"finite weight", "'inf'"}},
      {"infinite coordinate", edit(5, "v 0 inf 0"), 5, 5, {"finite coordinate", "'inf'"}},
      {"nan coordinate", edit(5, "v nan 1 0"), 5, 3, {"finite coordinate", "'nan'"}},
      {"vertex of two numbers", edit(5, "v 0 1"), 5, 6, {"3 to 4 numbers", "found 2"}},
      {"vertex of five numbers", edit(5, "v 0 1 0 1 2"), 5, 11, {"3 to 4 numbers", "found 5"}},
      {"weight in a non-rational record",
       edit(5, "v 0 1 0 0.5"),
       10,
       20,
       {"control point 3 has weight 0.5", "not rational"}},
      {"vn of two numbers", edit(1, "vn 0 1"), 1, 7, {"3 numbers", "found 2"}},
      {"vt a word", edit(1, "vt 0 u"), 1, 6, {"finite number", "'u'"}},
      // Indices
      {"index 0", edit(10, "surf 0 1 0 1 0 2 3 4 5 6"), 10, 14, {"nonzero integers", "'0'"}},
      {"index past the vertices", edit(10, "surf 0 1 0 1 1 2 3 4 5 7"), 10, 24, {"uses vertex 7", "only 6 vertices"}},
      {"relative index before the first vertex",
       edit(10, "surf 0 1 0 1 -7 2 3 4 5 6"),
       10,
       14,
       {"relative index -7", "6 vertices defined so far"}},
      {"most negative index",
       edit(10, "surf 0 1 0 1 -9223372036854775808 2 3 4 5 6"),
       10,
       14,
       {"relative index -9223372036854775808"}},
      {"index a word", edit(10, "surf 0 1 0 1 a 2 3 4 5 6"), 10, 14, {"control point", "'a'"}},
      {"four-part reference", edit(10, "surf 0 1 0 1 1/1/1/1 2 3 4 5 6"), 10, 14, {"'1/1/1/1'"}},
      {"vertex after the surf",
       "cstype bspline\ndeg 1\ncurv 0 1 1 2\nparm u 0 0 1 1\nend\nv 0 0 0\nv 1 0 0\n",
       3,
       10,
       {"uses vertex 1", "only 0 vertices"}},
      {"vt in a curve",
       "v 0 0 0\nv 1 0 0\nvt 0 0\ncstype bspline\ndeg 1\ncurv 0 1 1/1 2\nparm u 0 0 1 1\nend\n",
       6,
       10,
       {"curv control points are vertex indices", "'1/1'"}},
      // Statements out of place
      {"surf without cstype", edit(8, ""), 10, 1, {"'surf' without a 'cstype'"}},
      {"surf without deg", edit(9, ""), 10, 1, {"'surf' without a 'deg'"}},
      {"surf with one degree", edit(9, "deg 2"), 10, 1, {"needs 'deg du dv'", "line 9"}},
      {"parm outside a block", after_end("parm u 0 0 1 1"), 14, 1, {"'parm' outside a curv or surf block"}},
      {"end outside a block", after_end("end"), 14, 1, {"'end' outside a curv or surf block"}},
      {"missing end", edit(13, ""), 12, 15, {"missing 'end'", "surf block of line 10"}},
      {"parm v twice", edit(13, "parm v 0 0 1 1") + "end\n", 13, 6, {"second 'parm v'", "line 12"}},
      {"no parm v", edit(12, ""), 13, 1, {"surf block of line 10 has no 'parm v'"}},
      {"parm w", edit(12, "parm w 0 0 1 1"), 12, 6, {"'parm u' or 'parm v'"}},
      {"parm v in a curve",
       "v 0 0 0\nv 1 0 0\ncstype bspline\ndeg 1\ncurv 0 1 1 2\nparm v 0 0 1 1\nend\n",
       6,
       6,
       {"'parm v' in a curv block"}},
      {"vertex inside a block", edit(12, "v 0 0 0"), 12, 1, {"expected 'parm' or 'end'", "block of line 10", "'v'"}},
      {"end with words", edit(13, "end now"), 13, 5, {"'end' alone"}},
      // cstype and deg
      {"unknown cstype", edit(8, "cstype nurbs"), 8, 8, {"unknown cstype 'nurbs'"}},
      {"rat after the type", edit(8, "cstype bspline rat"), 8, 8, {"'cstype [rat] bezier'"}},
      {"cstype alone", edit(8, "cstype"), 8, 7, {"'cstype [rat] bezier'"}},
      {"degree 0", edit(9, "deg 0 1"), 9, 5, {"degree in [1, 64]", "'0'"}},
      {"degree 65", edit(9, "deg 2 65"), 9, 7, {"degree in [1, 64]", "'65'"}},
      {"deg of three", edit(9, "deg 1 1 1"), 9, 9, {"'deg du dv'"}},
      // The file
      {"empty file", "", 1, 1, {"no free-form curve or surface"}},
      {"vertices only", "v 0 0 0\nv 1 0 0\n", 2, 8, {"no free-form curve or surface"}},
      {"unknown statement", edit(2, "vx 1 2 3"), 2, 1, {"unknown OBJ statement 'vx'"}},
      {"binary garbage",
       std::string("\x7f"
                   "ELF\x02\x01\x00\xff\n",
                   9),
       1,
       1,
       {"unknown OBJ statement", "\\x7fELF"}},
  });
}

// A knot inside the domain standing p + 1 times would cut the surface in two (a B-spline allows
// at most p there): refused where it stands, not later by the surface type without a line.
TEST(ObjFreeform, InteriorKnotsStandAtMostDegreeTimes) {
  std::string text;
  for (int k = 0; k < 8; ++k) text += "v " + std::to_string(k % 4) + " " + std::to_string(k / 4) + " 0\n";
  text += "cstype bspline\ndeg 1 1\nsurf 0 1 0 1 1 2 3 4 5 6 7 8\nparm u 0 0 0.5 0.5 1 1\nparm v 0 0 1 1\nend\n";
  try {
    (void)parse_obj_freeform(text, "double.obj");
    FAIL() << "no ParseError";
  } catch (const ParseError& e) {
    EXPECT_NE(std::string(e.what()).find("double.obj:12:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("knot 0.5 stands more than degree = 1 times inside the domain"), std::string::npos)
        << e.what();
  }
  // Once (degree 1: C^0 there) it is a surface of two spans.
  const std::string three = text.substr(0, text.find("cstype")) +
                            "cstype bspline\ndeg 1 1\nsurf 0 1 0 1 1 2 3 5 6 7\nparm u 0 0 0.5 1 1\nparm v 0 0 1 1\nend\n";
  EXPECT_NO_THROW((void)parse_obj_freeform(three, "once.obj"));
}

// Free-form detection sees what the readers see: comments, continuation lines, blanks.
TEST(ObjFreeform, DetectionTokenizesAsTheReadersDo) {
  EXPECT_TRUE(is_obj_freeform("v 0 0 0\n  \tsurf 0 1 0 1 1\n"));
  EXPECT_TRUE(is_obj_freeform("cstype bspline # a comment\n"));
  EXPECT_FALSE(is_obj_freeform("v 0 0 0\nf 1 2 3\n# cstype in a comment\n"));
  EXPECT_FALSE(is_obj_freeform("#cstype glued to the comment sign\nf 1 2 3\n"));
  // "g part \" continued by "end" is the group name "part end", not an end statement.
  EXPECT_FALSE(is_obj_freeform("v 0 0 0\ng part \\\nend\nf 1 1 1\n"));
}

TEST(ObjFreeform, UnsupportedStatementsAreRefusedByName) {
  for (const char* keyword :
       {"trim", "hole", "scrv", "sp", "con", "bmat", "step", "curv2", "mg", "call", "csh", "f", "l", "p"}) {
    SCOPED_TRACE(keyword);
    for (const std::size_t line : {1u, 12u}) {  // before the block and inside it
      const auto error = parse_error(with_line(bspline_lines, line, std::string(keyword) + " 0 1 1"));
      ASSERT_TRUE(error);
      EXPECT_EQ(error->line(), static_cast<std::int64_t>(line));
      EXPECT_EQ(error->column(), 1);
      EXPECT_EQ(std::string(error->what())
                    .rfind("bad.obj:" + std::to_string(line) + ":1: unsupported statement '" + keyword + "': ", 0),
                0u)
          << error->what();
    }
  }
  const auto polygon = parse_error(with_line(bspline_lines, 1, "f 1 2 3"));
  ASSERT_TRUE(polygon);
  EXPECT_NE(std::string(polygon->what()).find("read_obj (io/obj.h)"), std::string::npos) << polygon->what();
  for (const char* type : {"cardinal", "taylor", "bmatrix"}) {
    SCOPED_TRACE(type);
    const auto error = parse_error(with_line(bspline_lines, 8, std::string("cstype rat ") + type));
    ASSERT_TRUE(error);
    EXPECT_EQ(error->line(), 8);
    EXPECT_EQ(error->column(), 12);
    EXPECT_NE(std::string(error->what()).find(std::string("unsupported statement 'cstype ") + type + "'"),
              std::string::npos)
        << error->what();
  }
}

TEST(ObjFreeform, DisplayHintsAreReadPast) {
  std::vector<std::string> lines = bspline_lines;
  lines[0] =
      "ctech cparm 0.5\nstech curv 0.5 10\ns 1\nusemtl red\nmtllib a.mtl\nlod 2\nbevel off\n"
      "c_interp on\nd_interp off\nmaplib a.map\nusemap b\nshadow_obj s.obj\ntrace_obj t.obj";
  FreeformSurface expected = bspline_patch();
  expected.line += 12;
  const FreeformDocument document = parse_obj_freeform(joined(lines), "hints.obj");
  ASSERT_EQ(document.surfaces.size(), 1u);
  EXPECT_EQ(document.surfaces[0], expected);
}

// ---------------------------------------------------------------------------------------------
// Files: nothing half written

TEST(ObjFreeform, InvalidDocumentsAreRefusedBeforeAnythingIsWritten) {
  const TemporaryDirectory folder;
  const fs::path path = folder.path() / "kept.obj";
  put_file(path, "previous content\n");
  const FreeformSurface good = bspline_patch();
  std::vector<std::pair<const char*, FreeformDocument>> bad;
  bad.push_back({"no curve or surface", FreeformDocument{}});
  // The good surface changed by `change`, after a good one (the second record fails).
  const auto changed = [&](const char* what, auto change) {
    FreeformSurface surface = good;
    change(surface);
    bad.push_back({what, FreeformDocument{{good, surface}, {}}});
    return surface;
  };
  const FreeformSurface decreasing =
      changed("must not decrease", [](FreeformSurface& s) { s.parameters_u = {0, 0, 1, 0.5, 1, 1}; });
  changed("surf lists 5", [](FreeformSurface& s) {
    s.points.pop_back();
    s.weights.pop_back();
  });
  changed("not rational", [](FreeformSurface& s) { s.weights[2] = 2; });
  changed("has a name that holds", [](FreeformSurface& s) { s.name = "a # b"; });
  changed("has a name that has leading", [](FreeformSurface& s) { s.name = " a"; });
  FreeformCurve zero_weight;
  zero_weight.rational = true;
  zero_weight.parameters = {0, 0, 1, 1};
  zero_weight.points = {Vec3(0, 0, 0), Vec3(1, 0, 0)};
  zero_weight.weights = {1, 0};
  bad.push_back({"weights are finite and > 0", FreeformDocument{{}, {zero_weight}}});
  for (const auto& [what, document] : bad) {
    SCOPED_TRACE(what);
    try {
      write_obj_freeform(path, document);
      ADD_FAILURE() << "no InvalidInput";
    } catch (const InvalidInput& error) {
      EXPECT_NE(std::string(error.what()).find(what), std::string::npos) << error.what();
      EXPECT_EQ(std::string(error.what()).rfind("format_obj_freeform: ", 0), 0u) << error.what();
    }
    EXPECT_EQ(testing::slurp(path), "previous content\n");
    EXPECT_EQ(folder.entries(), std::vector<std::string>{"kept.obj"});
  }
  EXPECT_THROW(validate(decreasing), InvalidInput);
  EXPECT_THROW(validate(zero_weight), InvalidInput);
  EXPECT_NO_THROW(validate(good));
}

TEST(ObjFreeform, UnwritablePathLeavesNoFile) {
  const TemporaryDirectory folder;
  FreeformDocument document;
  document.surfaces.push_back(bspline_patch());
  EXPECT_THROW(write_obj_freeform(folder.path() / "missing" / "patch.obj", document), IoError);
  fs::create_directory(folder.path() / "folder.obj");
  EXPECT_THROW(write_obj_freeform(folder.path() / "folder.obj", document), IoError);
  EXPECT_EQ(folder.entries(), std::vector<std::string>{"folder.obj"});
  EXPECT_TRUE(fs::is_empty(folder.path() / "folder.obj"));
}

TEST(ObjFreeform, ReadErrorsNameTheFile) {
  const TemporaryDirectory folder;
  const fs::path path = folder.path() / "bad.obj";
  put_file(path, with_line(bspline_lines, 11, "parm u 0 0 1 0.5 1 1"));
  const auto error = testing::parse_error_of([&] { read_obj_freeform(path); });
  ASSERT_TRUE(error);
  EXPECT_EQ(error->path(), path.string());
  EXPECT_EQ(std::string(error->what()).rfind(path.string() + ":11:14: ", 0), 0u) << error->what();
  EXPECT_THROW(read_obj_freeform(folder.path() / "absent.obj"), IoError);
  EXPECT_THROW(read_obj_freeform(folder.path()), IoError);
}

// The seeds of tests/fuzz/fuzz_obj_freeform are valid files (a seed that fails at once would
// leave the fuzzer to find the valid part by itself), each with the records it was written for.
TEST(ObjFreeform, FuzzSeedsRead) {
  const fs::path seeds = fs::path(PATCHWORK_SOURCE_DIR) / "tests" / "fuzz" / "corpus" / "fuzz_obj_freeform";
  const std::vector<std::pair<const char*, std::pair<std::size_t, std::size_t>>> expected = {
      {"bspline_patch.obj", {1, 0}},
      {"curve_continuation_triples.obj", {1, 1}},
      {"rational_bezier_cylinder.obj", {1, 0}}};
  for (const auto& [name, counts] : expected) {
    SCOPED_TRACE(name);
    const FreeformDocument document = read_obj_freeform(seeds / name);
    EXPECT_EQ(document.surfaces.size(), counts.first);
    EXPECT_EQ(document.curves.size(), counts.second);
  }
}

}  // namespace
}  // namespace patchwork
