#include "report/queries_crosscheck_document.h"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <thread>
#include <utility>

#include "report/format.h"
#include "report/occt_peer.h"

namespace patchwork::crosscheck {

double median(std::vector<double> x) {
  if (x.empty()) return 0.0;
  std::sort(x.begin(), x.end());
  const std::size_t h = x.size() / 2;
  return x.size() % 2 == 1 ? x[h] : 0.5 * (x[h - 1] + x[h]);
}

double slowest(const std::vector<double>& x) { return x.empty() ? 0.0 : *std::max_element(x.begin(), x.end()); }

double total(const std::vector<double>& x) {
  double s = 0;
  for (const double v : x) s += v;
  return s;
}

// The note on OCCT without culling: its median time and patchwork's speed ratio against it.
std::string unculled_note(const Row& row) {
  if (row.occt_unculled_seconds.empty()) return "";
  double ours = 0, theirs = 0;
  for (const double x : row.patchwork_seconds) ours += x;
  for (const double x : row.occt_unculled_seconds) theirs += x;
  std::string note = "OCCT on every patch without box culling: median " +
                     performance::text("%.3g", median(row.occt_unculled_seconds) * 1e6) + " us, speed ratio " +
                     performance::text("%.2f", theirs / ours) + ". ";
  if (row.culling_changed > 0) note += std::to_string(row.culling_changed) + " answers changed by culling! ";
  return note;
}

// A row with no answers yet.
Row new_row(std::string query, std::string family, std::size_t cases) {
  Row row;
  row.query = std::move(query), row.family = std::move(family), row.cases = static_cast<int>(cases);
  return row;
}

namespace {

// ---------------------------------------------------------------------------------------------
// The document

std::string machine() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line, model = "unknown CPU";
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  }
  return model + ", " + std::to_string(std::thread::hardware_concurrency()) + " hardware threads";
}

std::string tally_cell(const Tally& t, bool twice) {
  std::string cell = std::to_string(t.right) + " / " + std::to_string(t.wrong) + " / " + std::to_string(t.missed);
  if (twice) cell += " / " + std::to_string(t.twice);
  return cell;
}

std::string microseconds(double seconds) { return performance::text("%.3g", seconds * 1e6); }



