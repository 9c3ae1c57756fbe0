// The exhaustive blend matrix: every (SrcBlend, DestBlend, BlendOp) triple for
// RGB and every legal one for alpha, on every render-target format the reference
// model knows, with seeded random sources, destinations and blend factors,
// checked pixel by pixel against rhi::reference::BlendResult + CompareBlend (the
// stored-step table, or for ADD/SUBTRACT/REV_SUBTRACT the blend-term bound).
//
// Batching: one 256x256 target per format; every draw covers `casesPerTriple`
// consecutive pixels of one row (one case per pixel) with its own blend state and
// blend factor. The destination is uploaded with UpdateSubresource (exact bits),
// the pixel shader reads its SV_Target0 / SV_Target1 from structured buffers
// indexed by SV_Position. Draw k uses RGB triple k (1445 of them) and alpha triple
// (k*263) mod 605, so every alpha triple is used at least twice.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "conformance_gpu.h"
#include "rhi_reference/formats.h"

namespace conf {

using rhi::reference::Float4;
using rhi::reference::StoredColor;

struct Triple {
  rhi::BLEND src;
  rhi::BLEND dest;
  rhi::BLEND_OP op;
};

// 17 x 17 x 5 = 1445 for RGB. Alpha: D3D11 refuses the six colour factors in
// SrcBlendAlpha/DestBlendAlpha, so 11 x 11 x 5 = 605.
const std::vector<rhi::BLEND>& AllFactors();
const std::vector<rhi::BLEND>& AlphaFactors();
const std::vector<rhi::BLEND>& ColorOnlyFactors();
const std::vector<rhi::BLEND_OP>& AllOps();
std::vector<Triple> RgbTriples();
std::vector<Triple> AlphaTriples();

const std::vector<rhi::DXGI_FORMAT>& MatrixFormats();
const char* FormatName(rhi::DXGI_FORMAT format);
const char* FactorName(rhi::BLEND factor);
const char* OpName(rhi::BLEND_OP op);

struct MatrixOptions {
  UINT casesPerTriple = 4;  // divides 256; 4 in CI, 32 in the report
  uint32_t seed = 20240611;
  // Draw only triples k with k % tripleStride == (tripleOffset + format index) % tripleStride.
  // CI uses stride 4 (so 13 formats still cover every RGB triple 3-4 times in
  // total); the report uses 1 (every triple on every format).
  UINT tripleStride = 1;
  UINT tripleOffset = 0;
  std::vector<rhi::DXGI_FORMAT> formats = MatrixFormats();
};

struct CaseFailure {
  rhi::DXGI_FORMAT format;
  rhi::RENDER_TARGET_BLEND_DESC blend;
  Float4 factor, src0, src1;
  StoredColor dest, expected, actual;
  std::array<uint32_t, 4> steps;  // distance per channel (UINT32_MAX: incomparable)
  // Term bound per channel (tolerance.h): linear error, m, bound (k*unit(m) or the
  // float16 propagation bound); bound 0 where it does not apply.
  std::array<double, 4> error{}, magnitude{}, bound{};
  // SRC_ALPHA_SAT with f outside [0, 1]: the saturated reading's bits (also rejected).
  bool hadSaturatedReading = false;
  StoredColor saturatedExpected{};
  // Diagnosis only (not applied): the channel's error is within k*unit(M) with
  // M = max(m, |Csrc|, |Cdst|), the unscaled operands, as a rearranged
  // evaluation such as dst + f*(src - dst) would produce.
  bool withinOperandBound = false;
  std::string Describe() const;
};

struct Tally {
  uint64_t cases = 0, passed = 0;
  void Add(bool ok) { ++cases; passed += ok ? 1 : 0; }
};

struct FormatStats {
  rhi::DXGI_FORMAT format;
  Tally tally;
  std::array<uint32_t, 4> maxSteps{};      // largest distance seen per channel (comparable ones)
  std::array<uint32_t, 4> toleranceSteps{};
  uint64_t draws = 0;
  // Cases that failed the stored-step table and passed only by the blend-term
  // bound (|gpu-ref| <= k*unit(m), ADD/SUBTRACT/REV_SUBTRACT channels).
  uint64_t neededTermBound = 0;
  // Largest |gpu-ref| / bound over channels where the term bound applies (<= 1
  // passes by the bound), and k (propagated: float16's error-propagation bound).
  std::array<double, 4> maxTermRatio{};
  std::array<double, 4> termK{};
  std::array<bool, 4> termPropagated{};
  // SRC_ALPHA_SAT cases whose f = min(As, 1 - Ad) fell outside [0, 1] (float
  // targets only), and how many of them matched only the saturated reading
  // (f clamped to [0, 1]) rather than the FS 17.1 formula.
  uint64_t satOutOfRange = 0;
  uint64_t satSaturatedOnly = 0;
  // The case with the largest |gpu - ref| / bound (passing or not), described.
  double closestRatio = 0;
  std::string closestCase;
};

struct MatrixResult {
  std::vector<FormatStats> formats;
  std::map<rhi::BLEND, Tally> perFactor;   // a case counts for each factor its RGB or alpha uses
  std::map<rhi::BLEND_OP, Tally> perOp;    // a case counts for its RGB op and its alpha op
  std::vector<CaseFailure> failures;       // at most kMaxKeptFailures kept...
  uint64_t failureCount = 0;               // ...of this many
  uint64_t failuresWithinOperandBound = 0; // failures within k*unit(max(m, |Csrc|, |Cdst|)) (diagnosis)
  std::vector<std::string> validation;     // validation-layer messages seen
  std::vector<std::string> refusals;       // refusals seen (unexpected ones)
  static constexpr size_t kMaxKeptFailures = 400;
  uint64_t TotalCases() const;
};

// Runs the matrix on `gpu`. Throws std::runtime_error on setup failures.
MatrixResult RunBlendMatrix(Gpu& gpu, const MatrixOptions& options);

// CreateBlendState must refuse each colour factor in SrcBlendAlpha / DestBlendAlpha.
// Returns a description of every one it accepted (empty = conforming).
std::vector<std::string> CheckAlphaColorFactorsRefused(Gpu& gpu);

}  // namespace conf
