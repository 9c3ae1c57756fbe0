// Deterministic replay of tests/fuzz/texture_corpus/ through the same path as the fuzz
// target (texture_fuzz_common.h): every file must end in a clean success or a clean
// error, and the seeds named seed_*.dds / seed_*.<image> must parse / decode.
//
// usage: texture_corpus_replay DIR... (files directly in each DIR, sorted by name)
#include "corpus_replay.h"
#include "texture_fuzz_common.h"

int main(int argc, char** argv) {
  return corpus::Replay("texture_corpus_replay", argc, argv, [](const auto& path, const std::vector<uint8_t>& bytes) {
    texfuzz::Outcome o = texfuzz::RunOne(bytes.data(), bytes.size());
    const std::string name = path.filename().string();
    if (name.rfind("seed_", 0) == 0 && !(path.extension() == ".dds" ? o.parsedDds : o.decodedImage))
      o.problems.push_back("a seed must load");
    std::printf("%s: %s%s\n", path.string().c_str(),
                o.parsedDds ? "DDS" : o.decodedImage ? "image" : "rejected", o.problems.empty() ? "" : "  FAILED");
    for (const std::string& p : o.problems) std::printf("  problem: %s\n", p.c_str());
    return o.problems.empty();
  });
}
