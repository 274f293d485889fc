#include "report/hard_cases.h"

#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <span>
#include <sstream>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "curves/bernstein.h"
#include "curves/bezier_curve.h"
#include "curves/compensated.h"
#include "io/atomic_file.h"
#include "surfaces/bezier_patch.h"
#include "surfaces/patch_grid.h"
#include "tests/support/exact_rational.h"

namespace patchwork::performance {
namespace {

constexpr double kUnitRoundoff = 0x1p-53;
// The patch: degree 2 in v with z factors d_j, measured on the row v = 3/8 (1 - v exact).
constexpr int kPatchDegreeV = 2;
constexpr double kPatchV = 0.375;
constexpr std::array<double, 3> kPatchFactors = {1.0, 2.0, 1.0};
// Drawn at this height in the plot where the error is 0 (log scale); the y axis ends at 1.
constexpr double kPlotFloor = 1e-18;
// The condition number below which the compensated errors are summarised in the text.
constexpr double kModerateCondition = 1e15;
// (2s-1)^3(s-1) is swept at kHalfSweepUlps * 2^k ulps of 1/2 (u = 2^-53) on either side of 1/2.
constexpr int kHalfSweepUlps = 1001;
// The offset added to every Bernstein coefficient of the well-conditioned polynomial.
constexpr double kOffset = 1e8;

constexpr std::array<HardCaseEvaluator, kHardCaseEvaluatorCount> kEvaluators = {
    HardCaseEvaluator::de_casteljau, HardCaseEvaluator::compensated,        HardCaseEvaluator::batch_table,
    HardCaseEvaluator::horner,       HardCaseEvaluator::patch_de_casteljau, HardCaseEvaluator::patch_grid};

std::size_t index(HardCaseEvaluator evaluator) { return static_cast<std::size_t>(evaluator); }

// Each evaluator's file-name key and Markdown title, in enum order.
struct EvaluatorNames {
  const char* key;
  const char* title;
};
constexpr std::array<EvaluatorNames, kHardCaseEvaluatorCount> kEvaluatorNames = {
    {{"de_casteljau", "de Casteljau"},
     {"compensated", "compensated"},
     {"batch_table", "batch (table)"},
     {"horner", "Horner (power)"},
     {"patch_de_casteljau", "patch de Casteljau"},
     {"patch_grid", "patch grid"}}};

const char* evaluator_title(HardCaseEvaluator evaluator) { return kEvaluatorNames[index(evaluator)].title; }

// A polynomial, its parameters, and how they were chosen (Markdown).
struct CaseSpec {
  std::string name;
  std::string key;
  std::string parameters;
  std::vector<double> c;
  std::vector<double> s;
};

std::vector<mpq_class> roots_with(const std::vector<std::pair<mpq_class, int>>& roots_and_multiplicities) {
  std::vector<mpq_class> roots;
  for (const auto& [root, multiplicity] : roots_and_multiplicities) roots.insert(roots.end(), multiplicity, root);
  return roots;
}

// (k + 1/2) / count, k = 0..count-1: uniform, never on a dyadic root.
std::vector<double> midpoints(int count) {
  std::vector<double> s;
  for (int k = 0; k < count; ++k) s.push_back((k + 0.5) / count);
  return s;
}

std::string format_number(double x) {
  if (x == 0) return "0";
  if (std::isinf(x)) return "inf";
  char buffer[32];
  const double magnitude = std::abs(x);
  if (magnitude >= 1e4 || magnitude < 1e-2) {
    std::snprintf(buffer, sizeof buffer, "%.1e", x);
    std::string text(buffer);  // 3.2e+15 -> 3.2e15, 1.0e-05 -> 1.0e-5
    const std::size_t e = text.find('e');
    std::string exponent = text.substr(e + 1);
    const bool negative = exponent[0] == '-';
    exponent.erase(0, 1);
    exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
    return text.substr(0, e) + "e" + (negative ? "-" : "") + exponent;
  }
  std::snprintf(buffer, sizeof buffer, magnitude >= 100 ? "%.0f" : "%.3g", x);
  return buffer;
}

// The published hard cases (see hard_case_rows); `step` thins the parameter lists.
std::vector<CaseSpec> case_specs(bool quick) {
  const int step = quick ? 6 : 1;
  const int count = quick ? 40 : 400;
  std::vector<CaseSpec> specs;

  {
    CaseSpec spec{"(s-1)(s-3/4)^7", "seventh_power", "", {}, {}};
    spec.c = exact::scaled_bernstein_from_roots(roots_with({{mpq_class(3, 4), 7}, {mpq_class(1), 1}}));
    const int first = 5;
    const int last = 90;
    for (int j = first; j <= last; j += step) spec.s.push_back(0.75 - std::pow(1.3, -j));
    spec.parameters = "s = 3/4 - 1.3^-j, j = " + std::to_string(first) + ".." + std::to_string(last) +
                      (quick ? " step " + std::to_string(step) : "");
    specs.push_back(std::move(spec));
  }
  {
    CaseSpec spec{"(2s-1)^3(s-1)", "cubic_half", "", {}, {}};
    spec.c = exact::scaled_bernstein_from_roots(roots_with({{mpq_class(1, 2), 3}, {mpq_class(1), 1}}));
    const int ulps = kHalfSweepUlps;
    const int last = 42;  // 1001 * 2^42 u < 1/2
    for (int k = 0; k <= last; k += step) {
      const double d = std::ldexp(static_cast<double>(ulps), k - 53);
      spec.s.push_back(0.5 - d);
      spec.s.push_back(0.5 + d);
    }
    spec.parameters = "s = 1/2 ± " + std::to_string(ulps) + "·2^k u, k = 0.." + std::to_string(last) +
                      (quick ? " step " + std::to_string(step) : "");
    specs.push_back(std::move(spec));
  }
  const std::string uniform = "s = (k+1/2)/" + std::to_string(count) + ", k = 0.." + std::to_string(count - 1);
  {
    std::vector<mpq_class> roots;
    for (int j = 1; j <= 20; ++j) roots.emplace_back(j, 20);
    specs.push_back({"prod_{j=1..20} (s - j/20)", "twentieths", uniform, exact::scaled_bernstein_from_roots(roots),
                     midpoints(count)});
  }
  {
    std::vector<mpq_class> roots;
    mpq_class root(1);
    for (int j = 1; j <= 20; ++j, root /= 2) roots.push_back(root);
    std::vector<double> s;
    const int lowest = -21;  // below the smallest root 2^-19
    for (int k = 0; k < count; ++k) s.push_back(std::exp2(lowest * (k + 0.5) / count));
    specs.push_back({"prod_{j=1..20} (s - 2/2^j)", "halvings",
                     "s = 2^(" + std::to_string(lowest) + "(k+1/2)/" + std::to_string(count) + "), k = 0.." +
                         std::to_string(count - 1),
                     exact::scaled_bernstein_from_roots(roots), std::move(s)});
  }
  {
    std::vector<mpq_class> roots;
    for (int j = 1; j <= 40; ++j) roots.emplace_back(j, 41);
    specs.push_back({"prod_{j=1..40} (s - j/41)", "degree40", uniform, exact::scaled_bernstein_from_roots(roots),
                     midpoints(count)});
  }
  {
    const double offset = kOffset;
    const int n = 20;
    std::vector<double> c;
    for (int i = 0; i <= n; ++i) c.push_back(offset + std::cos(i));
    specs.push_back({"c_i = " + format_number(offset) + " + cos i, n = " + std::to_string(n), "offset", uniform,
                     std::move(c), midpoints(count)});
  }
  return specs;
}

// |computed - exact| / |exact| and / ulp(exact), rounded from the exact quotients.
void record_error(HardCasePoint& point, HardCaseEvaluator evaluator, const mpq_class& error, const mpq_class& exact) {
  point.relative_error[index(evaluator)] = exact::nearest_double(error / abs(exact));
  point.ulps[index(evaluator)] = exact::in_ulps(error, exact);
}

void record(HardCasePoint& point, HardCaseEvaluator evaluator, double computed, const mpq_class& exact) {
  record_error(point, evaluator, abs(mpq_class(computed) - exact), exact);
}

HardCaseRow measure(const CaseSpec& spec) {
  const int n = static_cast<int>(spec.c.size()) - 1;
  HardCaseRow row{spec.name, spec.key, n, {}};

  std::vector<Point<1>> curve_points;
  for (double c : spec.c) curve_points.push_back(Point<1>(c));
  const BezierCurve<1> curve(curve_points);
  const std::vector<double> power = exact::power_coefficients(spec.c);
  const std::vector<Point<1>> batch = evaluate(curve, BernsteinTable(n, spec.s));

  std::vector<Vec3> net;
  for (int j = 0; j <= kPatchDegreeV; ++j) {
    for (int i = 0; i <= n; ++i) {
      net.emplace_back(static_cast<double>(i) / n, static_cast<double>(j) / kPatchDegreeV,
                       spec.c[static_cast<std::size_t>(i)] * kPatchFactors[static_cast<std::size_t>(j)]);
    }
  }
  const BezierPatch3 patch(n, kPatchDegreeV, net);
  const std::vector<double> vs = {kPatchV};
  const PatchGridSamples grid = evaluate_grid(patch, PatchGridWeights(n, kPatchDegreeV, spec.s, vs));
  const mpq_class q = exact::evaluate(exact::rationals(kPatchFactors), mpq_class(kPatchV));

  for (std::size_t k = 0; k < spec.s.size(); ++k) {
    const double s = spec.s[k];
    const exact::EvaluationErrors e = exact::measure_errors(spec.c, s);
    if (e.exact == 0) continue;
    HardCasePoint point{};
    point.s = s;
    point.condition = exact::nearest_double(e.magnitude / abs(e.exact));
    const bool exact_complement = mpq_class(1.0 - s) == 1 - mpq_class(s);
    for (HardCaseEvaluator evaluator : kEvaluators) {
      point.bound[index(evaluator)] = hard_case_bound(evaluator, n, point.condition, exact_complement);
    }
    record_error(point, HardCaseEvaluator::de_casteljau, e.plain, e.exact);
    record_error(point, HardCaseEvaluator::compensated, e.compensated, e.exact);
    record(point, HardCaseEvaluator::batch_table, batch[k][0], e.exact);
    record(point, HardCaseEvaluator::horner, exact::horner(power, s), e.exact);
    const mpq_class patch_exact = e.exact * q;
    record(point, HardCaseEvaluator::patch_de_casteljau, patch.evaluate(s, kPatchV).z(), patch_exact);
    record(point, HardCaseEvaluator::patch_grid, grid.points[k].z(), patch_exact);
    row.points.push_back(point);
  }
  return row;
}

std::string data_file_name(const HardCaseRow& row, HardCaseEvaluator evaluator) {
  return "hard_cases_" + row.key + "_" + evaluator_key(evaluator) + ".dat";
}

void write_data_files(const std::filesystem::path& data_dir, const std::vector<HardCaseRow>& rows) {
  std::error_code error;
  std::filesystem::create_directories(data_dir, error);
  if (error) throw IoError(data_dir.string(), "hard_case_section: cannot create the folder: " + error.message());
  for (const HardCaseRow& row : rows) {
    for (HardCaseEvaluator evaluator : kEvaluators) {
      std::string text =
          "# " + row.name + ", " + evaluator_title(evaluator) + ": cond, relative error (clamped at 1), ulps\n";
      for (const HardCasePoint& point : row.points) {
        char line[96];
        const std::size_t e = index(evaluator);
        std::snprintf(line, sizeof line, "%.6e %.6e %.6e\n", point.condition, std::min(point.relative_error[e], 1.0),
                      point.ulps[e]);
        text += line;
      }
      write_file_atomically(data_dir / data_file_name(row, evaluator), text);
    }
  }
}

// Per evaluator: the largest of `value` over the points of `row` that pass `keep`.
template <class Value, class Keep>
double largest(const HardCaseRow& row, Value value, Keep keep) {
  double result = 0.0;
  for (const HardCasePoint& point : row.points) {
    if (keep(point)) result = std::max(result, value(point));
  }
  return result;
}

// The smallest condition number at which `evaluator` has no correct digit, over all rows (inf if never).
double first_lost(const std::vector<HardCaseRow>& rows, HardCaseEvaluator evaluator) {
  double result = std::numeric_limits<double>::infinity();
  for (const HardCaseRow& row : rows) {
    for (const HardCasePoint& point : row.points) {
      if (point.relative_error[index(evaluator)] >= 1.0) result = std::min(result, point.condition);
    }
  }
  return result;
}

std::string markdown(const std::vector<HardCaseRow>& rows, const std::vector<CaseSpec>& specs) {
  const auto all = [](const HardCasePoint&) { return true; };
  const auto ulps_of = [](HardCaseEvaluator evaluator) {
    return [e = index(evaluator)](const HardCasePoint& p) { return p.ulps[e]; };
  };
  const auto condition_of = [](const HardCasePoint& p) { return p.condition; };
  const auto row_with_key = [&rows](const std::string& key) -> const HardCaseRow& {
    for (const HardCaseRow& row : rows) {
      if (row.key == key) return row;
    }
    throw InvalidInput("hard_case_section: no case " + key);
  };

  std::ostringstream out;
  out << "## 6. Hard cases: accuracy against exact arithmetic\n\n";
  out << "| case | parameters | n | points |";
  for (HardCaseEvaluator evaluator : kEvaluators) out << " " << evaluator_title(evaluator) << " |";
  out << " max cond |\n|---|---|---:|---:|";
  for (std::size_t e = 0; e < kHardCaseEvaluatorCount; ++e) out << "---:|";
  out << "---:|\n";
  std::size_t total = 0;
  std::size_t violations = 0;
  double max_condition = 0.0;
  int max_degree = 0;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const HardCaseRow& row = rows[r];
    total += row.points.size();
    max_degree = std::max(max_degree, row.degree);
    out << "| `" << row.name << "` | " << specs[r].parameters << " | " << row.degree << " | " << row.points.size()
        << " |";
    for (HardCaseEvaluator evaluator : kEvaluators)
      out << " " << format_number(largest(row, ulps_of(evaluator), all)) << " |";
    const double row_condition = largest(row, condition_of, all);
    max_condition = std::max(max_condition, row_condition);
    out << " " << format_number(row_condition) << " |\n";
    for (const HardCasePoint& point : row.points) {
      for (std::size_t e = 0; e < kHardCaseEvaluatorCount; ++e) violations += point.relative_error[e] > point.bound[e];
    }
  }

