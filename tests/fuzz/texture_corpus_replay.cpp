// Deterministic replay of tests/fuzz/texture_corpus/ through the same path as the fuzz
// target (texture_fuzz_common.h): every file must end in a clean success or a clean
// error, and the seeds named seed_*.dds / seed_*.<image> must parse / decode.
//
// usage: texture_corpus_replay DIR... (files directly in each DIR, sorted by name)
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "texture_fuzz_common.h"

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  int failures = 0, files = 0;
  for (int i = 1; i < argc; ++i) {
    std::error_code ec;
    if (!fs::is_directory(argv[i], ec)) {
      std::fprintf(stderr, "texture_corpus_replay: %s: not a directory\n", argv[i]);
      return 2;
    }
    std::vector<fs::path> paths;
    for (const auto& entry : fs::directory_iterator(argv[i]))
      if (entry.is_regular_file() && entry.path().filename().string()[0] != '.') paths.push_back(entry.path());
    std::sort(paths.begin(), paths.end());
    for (const fs::path& path : paths) {
      std::ifstream in(path, std::ios::binary);
      std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      texfuzz::Outcome o = texfuzz::RunOne(bytes.data(), bytes.size());
      const std::string name = path.filename().string();
      if (name.rfind("seed_", 0) == 0 && !(path.extension() == ".dds" ? o.parsedDds : o.decodedImage))
        o.problems.push_back("a seed must load");
      ++files;
      std::printf("%s: %s%s\n", path.string().c_str(),
                  o.parsedDds ? "DDS" : o.decodedImage ? "image" : "rejected", o.problems.empty() ? "" : "  FAILED");
      for (const std::string& p : o.problems) std::printf("  problem: %s\n", p.c_str());
      if (!o.problems.empty()) ++failures;
    }
  }
  std::printf("texture_corpus_replay: %d files, %d failed\n", files, failures);
  return failures == 0 && files > 0 ? 0 : 1;
}
