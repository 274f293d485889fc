#include "surfaces/patch_grid.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "surfaces/surface_normal.h"
#include "tests/surfaces/patch_fixtures.h"

namespace patchwork {
namespace {

// evaluate_grid against pointwise evaluation on the grid of `weights`.
void check_against_pointwise(const BezierPatch3& patch, const PatchGridWeights& weights) {
  // A patch without a normal somewhere (a point or a curve: small generated sizes make those)
  // is rejected by unit_normal and by evaluate_grid alike.
  bool degenerate = false;
  for (double u : weights.us()) {
    for (double v : weights.vs()) {
      try {
        unit_normal(patch, u, v);
      } catch (const NumericalError&) {
        degenerate = true;
      }
    }
  }
  if (degenerate) {
    RC_ASSERT_THROWS_AS(evaluate_grid(patch, weights), NumericalError);
    return;
  }
  const PatchGridSamples samples = evaluate_grid(patch, weights);
  RC_ASSERT(samples.points.size() == weights.us().size() * weights.vs().size());
  for (std::size_t b = 0; b < weights.vs().size(); ++b) {
    for (std::size_t a = 0; a < weights.us().size(); ++a) {
      const double u = weights.us()[a];
      const double v = weights.vs()[b];
      const std::size_t k = a + samples.count_u * b;
      // Two ways of summing the same convex combinations: a few roundings of the net's size.
      RC_ASSERT((samples.points[k] - patch.evaluate(u, v)).norm() <= 1e-13 * testing::net_scale(patch));
      const Vec3 n = normal(patch, u, v);
      if (n.norm() > 1e-6) {
        const double conditioning =
            derivative(patch, u, v, 1, 0).norm() * derivative(patch, u, v, 0, 1).norm() / n.norm();
        RC_ASSERT((samples.normals[k] - unit_normal(patch, u, v)).norm() <= 1e-12 * conditioning);
      }
    }
  }
}

// `count` parameters in [0, 1], multiples of 1/1000 (repeats and the ends come up often).
std::vector<double> random_parameters(std::size_t count) {
  std::vector<double> ts(count);
  for (double& t : ts) t = *rc::gen::inRange(0, 1001) / 1000.0;
  return ts;
}

RC_GTEST_PROP(PatchGrid, MatchesPointwiseEvaluation, ()) {
  const BezierPatch3 patch = *testing::random_patch(1, 5);
  const auto segments_u = static_cast<std::size_t>(*rc::gen::inRange(1, 9));
  const auto segments_v = static_cast<std::size_t>(*rc::gen::inRange(1, 9));
  check_against_pointwise(patch, PatchGridWeights::uniform(patch.degree_u(), patch.degree_v(), segments_u, segments_v));
}

// A single column (one u, the side of a pattern) is evaluated along v; it matches too.
RC_GTEST_PROP(PatchGrid, OneColumnMatchesPointwiseEvaluation, ()) {
  const BezierPatch3 patch = *testing::random_patch(1, 4);
  const std::vector<double> us = {*rc::gen::inRange(0, 5) / 4.0};
  std::vector<double> vs(static_cast<std::size_t>(*rc::gen::inRange(2, 12)));
  for (std::size_t b = 0; b < vs.size(); ++b) vs[b] = static_cast<double>(b) / static_cast<double>(vs.size() - 1);
  check_against_pointwise(patch, PatchGridWeights(patch.degree_u(), patch.degree_v(), us, vs));
}

TEST(PatchGrid, CollapsedEdgeGetsTheLimitNormal) {
  // The octant-like cap: row j = 0 collapsed to the origin on the paraboloid z = x^2 + y^2.
  const BezierPatch3 patch = testing::product_patch({Vec3(1, 0, 1), Vec3(0.5, 0.5, 0), Vec3(0, 1, 1)},
                                                    {Vec3(0, 0, 0), Vec3(0.5, 0.5, 0), Vec3(1, 1, 1)});
  const PatchGridSamples samples = evaluate_grid(patch, PatchGridWeights::uniform(2, 2, 4, 4));
  for (std::size_t a = 0; a < samples.count_u; ++a) {
    EXPECT_LT((samples.normals[a] - Vec3(0, 0, -1)).norm(), 1e-12);
    EXPECT_LT(samples.points[a].norm(), 1e-15);
  }
}

// The boundary points' evaluator gives the grid's samples at any list of points: positions,
// normals (the limit normal on a collapsed edge) and tangents, for polynomial patches of every
// degree (the unrolled ones up to 3 and the general loop) and rational ones.
RC_GTEST_PROP(PatchGrid, PointListMatchesTheGridSamples, ()) {
  const BezierPatch3 patch = *testing::random_patch(1, 5);
  const bool rational = *rc::gen::arbitrary<bool>();
  std::vector<double> weights(patch.control_points().size(), 1.0);
  if (rational) {
    for (double& w : weights) w = *rc::gen::inRange(1, 17) / 4.0;
  }
  const RationalBezierPatch homogeneous(patch.degree_u(), patch.degree_v(), patch.control_points(), weights);
  std::vector<Vec2> uvs;
  for (int k = *rc::gen::inRange(1, 12); k > 0; --k) {
    // Corners and edges as often as interior points: a pattern's boundary.
    const auto coordinate = [] { return *rc::gen::inRange(0, 9) / 8.0; };
    uvs.emplace_back(coordinate(), coordinate());
  }
  const bool tangents = *rc::gen::arbitrary<bool>();
  std::vector<Vec3> points(uvs.size()), normals(uvs.size()), grid_points(1), grid_normals(1);
  std::vector<Vec4> with(tangents ? uvs.size() : 0), grid_tangents(tangents ? 1 : 0);
  try {
    if (rational) {
      evaluate_samples(homogeneous, uvs, {points, normals, with});
    } else {
      evaluate_samples(patch, uvs, {points, normals, with});
    }
  } catch (const NumericalError&) {
    RC_DISCARD("a point without a normal (generated nets can be degenerate)");
  }
  const double scale = testing::net_scale(patch);
  for (std::size_t k = 0; k < uvs.size(); ++k) {
    const std::array<double, 1> u = {uvs[k].x()};
    const std::array<double, 1> v = {uvs[k].y()};
    const PatchGridWeights one(patch.degree_u(), patch.degree_v(), u, v);
    if (rational) {
      evaluate_grid(homogeneous, one, {grid_points, grid_normals, grid_tangents});
    } else {
      evaluate_grid(patch, one, {grid_points, grid_normals, grid_tangents});
    }
    RC_ASSERT((points[k] - grid_points[0]).norm() <= 1e-13 * scale);
    // Normals agree to the rounding of the derivatives over |F_u x F_v|: the conditioning
    // |F_u| |F_v| / |F_u x F_v| scales the difference (as against pointwise evaluation above).
    const PartialDerivatives<3> d =
        rational ? partial_derivatives(homogeneous, u[0], v[0], 1) : partial_derivatives(patch, u[0], v[0], 1);
    const double cross = d.at(1, 0).cross(d.at(0, 1)).norm();
    if (cross > 1e-6 * scale * scale) {
      const double conditioning = d.at(1, 0).norm() * d.at(0, 1).norm() / cross;
      RC_ASSERT((normals[k] - grid_normals[0]).norm() <= 1e-12 * conditioning);
      if (tangents) RC_ASSERT((with[k] - grid_tangents[0]).norm() <= 1e-11 * conditioning * conditioning);
    }
    if (!rational) RC_ASSERT((evaluate_point(patch, u[0], v[0]) - patch.evaluate(u[0], v[0])).norm() <= 1e-13 * scale);
  }
}

// A pole far from the origin: F_u = sum_k B_k'(u) P_k over a collapsed row is rounding noise of
// size eps |P|, not zero (and where the row's points differ by rounding, as after a split, so is
// F_u from differences), so a threshold relative to the net's size alone took it for a regular
// derivative and the normal was that noise's (2.2 rad off at an offset of 1e6). Translated copies
// of a cone-like patch, and of a piece split from it, must keep the unmoved normals (to rounding)
// on the collapsed side: in the grid, the scattered samples, unit_normal and the rational
// evaluators. The offsets include one whose coordinates are not integers (the rational net's
// H / w then does not give back P exactly).
TEST(PatchGrid, PoleNormalsDoNotDependOnTheDistanceFromTheOrigin) {
  const auto net = [](const Vec3& offset) {
    std::vector<Vec3> points;
    for (int j = 0; j <= 3; ++j) {
      for (int i = 0; i <= 3; ++i) {
        const double r = j / 3.0;  // row j = 0 collapsed: a pole
        points.push_back(offset + Vec3(r * std::cos(0.5 * i), r * std::sin(0.5 * i), 0.3 * r * r));
      }
    }
    return BezierPatch3(3, 3, points);
  };
  const std::vector<double> us = {0.0, 0.3, 0.7, 1.0};
  const std::vector<double> vs = {0.0, 0.5};
  const PatchGridWeights weights(3, 3, us, vs);
  std::vector<Vec2> uvs;
  for (const double v : vs)
    for (const double u : us) uvs.emplace_back(u, v);
  std::vector<double> varied_weights;
  for (int k = 0; k < 16; ++k) varied_weights.push_back(1.0 + 0.25 * (k % 4));
  // The normals of a net: grid, samples, unit_normal, then the same of its rational form.
  const auto normals_of = [&](const BezierPatch3& patch) {
    std::vector<Vec3> all = evaluate_grid(patch, weights).normals;
    std::vector<Vec3> points(uvs.size()), samples(uvs.size()), rational(uvs.size());
    evaluate_samples(patch, uvs, {points, samples, {}});
    const RationalBezierPatch weighted(3, 3, patch.control_points(), varied_weights);
    evaluate_samples(weighted, uvs, {points, rational, {}});
    all.insert(all.end(), samples.begin(), samples.end());
    for (const Vec2& uv : uvs) all.push_back(unit_normal(patch, uv.x(), uv.y()));
    all.insert(all.end(), rational.begin(), rational.end());
    std::vector<Vec3> rational_grid(uvs.size());
    evaluate_grid(weighted, weights, {points, rational_grid, {}});
    all.insert(all.end(), rational_grid.begin(), rational_grid.end());
    for (const Vec2& uv : uvs) all.push_back(unit_normal(weighted, uv.x(), uv.y()));
    return all;
  };
  const auto split = [](const BezierPatch3& patch) { return subpatch(patch, 0.2, 0.9, 0.0, 0.7); };
  const std::vector<Vec3> expected = normals_of(net(Vec3::Zero()));
  const std::vector<Vec3> expected_split = normals_of(split(net(Vec3::Zero())));
  for (const Vec3& offset : {Vec3(1e3, 700, -300), Vec3(1e6, 7e5, -3e5), Vec3(1e9, 7e8, -3e8),
                             Vec3(0.0, 0.0, 1835008.0 + 7.0 * std::ldexp(1.0, -32))}) {
    const std::vector<Vec3> moved = normals_of(net(offset));
    const std::vector<Vec3> moved_split = normals_of(split(net(offset)));
    for (std::size_t k = 0; k < moved.size(); ++k) {
      SCOPED_TRACE(::testing::Message() << "offset " << offset.transpose() << ", normal " << k);
      EXPECT_LT((moved[k] - expected[k]).norm(), 1e-6);
      EXPECT_LT((moved_split[k] - expected_split[k]).norm(), 1e-6);
    }
  }
  // Weights 100 apart: the patch-wide bound grows with their ratio, but each point is judged by
  // its own derivatives, so the pole still has its limit normal (it threw "no normal" when the
  // higher orders were held to the patch-wide bound).
  std::vector<double> wide_weights;
  for (int k = 0; k < 16; ++k) wide_weights.push_back(1.0 + 33.0 * (k % 4));
  const auto wide_normals = [&](const BezierPatch3& patch) {
    const RationalBezierPatch weighted(3, 3, patch.control_points(), wide_weights);
    std::vector<Vec3> points(uvs.size()), all(uvs.size());
    evaluate_samples(weighted, uvs, {points, all, {}});
    for (const Vec2& uv : uvs) all.push_back(unit_normal(weighted, uv.x(), uv.y()));
    return all;
  };
  const std::vector<Vec3> expected_wide = wide_normals(net(Vec3::Zero()));
  // At 1e8 the net itself holds the normal to about w_max / w_min eps R = 2e-6 only.
  for (const Vec3& offset : {Vec3(1e3, 700, -300), Vec3(1e6, 7e5, -3e5), Vec3(0.0, 0.0, 1e6 + 0.1),
                             Vec3(1e8, 7e7, -3e7 + 0.1)}) {
    const std::vector<Vec3> moved = wide_normals(net(offset));
    for (std::size_t k = 0; k < moved.size(); ++k) {
      SCOPED_TRACE(::testing::Message() << "weights 1-100, offset " << offset.transpose() << ", normal " << k);
      EXPECT_LT((moved[k] - expected_wide[k]).norm(), offset.norm() > 1e7 ? 1e-4 : 1e-6);
    }
  }
}

TEST(PatchGrid, PointListGetsTheLimitNormalAndRefusesBadInput) {
  const BezierPatch3 patch = testing::product_patch({Vec3(1, 0, 1), Vec3(0.5, 0.5, 0), Vec3(0, 1, 1)},
                                                    {Vec3(0, 0, 0), Vec3(0.5, 0.5, 0), Vec3(1, 1, 1)});
  const std::vector<Vec2> uvs = {Vec2(0, 0), Vec2(0.25, 0), Vec2(1, 0), Vec2(0.5, 0.5)};
  std::vector<Vec3> points(uvs.size()), normals(uvs.size());
  evaluate_samples(patch, uvs, {points, normals, {}});
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_LT((normals[k] - Vec3(0, 0, -1)).norm(), 1e-12);
    EXPECT_LT(points[k].norm(), 1e-15);
  }
  EXPECT_LT((points[3] - patch.evaluate(0.5, 0.5)).norm(), 1e-15);
  std::vector<Vec3> short_points(2), short_normals(2);
  EXPECT_THROW(evaluate_samples(patch, uvs, {short_points, short_normals, {}}), InvalidInput);
  const std::vector<Vec2> bad = {Vec2(0.5, std::nan(""))};
  EXPECT_THROW(evaluate_samples(patch, bad, {points, normals, {}}), InvalidInput);
}

// The Bernstein values and derivatives of the point evaluators against the curves module's.
TEST(PatchGrid, BernsteinValuesAndDerivativesMatchTheCurvesModule) {
  for (int n = 0; n <= 7; ++n) {
    for (const double t : {0.0, 0.125, 1.0 / 3.0, 0.5, 0.9, 1.0}) {
      std::vector<double> values(static_cast<std::size_t>(n) + 1), derivatives(values.size());
      detail::bernstein_values_and_derivatives(n, t, values.data(), derivatives.data());
      const std::vector<double> expected = bernstein_all(n, t);
      const std::vector<double> expected_derivatives = bernstein_all_derivatives(n, t, 1);
      for (std::size_t i = 0; i < values.size(); ++i) {
        // The same recurrence and the same difference: the same bits.
        EXPECT_EQ(values[i], expected[i]) << "n " << n << " t " << t << " i " << i;
        EXPECT_EQ(derivatives[i], expected_derivatives[i]) << "n " << n << " t " << t << " i " << i;
      }
    }
  }
}

// Re-tabulating from the object's own lists (a new degree, the same parameters) is the weights
// of a fresh object, and a refused call leaves the weights as they were.
TEST(PatchGrid, WeightsReassignedFromTheirOwnLists) {
  const std::vector<double> us = {0.0, 0.25, 0.5, 1.0};
  const std::vector<double> vs = {0.0, 1.0 / 3.0, 1.0};
  PatchGridWeights weights(3, 2, us, vs);
  weights.assign(2, 3, weights.us(), weights.vs());
  const PatchGridWeights fresh(2, 3, us, vs);
  ASSERT_EQ(weights.degree_u(), 2);
  for (std::size_t k = 0; k < us.size(); ++k) {
    EXPECT_TRUE(std::equal(weights.u_values(k).begin(), weights.u_values(k).end(), fresh.u_values(k).begin()));
    EXPECT_TRUE(std::equal(weights.u_derivatives(k).begin(), weights.u_derivatives(k).end(), fresh.u_derivatives(k).begin()));
  }
  for (std::size_t k = 0; k < vs.size(); ++k) {
    EXPECT_TRUE(std::equal(weights.v_values(k).begin(), weights.v_values(k).end(), fresh.v_values(k).begin()));
  }
  const std::vector<double> bad = {0.5, std::nan("")};
  EXPECT_THROW(weights.assign(1, 1, bad, vs), InvalidInput);
  EXPECT_EQ(weights.degree_u(), 2);
  EXPECT_EQ(weights.us().size(), us.size());
}

TEST(PatchGrid, RejectsMismatchedDegrees) {
  const BezierPatch3 patch = testing::bilinear(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0));
  EXPECT_THROW(evaluate_grid(patch, PatchGridWeights::uniform(3, 3, 2, 2)), InvalidInput);
  EXPECT_THROW(PatchGridWeights::uniform(1, 1, 0, 2), InvalidInput);
}