  // The figures quoted in the paragraph.
  double compensated_moderate = 0.0;
  for (const HardCaseRow& row : rows) {
    compensated_moderate = std::max(compensated_moderate,
                                    largest(row, ulps_of(HardCaseEvaluator::compensated),
                                            [](const HardCasePoint& p) { return p.condition < kModerateCondition; }));
  }
  const HardCaseRow& high_degree = row_with_key("degree40");
  const HardCaseRow& offset = row_with_key("offset");
  double offset_worst = 0.0;
  for (HardCaseEvaluator evaluator : kEvaluators)
    offset_worst = std::max(offset_worst, largest(offset, ulps_of(evaluator), all));

  out << "\nMaximum error in ulps of the exact value (|computed - p(s)| / ulp(p(s))) per case and evaluator, over "
      << total << " parameters; cond(p, s) = p~(s)/|p(s)| with p~ = sum |c_i| B_i^n. The exact value is that of the "
      << "double coefficients at the double s, in GMP rationals; each product of roots is scaled so that its "
      << "Bernstein coefficients are exact in double where " << std::numeric_limits<double>::digits
      << " bits suffice (the condition number does not change). `(2s-1)^3(s-1)` is swept at " << kHalfSweepUlps
      << "·2^k ulps of 1/2 on either side of its triple root, from s = 1/2 ± " << kHalfSweepUlps
      << "u on. Horner runs on the power-basis coefficients of the same polynomial rounded to double; the patch "
      << "evaluators on a patch of degrees (n, " << kPatchDegreeV << ") whose z coordinate is p(u)(1 + 2v - 2v^2), "
      << "measured at v = " << format_number(kPatchV) << ". "
      << (violations == 0 ? std::string("Every measured error of the Bernstein-basis evaluators lies within its "
                                        "a-priori bound")
                          : std::to_string(violations) + " measured errors exceed their a-priori bound")
      << " (de Casteljau γ_{2n}·cond, compensated u + 2γ_{3n+2}²·cond, table, patch and grid paths the same with a "
      << "few more roundings in γ). Below cond " << format_number(kModerateCondition)
      << " the compensated result is off by at most " << format_number(compensated_moderate)
      << " ulps. The smallest condition numbers at which a result has no correct digit left are "
      << format_number(first_lost(rows, HardCaseEvaluator::compensated)) << " for the compensated evaluator and "
      << format_number(first_lost(rows, HardCaseEvaluator::de_casteljau)) << " for plain de Casteljau; Horner fails "
      << "already at " << format_number(first_lost(rows, HardCaseEvaluator::horner))
      << " (its error scales with sum |a_j| s^j of the power coefficients, not with p~). On the degree-"
      << high_degree.degree << " product Horner is off by up to "
      << format_number(largest(high_degree, ulps_of(HardCaseEvaluator::horner), all))
      << " ulps, de Casteljau by at most "
      << format_number(largest(high_degree, ulps_of(HardCaseEvaluator::de_casteljau), all)) << " at cond up to "
      << format_number(largest(high_degree, condition_of, all)) << ", compensated by at most "
      << format_number(largest(high_degree, ulps_of(HardCaseEvaluator::compensated), all)) << ". The offset of "
      << format_number(kOffset) << " is harmless to every evaluator (at most " << format_number(offset_worst)
      << " ulps): the coefficients share one sign, so cond is at most "
      << format_number(largest(offset, condition_of, all))
      << ". In the plot relative errors are clamped at 1 (no correct digit left) and errors of 0 are drawn at "
      << format_number(kPlotFloor) << "; the dashed line is u·cond (the rule of thumb for de Casteljau), the solid "
      << "ones de Casteljau's a-priori bound γ_{2n}·cond and the compensated bound u + 2γ_{3n}²·cond, both for the "
      << "largest degree, n = " << max_degree << ". Largest condition number measured: " << format_number(max_condition)
      << ".\n\n";
  out << "![Relative error against condition number on the hard cases](performance/hard_cases.png)\n";
  return out.str();
}

std::string gnuplot(const std::vector<HardCaseRow>& rows) {
  double max_condition = 1.0;
  int max_degree = 0;
  for (const HardCaseRow& row : rows) {
    max_degree = std::max(max_degree, row.degree);
    for (const HardCasePoint& point : row.points) max_condition = std::max(max_condition, point.condition);
  }
  static const std::array<const char*, kHardCaseEvaluatorCount> colors = {"#1f77b4", "#d62728", "#2ca02c",
                                                                          "#7f7f7f", "#9467bd", "#ff7f0e"};
  static const std::array<int, kHardCaseEvaluatorCount> point_types = {6, 7, 1, 2, 4, 3};
  std::ostringstream out;
  out << "set terminal pngcairo size 900,600 enhanced font ',10'\n"
      << "set encoding utf8\n"
      << "set output 'hard_cases.png'\n"
      << "set logscale xy\n"
      << "set format x '10^{%L}'\nset format y '10^{%L}'\n"
      << "set xrange [1:" << format_number(std::pow(10.0, std::ceil(std::log10(max_condition)))) << "]\n"
      << "set yrange [" << format_number(kPlotFloor / 10) << ":10]\n"
      << "set xlabel 'cond(p, s) = sum |c_i| B_i^n(s) / |p(s)|' noenhanced\n"
      << "set ylabel 'relative error |computed - p(s)| / |p(s)|, clamped at 1' noenhanced\n"
      << "set key bottom right box opaque\n"
      << "set grid\n"
      << "set samples 500\n"
      << "u = 2.0**-53\nn = " << max_degree << "\n"
      << "g(k) = k*u / (1 - k*u)\n"
      << "plot";
  // Horner first and compensated last, so that the Bernstein-basis series are not buried.
  constexpr std::array<HardCaseEvaluator, kHardCaseEvaluatorCount> drawing_order = {
      HardCaseEvaluator::horner,      HardCaseEvaluator::patch_grid,   HardCaseEvaluator::patch_de_casteljau,
      HardCaseEvaluator::batch_table, HardCaseEvaluator::de_casteljau, HardCaseEvaluator::compensated};
  const char* separator = " ";
  for (HardCaseEvaluator evaluator : drawing_order) {
    const std::size_t e = index(evaluator);
    for (std::size_t r = 0; r < rows.size(); ++r) {
      out << separator << "'" << data_file_name(rows[r], evaluator)
          << "' using 1:($2 > 0 ? $2 : " << format_number(kPlotFloor) << ") with points pt " << point_types[e]
          << " ps 0.6 lc rgb '" << colors[e] << "' "
          << (r == 0 ? std::string("title '") + evaluator_title(evaluator) + "'" : std::string("notitle"));
      separator = ", \\\n     ";
    }
  }
  out << separator << "u*x with lines lw 2 dt 2 lc rgb 'black' title 'u·cond'" << separator
      << "g(2*n)*x with lines lw 2 lc rgb '#1f77b4' title 'γ_{2n}·cond, n = " << max_degree << "'" << separator
      << "u + 2*g(3*n)**2*x with lines lw 2 lc rgb '#d62728' title 'u + 2γ_{3n}^2·cond, n = " << max_degree << "'";
  out << "\n";
  return out.str();
}

}  // namespace

