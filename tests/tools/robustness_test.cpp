// Every bad input we know of, fed to the command line as a user would: each must end with exit
// code 1, one line on stderr that names the file and the problem, and no output file (a file
// that was there before stays as it was). The table of inputs and answers is docs/robustness.md;
// this test writes it (PATCHWORK_UPDATE_DOCS=1) or fails when the committed one differs, so the
// document always shows what the program answers now.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/temporary_directory.h"

namespace patchwork {
namespace {

namespace fs = std::filesystem;

struct BadInput {
  std::string group;
  std::string what;
  /// A file to create first (empty name: none), and its bytes.
  std::string file;
  std::string bytes;
  /// The arguments, run in the test's folder (so messages show relative names).
  std::string arguments;
  /// The file the answer names first; empty: the command's input (the word after the command).
  std::string names = {};
};

// The file an answer must name: the row's own, or the first argument after the command.
std::string named_file(const BadInput& bad) {
  if (!bad.names.empty()) return bad.names;
  std::istringstream words(bad.arguments);
  std::string command, input;
  words >> command >> input;
  return input;
}

std::vector<std::string> sorted_entries(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

using testing::slurp;

std::string repeat(const std::string& s, int n) {
  std::string out;
  for (int k = 0; k < n; ++k) out += s;
  return out;
}

const std::string cube_obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                             "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
const std::string patch_header = "1\n3 3\n";
std::string patch_points(int count) {
  std::string out;
  // A curved patch: z = i j mod 3 over the 4 x 4 net.
  for (int k = 0; k < count; ++k) {
    out += std::to_string(k % 4) + " " + std::to_string(k / 4) + " " + std::to_string((k % 4) * (k / 4) % 3) + "\n";
  }
  return out;
}
const std::string ply_header_binary = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                                      "property float y\nproperty float z\nelement face 1\n"
                                      "property list uchar int vertex_indices\nend_header\n";

// A glTF document whose one buffer is the file `uri`.
std::string gltf_buffer_uri(const std::string& uri) {
  return R"({"asset": {"version": "2.0"}, "buffers": [{"uri": ")" + uri + R"(", "byteLength": 36}]})";
}

// A glTF document of one triangle, (0, 0, 0) (1, 0, 0) (0, 1, 0) in a data: URI, held by `nodes`
// (node 0 the root of scene 0).
std::string gltf_triangle(const std::string& nodes) {
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": )" + nodes +
         R"(, "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],)"
         R"( "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],)"
         R"( "bufferViews": [{"buffer": 0, "byteLength": 36}],)"
         R"( "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,)"
         R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]})";
}

