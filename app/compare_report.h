// replay --compare's outputs (issue 16) from renderer::CompareMethods' results:
// DIR/comparison.md (the tables), DIR/compare_grid.png (rows scenes, columns methods,
// each scene's images over their error heat maps) and DIR/pareto_<scene>.png (error
// against GPU time per scene).
#pragma once

#include <string>
#include <vector>

#include "renderer/comparison.h"

// The heat maps' full scale, in 8-bit steps (white from there on).
inline constexpr int kHeatFullScale = 64;

struct CompareRun {
  std::string adapter;  // the device's name
  std::string command;  // the command line that made it
  renderer::ComparisonSettings settings;
};

// Each returns false (and `error`) when a file cannot be written.
bool WriteComparisonMarkdown(const std::string& path, const CompareRun& run,
                             const std::vector<renderer::SceneComparison>& scenes, std::string* error);
bool WriteCompareGrid(const std::string& path, const CompareRun& run,
                      const std::vector<renderer::SceneComparison>& scenes, std::string* error);
// DIR/pareto_<scene>.png for every scene with a reference.
bool WriteParetoPlots(const std::string& dir, const std::vector<renderer::SceneComparison>& scenes,
                      std::string* error);
// The file name of a scene's plot in `dir`.
std::string ParetoFile(const renderer::SceneComparison& scene);
