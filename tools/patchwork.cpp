// The patchwork command-line tool. Each subcommand prints one line and exits 1 on bad input.

#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>
#include <string>

#include "tools/curve_demo.h"
#include "tools/info_command.h"
#include "tools/patches_command.h"

int main(int argc, char** argv) {
  CLI::App app{"patchwork: Bezier curves, patches and meshes"};
  app.require_subcommand(1);

  int degree = 20;
  long evaluations = 2'000'000;
  CLI::App* demo = app.add_subcommand("curve-demo", "Accuracy and speed of the curves module");
  demo->add_option("--degree", degree, "Degree of the hard-case polynomial")->check(CLI::Range(2, 33));
  demo->add_option("--evaluations", evaluations, "Evaluations timed per method")->check(CLI::Range(1000L, 1'000'000'000L));

  std::string patch_file;
  bool json = false;
  CLI::App* patches = app.add_subcommand("patches", "Adjacency, continuity and area of a BPT patch set");
  patches->add_option("file", patch_file, "BPT file (e.g. data/teapot.bpt)")->required();
  patches->add_flag("--json", json, "Print the report as JSON");

  std::string mesh_file;
  bool info_json = false;
  CLI::App* info = app.add_subcommand("info", "Topology of a mesh file (OBJ, OFF, PLY)");
  info->add_option("file", mesh_file, "Mesh file")->required();
  info->add_flag("--json", info_json, "Print the report as JSON");

  CLI11_PARSE(app, argc, argv);
  try {
    if (demo->parsed()) patchwork::tools::run_curve_demo(std::cout, degree, evaluations);
    if (patches->parsed()) patchwork::tools::run_patches_report(std::cout, patch_file, json);
    if (info->parsed()) patchwork::tools::run_info(std::cout, mesh_file, info_json);
  } catch (const std::exception& error) {
    std::cerr << "patchwork: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
