#pragma once
// The hard-case accuracy section of docs/performance.md: the curve and patch evaluators measured
// against exact rational arithmetic (GMP) on the ill-conditioned polynomials of the
// compensated-evaluation literature (Graillat, Langlois & Louvet 2009; Jiang, Li, Cheng & Wang
// 2010; Delgado & Pena 2009).
//
//   p(s)    = sum_i c_i B_i^n(s),  p~(s) = sum_i |c_i| B_i^n(s),  cond(p, s) = p~(s) / |p(s)|
//   relative error = |computed - p(s)| / |p(s)|,  ulps = |computed - p(s)| / ulp(p(s))
//
// The doubles c_i are the polynomial under test: the exact value is that of the doubles at the
// double s. The patch evaluators run on the 3D patch P_ij = (i/n, j/2, c_i d_j), d = (1, 2, 1),
// at v = 3/8, whose z coordinate is p(u) q(v) with q = 1 + 2v - 2v^2 > 0 (so its condition
// number is that of p at u); z is what is measured.

#include <array>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "report/report_section.h"

namespace patchwork::performance {

/// The evaluators compared, in table order.
enum class HardCaseEvaluator {
  de_casteljau,        ///< BezierCurve<1>::evaluate
  compensated,         ///< evaluate_compensated
  batch_table,         ///< evaluate(curve, BernsteinTable): weights tabulated once, then dot products
  horner,              ///< Horner's rule on the power-basis coefficients, rounded to double
  patch_de_casteljau,  ///< BezierPatch3::evaluate, tensor de Casteljau
  patch_grid,          ///< evaluate_grid with PatchGridWeights
};

/// Number of HardCaseEvaluator values.
inline constexpr std::size_t kHardCaseEvaluatorCount = 6;

/// Short name of an evaluator, used in file names and the plot ("de_casteljau", ...).
const char* evaluator_key(HardCaseEvaluator evaluator);

/// One parameter of one case, measured by every evaluator.
struct HardCasePoint {
  double s;          ///< the parameter (u for the patch evaluators)
  double condition;  ///< cond(p, s), rounded from the exact quotient
  /// Per evaluator: |computed - p(s)| / |p(s)|, not clamped (rounded from the exact quotient).
  std::array<double, kHardCaseEvaluatorCount> relative_error;
  /// Per evaluator: |computed - p(s)| / ulp(p(s)).
  std::array<double, kHardCaseEvaluatorCount> ulps;
  /// Per evaluator: the a-priori bound on the relative error (Horner: none, +infinity). See
  /// hard_case_bound.
  std::array<double, kHardCaseEvaluatorCount> bound;
};

/// One polynomial and its parameters.
struct HardCaseRow {
  std::string name;                   ///< Markdown label, e.g. "(s-1)(s-3/4)^7"
  std::string key;                    ///< file-name stem, e.g. "seventh_power"
  int degree;                         ///< n
  std::vector<HardCasePoint> points;  ///< parameters where p(s) != 0
};

/// The relative a-priori bound of `evaluator` for degree n at condition number `condition`,
/// with `exact_complement` saying whether 1 - s is exact in double (else it rounds once more per
/// level), u = 2^-53, gamma_k = k u / (1 - k u), v = 3/8 (1 - v exact) and m = 2 for the patch:
///   de Casteljau        gamma_{2n} cond           (gamma_{3n} if 1 - s rounds)
///   compensated         u + 2 gamma_{3n+2}^2 cond
///   batch table         gamma_{3n+1} cond         (gamma_{4n+1}): weights gamma_{2n}, sum gamma_{n+1}
///   patch de Casteljau  gamma_{2n+2m} cond        (gamma_{3n+2m})
///   patch grid          gamma_{3n+3m+2} cond      (gamma_{4n+3m+2})
///   Horner              none (+infinity): its error scales with sum |a_j| s^j, not p~.
double hard_case_bound(HardCaseEvaluator evaluator, int n, double condition, bool exact_complement);

/// Every case measured; `quick` takes about a tenth of the parameters.
std::vector<HardCaseRow> hard_case_rows(bool quick);

/// The hard-case accuracy section: a table of the maximum error in ulps per case and evaluator,
/// a paragraph, and the plot of relative error against condition number with the bounds drawn
/// in; writes one data file per case and evaluator (hard_cases_CASE_EVALUATOR.dat, columns cond,
/// relative error clamped at 1, ulps) into data_dir. \throws IoError if a file cannot be written.
ReportSection hard_case_section(const std::filesystem::path& data_dir, bool quick);

}  // namespace patchwork::performance