// The row kernel of degrees 1-3 runs with AVX2 where the processor has it; it must give the
// portable kernel's bits (no fused multiply-adds, the same sums in the same order). On a machine
// without AVX2 both are the portable kernel.
RC_GTEST_PROP(PatchGrid, EveryInstructionSetGivesTheSameBits, ()) {
  const BezierPatch3 patch = *testing::random_patch(1, 3);
  const auto count_u = static_cast<std::size_t>(*rc::gen::inRange(1, 40));
  const auto count_v = static_cast<std::size_t>(*rc::gen::inRange(1, 4));
  const std::vector<double> us = random_parameters(count_u);
  const std::vector<double> vs = random_parameters(count_v);
  const PatchGridWeights weights(patch.degree_u(), patch.degree_v(), us, vs);
  std::vector<Vec3> points(count_u * count_v), normals(points.size());
  std::vector<Vec3> portable_points(points.size()), portable_normals(points.size());
  try {
    evaluate_grid(patch, weights, {points, normals, {}});
  } catch (const NumericalError&) {
    // No normal somewhere (a point or a curve): the portable kernel says so too.
    RC_ASSERT_THROWS_AS(detail::evaluate_grid_portable(patch, weights, {portable_points, portable_normals, {}}),
                        NumericalError);
    return;
  }
  detail::evaluate_grid_portable(patch, weights, {portable_points, portable_normals, {}});
  RC_ASSERT(points == portable_points);
  RC_ASSERT(normals == portable_normals);
  // Streaming stores write the same bits (rows go through scratch, then out).
  std::vector<Vec3> streamed_points(points.size()), streamed_normals(points.size());
  evaluate_grid(patch, weights, {streamed_points, streamed_normals, {}, true});
  RC_ASSERT(streamed_points == points);
  RC_ASSERT(streamed_normals == normals);
}

