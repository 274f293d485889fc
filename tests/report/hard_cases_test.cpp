// The hard-case section of the report: the measured errors obey the theory they are plotted
// against, and the section's files are what its gnuplot commands read.

#include "report/hard_cases.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "curves/compensated.h"
#include "tests/support/temporary_directory.h"

namespace patchwork {
namespace {

using performance::HardCaseEvaluator;
using performance::HardCasePoint;
using performance::HardCaseRow;

std::size_t at(HardCaseEvaluator evaluator) { return static_cast<std::size_t>(evaluator); }

const std::vector<HardCaseRow>& quick_rows() {
  static const std::vector<HardCaseRow> rows = performance::hard_case_rows(true);
  return rows;
}

const HardCaseRow& row_with_key(const std::string& key) {
  for (const HardCaseRow& row : quick_rows()) {
    if (row.key == key) return row;
  }
  ADD_FAILURE() << "no case " << key;
  return quick_rows().front();
}

TEST(HardCaseSection, EveryCaseHasPointsOverAWideRangeOfConditionNumbers) {
  ASSERT_EQ(quick_rows().size(), 6u);
  double largest = 0.0;
  for (const HardCaseRow& row : quick_rows()) {
    EXPECT_GE(row.points.size(), 8u) << row.key;
    for (const HardCasePoint& p : row.points) {
      EXPECT_GE(p.condition, 1.0) << row.key;  // p~ >= |p|
      largest = std::max(largest, p.condition);
    }
  }
  EXPECT_GT(largest, 1e30);  // the range
}

TEST(HardCaseSection, BernsteinEvaluatorsStayWithinTheirAPrioriBounds) {
  // The two bounds the issue names, stated here independently: plain de Casteljau gamma_{2n} cond
  // where 1 - s is exact (s in [1/2, 1], Sterbenz), gamma_{3n} cond anywhere; compensated
  // u + 2 gamma_{3n+2}^2 cond (Jiang et al. 2010). The tabulated paths against hard_case_bound.
  std::size_t checked = 0;
  for (const HardCaseRow& row : quick_rows()) {
    const int n = row.degree;
    const double g = gamma_constant(3 * n + 2);
    for (const HardCasePoint& p : row.points) {
      const double plain_bound = gamma_constant(p.s >= 0.5 ? 2 * n : 3 * n) * p.condition;
      EXPECT_LE(p.relative_error[at(HardCaseEvaluator::de_casteljau)], plain_bound) << row.key << " s=" << p.s;
      EXPECT_LE(p.relative_error[at(HardCaseEvaluator::compensated)], 0x1p-53 + 2 * g * g * p.condition)
          << row.key << " s=" << p.s;
      for (HardCaseEvaluator e :
           {HardCaseEvaluator::de_casteljau, HardCaseEvaluator::compensated, HardCaseEvaluator::batch_table,
            HardCaseEvaluator::patch_de_casteljau, HardCaseEvaluator::patch_grid}) {
        EXPECT_LE(p.relative_error[at(e)], p.bound[at(e)])
            << row.key << " s=" << p.s << " " << performance::evaluator_key(e);
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 150u);
}

TEST(HardCaseSection, CompensatedIsWithinTwoUlpsWhileTheTheoremSaysSo) {
  // |res - p| <= u|p| + 2 gamma^2 p~ and u|p| < ulp(p): below 2 ulps wherever 2 gamma^2 cond <= u.
  std::size_t checked = 0;
  for (const HardCaseRow& row : quick_rows()) {
    const double g = gamma_constant(3 * row.degree + 2);
    const double limit = 0x1p-53 / (2 * g * g);
    for (const HardCasePoint& p : row.points) {
      if (p.condition > limit) continue;
      EXPECT_LT(p.ulps[at(HardCaseEvaluator::compensated)], 2.0) << row.key << " s=" << p.s << " cond=" << p.condition;
      ++checked;
    }
  }
  EXPECT_GT(checked, 100u);
}

TEST(HardCaseSection, CompensatedBeatsPlainWhereConditioningIsModerate) {
  // Between cond 1e8 and 1e15 plain de Casteljau loses about log10(cond) digits; compensated none.
  std::size_t compared = 0;
  for (const HardCaseRow& row : quick_rows()) {
    for (const HardCasePoint& p : row.points) {
      if (p.condition < 1e8 || p.condition > 1e15) continue;
      const double plain = p.relative_error[at(HardCaseEvaluator::de_casteljau)];
      const double compensated = p.relative_error[at(HardCaseEvaluator::compensated)];
      EXPECT_LE(compensated, plain) << row.key << " s=" << p.s;
      ++compared;
    }
  }
  EXPECT_GT(compared, 10u);
}

TEST(HardCaseSection, HornerIsFarWorseThanDeCasteljauAtDegreeForty) {
  const HardCaseRow& row = row_with_key("degree40");
  ASSERT_EQ(row.degree, 40);
  double horner = 0.0;
  double plain = 0.0;
  for (const HardCasePoint& p : row.points) {
    horner = std::max(horner, p.ulps[at(HardCaseEvaluator::horner)]);
    plain = std::max(plain, p.ulps[at(HardCaseEvaluator::de_casteljau)]);
  }
  EXPECT_GT(horner, 1e6 * plain) << "horner " << horner << " ulps, de Casteljau " << plain;
}

TEST(HardCaseSection, OffsetCoefficientsAreEvaluatedFaithfully) {
  // Every c_i = 1e8 + cos i > 0: cond = 1, and the compensated result is faithful (< 1 ulp).
  for (const HardCasePoint& p : row_with_key("offset").points) {
    EXPECT_DOUBLE_EQ(p.condition, 1.0);
    EXPECT_LT(p.ulps[at(HardCaseEvaluator::compensated)], 1.0) << "s=" << p.s;
  }
}

TEST(HardCaseSection, WritesOneDataFilePerCaseAndEvaluatorAndATable) {
  testing::TemporaryDirectory folder("hard_cases");
  const performance::ReportSection section = performance::hard_case_section(folder.path(), true);
  for (const HardCaseRow& row : quick_rows()) {
    for (std::size_t e = 0; e < performance::kHardCaseEvaluatorCount; ++e) {
      const auto evaluator = static_cast<HardCaseEvaluator>(e);
      const std::string name = "hard_cases_" + row.key + "_" + performance::evaluator_key(evaluator) + ".dat";
      std::ifstream in(folder.path() / name);
      ASSERT_TRUE(in) << name;
      std::size_t rows = 0;
      std::string line;
      while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        double condition = 0;
        double relative = 0;
        double ulps = 0;
        ASSERT_EQ(std::sscanf(line.c_str(), "%lf %lf %lf", &condition, &relative, &ulps), 3) << name << ": " << line;
        EXPECT_LE(relative, 1.0) << name;  // clamped
        ++rows;
      }
      EXPECT_EQ(rows, row.points.size()) << name;
      EXPECT_NE(section.gnuplot.find("'" + name + "'"), std::string::npos) << name;
    }
    EXPECT_NE(section.markdown.find("`" + row.name + "`"), std::string::npos) << row.name;
  }
  EXPECT_EQ(section.markdown.rfind("## 6. Hard cases: accuracy against exact arithmetic\n", 0), 0u);
  EXPECT_NE(section.markdown.find("](performance/hard_cases.png)"), std::string::npos);
  EXPECT_NE(section.gnuplot.find("set output 'hard_cases.png'"), std::string::npos);
  EXPECT_NE(section.gnuplot.find("pngcairo size 900,600"), std::string::npos);
}

}  // namespace
}  // namespace patchwork
