// Deterministic replay of tests/fuzz/corpus/ and tests/fuzz/regressions/
// through the same path as the fuzz target (fx_fuzz_common.h): every file must
// parse and compile (bounded) without a crash and end in a clean success or
// clean errors. No fuzzing, nothing random, nothing timed.
//
// usage: fx_corpus_replay DIR... (files directly in each DIR, sorted by name)
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "fx_fuzz_common.h"

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  int failures = 0, files = 0;
  for (int i = 1; i < argc; ++i) {
    std::error_code ec;
    if (!fs::is_directory(argv[i], ec)) {
      std::fprintf(stderr, "fx_corpus_replay: %s: not a directory\n", argv[i]);
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
      std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      fxfuzz::Outcome o = fxfuzz::RunOne(bytes.data(), bytes.size());
      // The hand-written seeds (seed_*.fx) are valid effects: they must parse and compile.
      if (path.filename().string().rfind("seed_", 0) == 0 && (!o.parsed || o.compiledOk != o.compiled || o.compiled == 0))
        o.problems.push_back("a seed effect must parse and compile");
      ++files;
      std::printf("%s: %s, %zu parse errors, %d/%d compiles ok%s\n", path.string().c_str(),
                  bytes.size() > fxfuzz::kMaxSourceBytes ? "skipped (too large)"
                  : o.parsed                              ? "parsed"
                                                          : "rejected",
                  o.parseErrors, o.compiledOk, o.compiled, o.problems.empty() ? "" : "  FAILED");
      for (const std::string& p : o.problems) std::printf("  problem: %s\n", p.c_str());
      if (!o.problems.empty()) ++failures;
    }
  }
  std::printf("fx_corpus_replay: %d files, %d failed\n", files, failures);
  return failures == 0 && files > 0 ? 0 : 1;
}