// How every number of the table is made: the truths, the matching, the timing.
std::string definitions(const Sizes& sizes) {
  std::ostringstream out;
  out << "## How the table is made\n\n"
      << "Everything comes from `report/queries_cases.h` (the cases and truths, no Open CASCADE: `queries_cases.cpp` for\n"
      << "points and curves against surfaces, `queries_pair_cases.cpp` for planar curve pairs; tested by\n"
      << "`tests/report/queries_cases_test.cpp`), `report/queries_crosscheck.cpp` (both libraries) and\n"
      << "`report/queries_crosscheck_document.cpp` (the table).\n"
      << "The size below is the diagonal of the box of the control points: teapot "
      << performance::text("%.4g", sizes.teapot) << ", sphere " << performance::text("%.4g", sizes.sphere) << ".\n\n"
      << "**Closest point.** patchwork: `closest_point(bvh, q)`, the `PatchBvh` built once. OCCT: one\n"
      << "`GeomAPI_ProjectPointOnSurf` per patch (the teapot's 32 `Geom_BezierSurface`s; the sphere as one\n"
      << "`Geom_BSplineSurface`, the same NURBS surface), `Init`ed once with the surface and its bounds\n"
      << "outside the timing, then `Perform(q)` patch by patch, nearest control-point box first, skipping\n"
      << "patches whose box is no nearer than the best distance so far (the box holds the patch, so this\n"
      << "loses nothing), and the least `LowerDistance` kept. The notes give OCCT's time without that\n"
      << "culling (every patch projected), measured in the same run.\n\n"
      << "- Truth, sphere: `||q - c| - r|` in closed form, c = (1/4, -1/2, 1/8), r = 3/2 (the NURBS sphere's\n"
      << "  weights are rounded doubles: it is that sphere to about 1e-16).\n"
      << "- Truth, teapot: the least of (a) every sample of a 48 x 48 grid on every patch, (b) local Newton\n"
      << "  (`newton_foot`, queries/patch_evaluation.h) from both libraries' feet, (c) the same Newton from the\n"
      << "  nearest sample of every patch whose nearest sample, less the patch's reach (n max |P_(i+1)j - P_ij|\n"
      << "  plus the same along v, times half a grid step: no point of the patch is farther than that from a\n"
      << "  sample), is below the best so far. (a) and (c) use neither library's answer. The truth is a\n"
      << "  distance some surface point attains; it misses the exact minimum only if that lies in a basin\n"
      << "  that neither library, nor Newton from the nearest sample of its patch, reaches.\n"
      << "- Right: the reported distance is within 1e-9 x size of the truth (so not above it by more; no\n"
      << "  answer was below it by more), the point at the reported parameters (OCCT: `S(U, V)` by OCCT;\n"
      << "  patchwork: `F(u, v)`) is within 1e-9 x size of the reported point (OCCT's issue #345), and for\n"
      << "  patchwork the certified lower bound is at most the truth (+ 1e-9 x size). Wrong: an answer that\n"
      << "  fails one of these. Missed: no answer (OCCT: no extremum on any patch).\n\n"
      << "**Curve x surface.** patchwork: `intersect_curve_surface(curve, set)` (the sphere: its 8 rational\n"
      << "patches). OCCT: `GeomAPI_IntCS(Geom_BezierCurve, surface)` on every patch whose control-point box\n"
      << "meets the curve's (the notes give the time without that culling); hits of different patches\n"
      << "within 1e-7 in t are merged by this program (a hit on a shared edge, found by both patches: a\n"
      << "B-rep caller would merge them too); hits of one surface are not merged. Curves run over t in [0, 1].\n\n"
      << "- Truth, sphere: the real roots in [0, 1] of `|C(t) - c|^2 - r^2`, exactly (Sturm sequences in GMP\n"
      << "  rationals; the control points are doubles, so rationals), each isolated to 2^-60. Tangent lines:\n"
      << "  one contact at t = 1/2 plus the exact roots farther than 1e-4 from it. The first 12 touch at the\n"
      << "  poles and at the patch corners on the equator and are exactly tangent (dyadic numbers); the\n"
      << "  others are tangent to rounding (the exact line misses or cuts by about 1e-16, roots within\n"
      << "  about 1e-8 of 1/2), counted as one contact.\n"
      << "- Truth, teapot: no closed form. The answers of either library that lie within 1e-7 x size of both\n"
      << "  curve and patch and from which Newton on F(u, v) = C(t) reaches a root (residual 1e-12 x size)\n"
      << "  within 1e-4 in t; the contact of a tangent line (built at a convex point, K > 0.01, along a\n"
      << "  principal direction); and a dense check: the curve's polyline (1 piece for lines, 32 for cubics)\n"
      << "  against the triangles of the 48 x 48 grid of every patch, Newton from every crossing, a root\n"
      << "  found this way joins the truth (a hit both missed). Crossings no Newton confirms far from every\n"
      << "  true hit are counted in the notes. A hit that both libraries and the mesh miss is not in the truth.\n"
      << "- Matching: every answer goes to the nearest true t within 1e-4; the first is right, further ones\n"
      << "  are reported twice, answers with no true t that near are wrong; true hits no answer reached are\n"
      << "  missed.\n\n"
      << "**2D curve x curve.** patchwork: `intersect_curves` (Bezier or rational Bezier). OCCT:\n"
      << "`Geom2dAPI_InterCurveCurve` on two `Geom2d_BezierCurve`s with its default tolerance 1e-6, points and\n"
      << "segments from its `Intersector()`. Control points are multiples of 1/64 and weights 1/2 to 2 in\n"
      << "steps of 1/4, so the inputs are exact rationals.\n\n"
      << "- Truth: the resultant R(s) = Res_t(X_A(t) w_B(s) - X_B(s) w_A(t), Y_A(t) w_B(s) - Y_B(s) w_A(t)) in\n"
      << "  GMP rationals (Sylvester determinants at 2 n_A n_B + 1 integers s, interpolated exactly), its\n"
      << "  distinct real roots in [0, 1] isolated by Sturm sequences to 2^-60, the multiplicity of each from\n"
      << "  repeated gcds. For each root s the partner t is found in floating point (the least |A(t) - B(s)|\n"
      << "  over [-1/4, 5/4], sampling then Gauss-Newton); the root is a true point if that distance is below\n"
      << "  4e-9 and t lies in [0, 1] (a t within 1e-9 of 0 or 1 is decided exactly: A(end) = B(s) in\n"
      << "  rationals). So the count in s is exact; the t of each point and its being inside [0, 1] are\n"
      << "  decided in floating point away from the ends. R = 0 identically: the curves overlap (the\n"
      << "  overlap's interval is known from the construction).\n"
      << "- Cases: random cubic pairs in [0, 1]^2 (polynomial, and rational); tangent: a cubic and a\n"
      << "  parabola touching a line, a cubic touching its mirror image (multiplicity 2); inflection: a cubic\n"
      << "  against its inflection tangent, and y = (2t - 1)^3 against y = c (2s - 1)^3 (multiplicity 3);\n"
      << "  near-parallel: lines at angles 2^-10 to 2^-34, and a cubic against itself lifted by\n"
      << "  e (3t - 3/2) (crossing at an angle of about 3e); overlapping: a cubic (x increasing, so without a\n"
      << "  loop) against its middle half, forward or reversed, or two pieces sharing [3/8, 5/8] of it; end\n"
      << "  points: end to end, and an end on the other's middle. The hard cases are turned by 90 degrees and\n"
      << "  moved (exactly).\n"
      << "- Matching: a point answer goes to the nearest true point within 1e-4 in t and in s; an interval\n"
      << "  answer (patchwork's overlap, OCCT's segment: where the curves are within its tolerance) matches a\n"
      << "  true point inside it. Against an overlap, an interval whose ends are within 1e-4 of the\n"
      << "  overlap's is right, further such intervals are reported twice, points and other intervals are\n"
      << "  wrong, and without such an interval the overlap is missed.\n\n"
      << "**Time.** `steady_clock` around each call (a point, a curve against the whole surface, a pair);\n"
      << "patchwork and OCCT alternate case by case in one process, one thread, Release (-O3). The machine is\n"
      << "shared with other builds: times and ratios move by some 20% between runs. The speed ratio is\n"
      << "OCCT's total time over patchwork's for the family (patchwork's queries per second over OCCT's); a\n"
      << "family with one slow case (see the slowest column) has its ratio set by that case.\n\n"
      << "**Limits.** The teapot's truths are not proofs: for closest points a minimum in a basin that no\n"
      << "start reaches would be missed by the truth too; for curves a hit that both libraries and the\n"
      << "48 x 48 mesh miss (two hits closer than the mesh resolves, a tangent contact the mesh does not\n"
      << "cross) is not in the truth, so there \"right\" means agreement with verified hits. In the plane the\n"
      << "count of roots in s is exact, but each root's t comes from floating point (roots whose t lies\n"
      << "within 1e-9 of 0 or 1 are decided exactly or reported as undecided in the notes). The matching\n"
      << "tolerance of 1e-4 in the parameters is generous (tangent contacts are known to about 1e-8,\n"
      << "inflection contacts to about 1e-5); the error column shows how close the right answers came.\n"
      << "OCCT answers within its tolerance (1e-6 for planar curves): its points along near-parallel lines\n"
      << "lie within that tolerance of both curves but are not crossings, so they count as wrong, while its\n"
      << "segments count as right when they contain the true point. Random tangent lines to the sphere are\n"
      << "tangent only to rounding and count as one contact by definition.\n";
  return out.str();
}

}  // namespace

