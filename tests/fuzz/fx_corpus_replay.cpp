// Deterministic replay of tests/fuzz/corpus/ and tests/fuzz/regressions/
// through the same path as the fuzz target (fx_fuzz_common.h): every file must
// parse and compile (bounded) without a crash and end in a clean success or
// clean errors. No fuzzing, nothing random, nothing timed.
//
// usage: fx_corpus_replay DIR... (files directly in each DIR, sorted by name)
#include "corpus_replay.h"
#include "fx_fuzz_common.h"

int main(int argc, char** argv) {
  return corpus::Replay("fx_corpus_replay", argc, argv, [](const auto& path, const std::vector<uint8_t>& bytes) {
    fxfuzz::Outcome o = fxfuzz::RunOne(bytes.data(), bytes.size());
    // The hand-written seeds (seed_*.fx) are valid effects: they must parse and compile.
    if (path.filename().string().rfind("seed_", 0) == 0 && (!o.parsed || o.compiledOk != o.compiled || o.compiled == 0))
      o.problems.push_back("a seed effect must parse and compile");
    std::printf("%s: %s, %zu parse errors, %d/%d compiles ok%s\n", path.string().c_str(),
                bytes.size() > fxfuzz::kMaxSourceBytes ? "skipped (too large)"
                : o.parsed                              ? "parsed"
                                                        : "rejected",
                o.parseErrors, o.compiledOk, o.compiled, o.problems.empty() ? "" : "  FAILED");
    for (const std::string& p : o.problems) std::printf("  problem: %s\n", p.c_str());
    return o.problems.empty();
  });
}