const char* evaluator_key(HardCaseEvaluator evaluator) { return kEvaluatorNames[index(evaluator)].key; }

double hard_case_bound(HardCaseEvaluator evaluator, int n, double condition, bool exact_complement) {
  // Per level of a Bernstein recursion: a product and a sum round, and 1 - s unless it is exact.
  const int per_level = exact_complement ? 2 : 3;
  const int m = kPatchDegreeV;
  switch (evaluator) {
    case HardCaseEvaluator::de_casteljau:
      return gamma_constant(per_level * n) * condition;
    case HardCaseEvaluator::compensated: {
      const double g = gamma_constant(3 * n + 2);
      return kUnitRoundoff + 2 * g * g * condition;
    }
    case HardCaseEvaluator::batch_table:
      return gamma_constant(per_level * n + n + 1) * condition;
    case HardCaseEvaluator::horner:
      return std::numeric_limits<double>::infinity();
    case HardCaseEvaluator::patch_de_casteljau:
      return gamma_constant(per_level * n + 2 * m) * condition;
    case HardCaseEvaluator::patch_grid:
      return gamma_constant(per_level * n + n + 3 * m + 2) * condition;
  }
  return 0.0;
}

std::vector<HardCaseRow> hard_case_rows(bool quick) {
  std::vector<HardCaseRow> rows;
  for (const CaseSpec& spec : case_specs(quick)) rows.push_back(measure(spec));
  return rows;
}

ReportSection hard_case_section(const std::filesystem::path& data_dir, bool quick) {
  const std::vector<CaseSpec> specs = case_specs(quick);
  std::vector<HardCaseRow> rows;
  for (const CaseSpec& spec : specs) rows.push_back(measure(spec));
  write_data_files(data_dir, rows);
  return {markdown(rows, specs), gnuplot(rows)};
}

}  // namespace patchwork::performance