std::string document(const std::vector<Row>& rows, const std::string& commit, int count, double run_seconds,
                     const Sizes& sizes) {
  std::ostringstream out;
  out << "# Modeling queries: patchwork against Open CASCADE\n\n"
      << "Written by `scripts/crosscheck-queries` (report/queries_crosscheck.cpp) in one run: the same cases\n"
      << "through patchwork's queries and through Open CASCADE " << performance::occt_version()
      << ", each answer judged against an independent truth\n(definitions below the table). Machine: " << machine()
      << "; one thread, Release build; commit " << commit << "; " << count
      << " random cases per random family; the run took " << performance::text("%.0f", run_seconds) << " s.\n\n"
      << "Columns: right / wrong / missed (and / reported twice for intersections) per library; the time is the\n"
      << "median of one query (one point, one curve against the whole surface, one pair), measured side by side; the\n"
      << "ratio is patchwork's queries per second over OCCT's, from the total times of the family. The error is the\n"
      << "largest of a right answer (distance for closest points, parameter for intersections).\n\n"
      << "| query | family | cases | true answers | patchwork | OCCT | patchwork us | OCCT us | speed ratio | slowest "
         "ms patchwork / OCCT | max error patchwork / OCCT |\n"
      << "|---|---|---:|---:|---|---|---:|---:|---:|---|---|\n";
  for (const Row& row : rows) {
    const bool twice = row.query != "closest point";
    const double ours = total(row.patchwork_seconds), theirs = total(row.occt_seconds);
    out << "| " << row.query << " | " << row.family << " | " << row.cases << " | " << row.truths << " | "
        << tally_cell(row.patchwork, twice) << " | " << tally_cell(row.occt, twice) << " | "
        << microseconds(median(row.patchwork_seconds)) << " | " << microseconds(median(row.occt_seconds)) << " | "
        << performance::text("%.2f", ours > 0 ? theirs / ours : 0.0) << " | "
        << performance::text("%.3g", slowest(row.patchwork_seconds) * 1e3) << " / "
        << performance::text("%.3g", slowest(row.occt_seconds) * 1e3) << " | "
        << performance::text("%.1e", row.patchwork.max_error) << " / " << performance::text("%.1e", row.occt.max_error)
        << " |\n";
  }
  out << "\nNotes per row (rows without notes left out):\n\n";
  for (const Row& row : rows) {
    if (!row.notes.empty()) out << "- " << row.query << ", " << row.family << ": " << row.notes << "\n";
  }
  out << "\n" << definitions(sizes);
  return out.str();
}

}  // namespace patchwork::crosscheck