// evaluate_points (F alone at scattered points) gives evaluate_grid's points bit for bit (the
// same Bernstein values and sums; the grid has at least two columns, so the row kernel or the
// generic loop, never the column kernel, which sums in the other order), polynomial and
// rational, every degree from 0 to 5, with and without AVX2; and the pointwise patch to rounding.
RC_GTEST_PROP(PatchGrid, PointsAreTheGridsPointsBitForBit, ()) {
  const BezierPatch3 net = *testing::random_patch(0, 5);
  std::vector<double> weights;
  for (std::size_t k = 0; k < net.control_points().size(); ++k) weights.push_back(*testing::coordinate(0.2, 5.0));
  const RationalBezierPatch rational(net.degree_u(), net.degree_v(), net.control_points(), weights);
  const auto count_u = static_cast<std::size_t>(*rc::gen::inRange(2, 12));
  const auto count_v = static_cast<std::size_t>(*rc::gen::inRange(1, 5));
  const std::vector<double> grid_us = random_parameters(count_u);
  const std::vector<double> grid_vs = random_parameters(count_v);
  const PatchGridWeights grid(net.degree_u(), net.degree_v(), grid_us, grid_vs);
  // The grid's points in some order as scattered points (more than a chunk of the kernel).
  std::vector<double> us;
  std::vector<double> vs;
  std::vector<std::size_t> at;
  const auto repeats = static_cast<std::size_t>(*rc::gen::inRange(1, 12));
  for (std::size_t r = 0; r < repeats; ++r) {
    for (std::size_t k = 0; k < count_u * count_v; ++k) {
      const std::size_t s = (k * 7 + r) % (count_u * count_v);
      us.push_back(grid_us[s % count_u]);
      vs.push_back(grid_vs[s / count_u]);
      at.push_back(s);
    }
  }
  std::vector<Vec3> points(us.size());
  std::vector<Vec3> portable(us.size());
  for (const bool is_rational : {false, true}) {
    std::vector<Vec3> grid_points(count_u * count_v);
    std::vector<Vec3> grid_normals(grid_points.size());
    try {
      if (is_rational) {
        evaluate_grid(rational, grid, {grid_points, grid_normals, {}});
      } else {
        evaluate_grid(net, grid, {grid_points, grid_normals, {}});
      }
    } catch (const NumericalError&) {
      continue;  // no normal somewhere (a point or a curve): the grid says no, not the points
    }
    // The dispatched kernel or the portable one, of the polynomial or the rational patch.
    const auto evaluate = [&](bool portable_kernel, const std::vector<double>& at_u, const std::vector<double>& at_v,
                              std::vector<Vec3>& out) {
      if (portable_kernel && is_rational) detail::evaluate_points_portable(rational.homogeneous(), at_u, at_v, out);
      if (portable_kernel && !is_rational) detail::evaluate_points_portable(net, at_u, at_v, out);
      if (!portable_kernel && is_rational) evaluate_points(rational, at_u, at_v, out);
      if (!portable_kernel && !is_rational) evaluate_points(net, at_u, at_v, out);
    };
    evaluate(false, us, vs, points);
    evaluate(true, us, vs, portable);
    RC_ASSERT(points == portable);
    for (std::size_t k = 0; k < points.size(); ++k) {
      RC_ASSERT(points[k] == grid_points[at[k]]);
      const Vec3 pointwise = is_rational ? rational.evaluate(us[k], vs[k]) : net.evaluate(us[k], vs[k]);
      RC_ASSERT((points[k] - pointwise).norm() <=
                1e-13 * (testing::net_scale(net) + 1e-300) * (is_rational ? 25.0 : 1.0));
    }
    // Each grid row on its own, its u repeated: every v the same, so the kernel's row loop (the
    // net contracted in v once) runs; the same bits again.
    for (std::size_t b = 0; b < count_v; ++b) {
      std::vector<double> row_us;
      for (std::size_t r = 0; r < repeats; ++r) row_us.insert(row_us.end(), grid_us.begin(), grid_us.end());
      const std::vector<double> row_vs(row_us.size(), grid_vs[b]);
      std::vector<Vec3> row(row_us.size());
      std::vector<Vec3> row_portable(row_us.size());
      evaluate(false, row_us, row_vs, row);
      evaluate(true, row_us, row_vs, row_portable);
      RC_ASSERT(row == row_portable);
      for (std::size_t k = 0; k < row.size(); ++k) RC_ASSERT(row[k] == grid_points[k % count_u + count_u * b]);
    }
  }
  std::vector<Vec3> too_few(us.size() - 1);
  RC_ASSERT_THROWS_AS(evaluate_points(net, us, vs, too_few), InvalidInput);
  RC_ASSERT_THROWS_AS(evaluate_points(net, us, std::span<const double>(vs).first(vs.size() - 1), points), InvalidInput);
}