std::vector<BadInput> bad_inputs() {
  const std::string bpt = patch_header + patch_points(16);
  return {
      // --- readers
      {"BPT", "missing file", "", "", "info missing.bpt"},
      {"BPT", "empty file", "empty.bpt", "", "info empty.bpt"},
      {"BPT", "a directory", "", "", "info folder.bpt"},
      {"BPT", "truncated: 16 points announced, 3 given", "short.bpt", patch_header + patch_points(3), "info short.bpt"},
      {"BPT", "patch count 2, one patch given", "count.bpt", "2\n3 3\n" + patch_points(16), "info count.bpt"},
      {"BPT", "degree 100 (limit 64)", "degree.bpt", "1\n100 3\n" + patch_points(4), "info degree.bpt"},
      {"BPT", "negative degree", "negative.bpt", "1\n-1 3\n", "info negative.bpt"},
      {"BPT", "10^12 patches announced (nothing allocated first)", "huge.bpt",
       "1000000000000\n3 3\n" + patch_points(16), "info huge.bpt"},
      {"BPT", "NaN coordinate", "nan.bpt", patch_header + "nan 0 0\n" + patch_points(15), "info nan.bpt"},
      {"BPT", "infinite coordinate", "inf.bpt", patch_header + "inf 0 0\n" + patch_points(15), "info inf.bpt"},
      {"BPT", "a word for a number", "word.bpt", patch_header + "one 0 0\n" + patch_points(15), "info word.bpt"},
      {"BPT", "binary garbage", "garbage.bpt", std::string("\x7f\x45\x4c\x46\x02\x01\x00\xff\xfe", 9),
       "info garbage.bpt"},
      {"BPT", "all 16 control points equal (no surface)", "point.bpt", patch_header + repeat("1 1 1\n", 16),
       "tessellate point.bpt -o out.glb --relative-tolerance 0.001"},
      {"OBJ", "empty file", "empty.obj", "", "subdivide empty.obj -o out.obj"},
      {"OBJ", "face index 9 of 8 vertices", "range.obj", cube_obj + "f 1 2 9\n", "info range.obj"},
      {"OBJ", "face index 0 (OBJ counts from 1)", "zero.obj", cube_obj + "f 0 1 2\n", "info zero.obj"},
      {"OBJ", "relative index before the first vertex", "relative.obj", "v 0 0 0\nf -1 -2 -3\n", "info relative.obj"},
      {"OBJ", "face with two corners", "two.obj", cube_obj + "f 1 2\n", "info two.obj"},
      {"OBJ", "NaN vertex", "nan.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "info nan.obj"},
      {"OBJ", "non-UTF-8 bytes in a keyword", "latin1.obj", "v 0 0 0\n\xe9\xe8 1 2 3\n", "info latin1.obj"},
      {"OBJ free-form", "a knot vector that decreases", "knots.obj",
       "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\ncstype bspline\ndeg 1 1\nsurf 0 1 0 1 1 2 3 4\nparm u 0 1 0 1\n"
       "parm v 0 0 1 1\nend\n",
       "info knots.obj"},
      {"OBJ free-form", "a trimming curve (trim), which is not honoured", "trim.obj",
       "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\ncstype bspline\ndeg 1 1\nsurf 0 1 0 1 1 2 3 4\nparm u 0 0 1 1\n"
       "parm v 0 0 1 1\ntrim 0 1 1\nend\n",
       "tessellate trim.obj -o out.glb"},
      {"OBJ free-form", "a surface's range outside its knots", "range.obj",
       "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\ncstype bspline\ndeg 1 1\nsurf 0 2 0 1 1 2 3 4\nparm u 0 0 1 1\n"
       "parm v 0 0 1 1\nend\n",
       "convert range.obj out.bpt"},
      {"OBJ", "self-intersecting face (a bow-tie) converted to glTF", "bowtie.obj",
       "v 0 0 0\nv 2 2 0\nv 2 0 0\nv 0 1 0\nf 1 2 3 4\n", "convert bowtie.obj out.glb"},
      {"OFF", "wrong magic", "magic.off", "OF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "info magic.off"},
      {"OFF", "10^12 faces announced", "huge.off", "OFF\n3 1000000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
       "info huge.off"},
      {"OFF", "truncated vertex list", "short.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n", "info short.off"},
      {"OFF", "negative index", "negative.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 -2\n", "info negative.off"},
      {"OFF", "repeated vertex in a face", "repeat.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 1\n",
       "subdivide repeat.off -o out.obj"},
      {"PLY", "binary, data cut short", "short.ply", ply_header_binary + std::string(10, '\0'), "info short.ply"},
      {"PLY", "binary, face index out of range", "range.ply",
       ply_header_binary + std::string(36, '\0') +
           std::string("\x03\x00\x00\x00\x00\x01\x00\x00\x00\x07\x00\x00\x00", 13),
       "info range.ply"},
      {"PLY", "unknown format", "format.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n", "info format.ply"},
      {"PLY", "no end_header", "header.ply", "ply\nformat ascii 1.0\nelement vertex 1\n", "info header.ply"},
      {"glTF", "not glTF at all", "garbage.glb", std::string("glTF\x02\x00\x00\x00\xff\xff", 10),
       "convert garbage.glb out.obj"},
      {"glTF", "JSON that is not glTF", "empty.gltf", "{}", "convert empty.gltf out.obj"},
      {"glTF", "buffer URI going up out of the file's folder", "up.gltf", gltf_buffer_uri("../secret/data.bin"),
       "convert up.gltf out.obj"},
      {"glTF", "buffer URI going up, percent-encoded", "encoded.gltf", gltf_buffer_uri("%2e%2e/secret/data.bin"),
       "convert encoded.gltf out.obj"},
      {"glTF", "buffer URI an absolute path", "absolute.gltf", gltf_buffer_uri("/etc/passwd"),
       "convert absolute.gltf out.obj"},
      {"glTF", "node hierarchy with a cycle", "cycle.gltf",
       gltf_triangle(R"([{"mesh": 0, "children": [1]}, {"name": "loop", "children": [0]}])"), "convert cycle.gltf out.obj"},
      {"glTF", "node scale with a zero (a singular transform)", "flat.gltf",
       gltf_triangle(R"([{"mesh": 0, "scale": [1, 0, 1]}])"), "convert flat.gltf out.obj"},
      // --- geometry and options
      {"mesh", "non-manifold edge (three faces) as a subdivision cage", "book.obj",
       "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n", "subdivide book.obj -o out.obj"},
      {"mesh", "the limit surface of a Moebius band (not orientable)", "band.obj",
       "v 0.5 0 0\nv 0 0.646 -0.354\nv 0 1.354 0.354\nv 1.5 0 0\nv -1 0 -0.5\nv -1 0 0.5\nv 0 -1.354 -0.354\n"
       "v 0 -0.646 0.354\nf 1 2 3 4\nf 2 5 6 3\nf 5 7 8 6\nf 7 4 1 8\n",
       "subdivide band.obj -o out.glb --limit"},
      {"mesh", "quads for Loop subdivision", "cube.obj", cube_obj, "subdivide cube.obj -o out.obj --scheme loop"},
      {"mesh", "11 subdivision levels", "cube.obj", cube_obj, "subdivide cube.obj -o out.obj --levels 11"},
      {"tessellate", "tolerance 0", "patch.bpt", bpt, "tessellate patch.bpt -o out.glb --tolerance 0"},
      {"tessellate", "negative tolerance", "patch.bpt", bpt, "tessellate patch.bpt -o out.glb --tolerance -1"},
      {"tessellate", "NaN tolerance", "patch.bpt", bpt, "tessellate patch.bpt -o out.glb --tolerance nan"},
      {"tessellate", "a tolerance that needs more triangles than the limit", "patch.bpt", bpt,
       "tessellate patch.bpt -o out.glb --tolerance 1e-12"},
      {"tessellate", "more triangles than --max-triangles", "patch.bpt", bpt,
       "tessellate patch.bpt -o out.glb --relative-tolerance 1e-5 --max-triangles 1000"},
      {"tessellate", "0 segments", "patch.bpt", bpt, "tessellate patch.bpt -o out.glb --segments 0"},
      {"tessellate", "camera looking at itself", "patch.bpt", bpt,
       "tessellate patch.bpt -o out.glb --camera eye=0,0,0 target=0,0,0 fov=40 width=10 height=10"},
      // --- output
      {"output", "unknown output extension", "patch.bpt", bpt, "tessellate patch.bpt -o out.stl --segments 2"},
      {"output", "output folder does not exist", "patch.bpt", bpt,
       "tessellate patch.bpt -o no/such/out.glb --segments 2", "no/such/out.glb"},
      {"output", "output is a directory", "patch.bpt", bpt, "tessellate patch.bpt -o folder.glb --segments 2",
       "folder.glb"},
  };
}

std::string markdown_cell(std::string text) {
  while (!text.empty() && text.back() == '\n') text.pop_back();
  std::string out;
  for (char c : text) {
    if (c == '|') {
      out += "\\|";
    } else if (c == '\n') {
      out += "<br>";
    } else {
      out += c;
    }
  }
  return out;
}

TEST(Robustness, EveryBadInputGetsOneLineExitOneAndNoFile) {
  std::ostringstream table;
  table << "# Robustness: every bad input tried, and what patchwork answers\n\n"
        << "Written by `tests/tools/robustness_test.cpp` (`PATCHWORK_UPDATE_DOCS=1` rewrites it; the test fails\n"
        << "when this file differs from what the program answers). Each row runs the `patchwork` command\n"
        << "line in a fresh folder. Every answer is exit code 1 with this one line on stderr, naming the\n"
        << "file first (the input, or the output the write failed for), and no file is left: `out.*` does\n"
        << "not exist afterwards, no temporary of the atomic writer either (the folder holds what it held\n"
        << "before), and a `keep.glb` written before is unchanged.\n"
        << "The fuzzing of the same readers is in [fuzzing](#fuzzing) below.\n\n"
        << "| input | what is wrong | command | answer |\n|---|---|---|---|\n";
  for (const BadInput& bad : bad_inputs()) {
    const testing::TemporaryDirectory folder("patchwork_robustness");
    if (!bad.file.empty()) std::ofstream(folder.path() / bad.file, std::ios::binary) << bad.bytes;
    fs::create_directory(folder.path() / "folder.bpt");
    fs::create_directory(folder.path() / "folder.glb");
    std::ofstream(folder.path() / "keep.glb", std::ios::binary) << "previous contents";
    std::ofstream(folder.path() / "stdout.txt");
    std::ofstream(folder.path() / "stderr.txt");
    const std::vector<std::string> before = sorted_entries(folder.path());
    const std::string command = "cd '" + folder.path().string() + "' && '" PATCHWORK_CLI "' " + bad.arguments +
                                " > stdout.txt 2> stderr.txt";
    const int status = std::system(command.c_str());
    const int exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    const std::string err = slurp(folder.path() / "stderr.txt");
    EXPECT_EQ(exit_code, 1) << bad.arguments << "\n" << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << bad.arguments << "\n" << err;
    // The line names the file first, as "patchwork: FILE: ..." or "patchwork: FILE:LINE:COLUMN: ...".
    EXPECT_EQ(err.rfind("patchwork: " + named_file(bad) + ":", 0), 0u) << bad.arguments << "\n" << err;
    // Once: a library error the CLI names must not name the file again.
    const std::string after = err.substr(std::string("patchwork: ").size() + named_file(bad).size() + 1);
    EXPECT_EQ(after.find(" " + named_file(bad) + ":"), std::string::npos) << "the file is named twice: " << err;
    EXPECT_FALSE(fs::exists(folder.path() / "out.glb") || fs::exists(folder.path() / "out.obj")) << bad.arguments;
    EXPECT_EQ(slurp(folder.path() / "keep.glb"), "previous contents");
    // Nothing is left behind: not the output, not the atomic writer's temporary (a hidden
    // ".NAME.XXXXXX" beside the output, io/atomic_file.cpp), nothing else.
    EXPECT_EQ(sorted_entries(folder.path()), before) << bad.arguments;
    table << "| " << bad.group << " | " << markdown_cell(bad.what) << " | `patchwork " << bad.arguments << "` | "
          << markdown_cell(err) << (exit_code == 1 ? "" : " (exit " + std::to_string(exit_code) + ")") << " |\n";
  }
  const fs::path document = fs::path(PATCHWORK_SOURCE_DIR) / "docs" / "robustness.md";
  const std::string text = slurp(document);
  const std::string marker = "\n## Fuzzing";
  const std::string rest = text.find(marker) == std::string::npos ? "" : text.substr(text.find(marker));
  const std::string expected = table.str() + rest;
  if (std::getenv("PATCHWORK_UPDATE_DOCS") != nullptr) {
    std::ofstream(document, std::ios::binary) << expected;
  } else {
    EXPECT_EQ(text, expected) << "docs/robustness.md is out of date: run this test with PATCHWORK_UPDATE_DOCS=1";
  }
}

}  // namespace
}  // namespace patchwork
