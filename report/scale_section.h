#pragma once
// Section 9 of docs/performance.md: scale and the per-frame path.
//
// Scale: scenes of 1, 16, 256 and 1,024 rotated teapots (bench/make_scene, bench/scene.h: copies
// that never touch, so a scene of c copies is c times the work of one) tessellated by the CLI as
// a user runs it, whole process (`patchwork tessellate SCENE.bpt -o SCENE.glb --tolerance T
// --no-measure --threads 2`, T = 10^-3 of one teapot's diagonal), its wall time and peak memory
// read by GNU time; once more with the meter on, for the tessellation's and the measurement's
// times (the CLI's JSON). Linear cost shows as time and memory per triangle that do not grow
// with the scene; the plot draws both against the patch count in log-log with a line of slope 1.
//
// The per-frame path: the benchmarks of bench/tessellator_bench.cpp, run by this report: the
// teapot at one relative tolerance through the plain call and through a PreparedSurface
// (surfaces/prepared_surface.h), and the 1,024-teapot scene re-tessellated frame after frame
// from a moving camera.

#include <filesystem>

#include "report/report_section.h"

namespace patchwork::performance {

/// Section 9 (file comment). `bench_dir` holds make_scene and tessellator_bench, and
/// `cli` is the patchwork program; an empty bench_dir (the quick mode) gives a section saying
/// it was not run. Scratch files (the scenes, their glb files) go to a temporary folder that is
/// removed; the data and plot go to `data`.
ReportSection scale_section(const std::filesystem::path& bench_dir, const std::filesystem::path& cli,
                            const std::filesystem::path& source_dir, const std::filesystem::path& data);

}  // namespace patchwork::performance