// A row on a collapsed edge has no F_u x F_v: its normals are the limit normals, redone after
// the row kernel. With streaming stores they are redone in the row's scratch before the row
// goes out, and must arrive the same.
TEST(PatchGrid, StreamedRowsKeepTheLimitNormalsOfACollapsedEdge) {
  std::vector<Vec3> net;  // a bicubic cone: row v = 0 is one point
  for (int j = 0; j <= 3; ++j) {
    for (int i = 0; i <= 3; ++i) {
      const double r = j / 3.0;
      const double angle = i * 0.5;
      net.emplace_back(r * std::cos(angle), r * std::sin(angle), 1.0 - r * r);
    }
  }
  const BezierPatch3 patch(3, 3, net);
  const PatchGridWeights weights = PatchGridWeights::uniform(3, 3, 40, 5);
  std::vector<Vec3> points(41 * 6), normals(points.size()), streamed_points(points.size()),
      streamed_normals(points.size());
  evaluate_grid(patch, weights, {points, normals, {}});
  evaluate_grid(patch, weights, {streamed_points, streamed_normals, {}, true});
  EXPECT_EQ(streamed_points, points);
  EXPECT_EQ(streamed_normals, normals);
  // The first row is the pole, every normal there the limit normal.
  for (std::size_t a = 0; a <= 40; ++a) EXPECT_EQ(normals[a], unit_normal(patch, weights.us()[a], 0.0)) << a;
}

