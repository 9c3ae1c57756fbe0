// libFuzzer target: the bytes of an .fx file through the effect front end and,
// when it parses, the HLSL compiler (see fx_fuzz_common.h). Built only with
// clang; see docs/FUZZING.md.
#include <cstdio>
#include <cstdlib>

#include "fx_fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > fxfuzz::kMaxSourceBytes) return -1;  // keep it out of the corpus
  // FX_FUZZ_COMPILES=0 fuzzes the front end alone (much faster).
  static const int maxCompiles = [] {
    const char* env = std::getenv("FX_FUZZ_COMPILES");
    return env ? std::atoi(env) : fxfuzz::kMaxCompilesPerInput;
  }();
  fxfuzz::Outcome outcome = fxfuzz::RunOne(data, size, maxCompiles);
  if (!outcome.problems.empty()) {
    for (const std::string& p : outcome.problems) std::fprintf(stderr, "fx_fuzz: %s\n", p.c_str());
    std::abort();
  }
  return 0;
}
