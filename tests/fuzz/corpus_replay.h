// The deterministic replay of a fuzz corpus, shared by fx_corpus_replay and
// texture_corpus_replay: every file directly in each folder named on the command
// line (dot files and README.md left out), sorted by name, read whole and handed to
// `check`, which prints its line and returns false for a failure.
//
// usage: <program> DIR...
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <vector>

namespace corpus {

using Check = std::function<bool(const std::filesystem::path& file, const std::vector<uint8_t>& bytes)>;

// 0 when every file passed and there was one at least; 2 for a folder that is not one.
inline int Replay(const char* program, int argc, char** argv, const Check& check) {
  namespace fs = std::filesystem;
  int failures = 0, files = 0;
  for (int i = 1; i < argc; ++i) {
    std::error_code ec;
    if (!fs::is_directory(argv[i], ec)) {
      std::fprintf(stderr, "%s: %s: not a directory\n", program, argv[i]);
      return 2;
    }
    std::vector<fs::path> paths;
    for (const auto& entry : fs::directory_iterator(argv[i]))
      if (entry.is_regular_file() && entry.path().filename().string()[0] != '.' &&
          entry.path().filename() != "README.md")
        paths.push_back(entry.path());
    std::sort(paths.begin(), paths.end());
    for (const fs::path& path : paths) {
      std::ifstream in(path, std::ios::binary);
      const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      ++files;
      if (!check(path, bytes)) ++failures;
    }
  }
  std::printf("%s: %d files, %d failed\n", program, files, failures);
  return failures == 0 && files > 0 ? 0 : 1;
}

}  // namespace corpus