TEST(PatchGrid, WritesIntoCallerStorageOrRefusesTooLittle) {
  // A biquadratic bump over the unit square: x = u, y = v, z = 4 u (1 - u) v (1 - v).
  std::vector<Vec3> net;
  for (int j = 0; j <= 2; ++j) {
    for (int i = 0; i <= 2; ++i) net.emplace_back(0.5 * i, 0.5 * j, i == 1 && j == 1 ? 1.0 : 0.0);
  }
  const BezierPatch3 patch(2, 2, std::move(net));
  const PatchGridWeights weights = PatchGridWeights::uniform(2, 2, 5, 3);
  const PatchGridSamples samples = evaluate_grid(patch, weights, true);
  std::vector<Vec3> points(24), normals(24);
  std::vector<Vec4> tangents(24);
  evaluate_grid(patch, weights, {points, normals, tangents});
  EXPECT_EQ(points, samples.points);
  EXPECT_EQ(normals, samples.normals);
  EXPECT_EQ(tangents, samples.tangents);
  std::vector<Vec3> short_normals(23);
  EXPECT_THROW(evaluate_grid(patch, weights, {points, short_normals, {}}), InvalidInput);
  std::vector<Vec4> short_tangents(1);
  EXPECT_THROW(evaluate_grid(patch, weights, {points, normals, short_tangents}), InvalidInput);
}

}  // namespace
}  // namespace patchwork
