#pragma once
// The queries cross-check's table (docs/queries-crosscheck.md): its rows, filled by
// report/queries_crosscheck.cpp (both libraries), and the Markdown document made of them. No
// Open CASCADE here. Internal to report/.

#include <string>
#include <vector>

#include "report/queries_cases.h"

namespace patchwork::crosscheck {

// One row of the table: a query kind on a family, both libraries.
struct Row {
  std::string query;
  std::string family;
  int cases = 0;
  int truths = 0;  // true answers (for closest points: cases)
  Tally patchwork;
  Tally occt;
  std::vector<double> patchwork_seconds;
  std::vector<double> occt_seconds;
  // OCCT on every patch, without the box culling (where there is more than one surface).
  std::vector<double> occt_unculled_seconds;
  // Cases where the culled and unculled OCCT answers differ (they may not: the boxes hold the patches).
  int culling_changed = 0;
  std::string notes;
};

// The sizes tolerances are relative to: the diagonals of the control points' boxes.
struct Sizes {
  double teapot;
  double sphere;
};

/// The median of `x` (0 for none).
double median(std::vector<double> x);
/// The largest of `x` (0 for none).
double slowest(const std::vector<double>& x);
/// The sum of `x`.
double total(const std::vector<double>& x);
/// The note on OCCT without culling: its median time and patchwork's speed ratio against it.
std::string unculled_note(const Row& row);
/// A row with no answers yet.
Row new_row(std::string query, std::string family, std::size_t cases);
/// The document: the table of `rows` and how it is made, for a run of `count` cases a random
/// family at `commit` that took `run_seconds`.
std::string document(const std::vector<Row>& rows, const std::string& commit, int count, double run_seconds,
                     const Sizes& sizes);

}  // namespace patchwork::crosscheck
