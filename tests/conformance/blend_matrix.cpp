#include "blend_matrix.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <random>
#include <sstream>
#include <stdexcept>

#include "rhi_reference/blend.h"
#include "rhi_reference/tolerance.h"

namespace conf {

using namespace rhi;
namespace ref = rhi::reference;

const std::vector<BLEND>& AllFactors() {
  static const std::vector<BLEND> f{BLEND_ZERO, BLEND_ONE, BLEND_SRC_COLOR, BLEND_INV_SRC_COLOR,
                                    BLEND_SRC_ALPHA, BLEND_INV_SRC_ALPHA, BLEND_DEST_ALPHA, BLEND_INV_DEST_ALPHA,
                                    BLEND_DEST_COLOR, BLEND_INV_DEST_COLOR, BLEND_SRC_ALPHA_SAT,
                                    BLEND_BLEND_FACTOR, BLEND_INV_BLEND_FACTOR, BLEND_SRC1_COLOR,
                                    BLEND_INV_SRC1_COLOR, BLEND_SRC1_ALPHA, BLEND_INV_SRC1_ALPHA};
  return f;
}

const std::vector<BLEND>& ColorOnlyFactors() {
  static const std::vector<BLEND> f{BLEND_SRC_COLOR,  BLEND_INV_SRC_COLOR,  BLEND_DEST_COLOR,
                                    BLEND_INV_DEST_COLOR, BLEND_SRC1_COLOR, BLEND_INV_SRC1_COLOR};
  return f;
}

const std::vector<BLEND>& AlphaFactors() {
  static const std::vector<BLEND> f = [] {
    std::vector<BLEND> out;
    for (BLEND b : AllFactors()) {
      bool colour = false;
      for (BLEND c : ColorOnlyFactors()) colour |= b == c;
      if (!colour) out.push_back(b);
    }
    return out;
  }();
  return f;
}

const std::vector<BLEND_OP>& AllOps() {
  static const std::vector<BLEND_OP> o{BLEND_OP_ADD, BLEND_OP_SUBTRACT, BLEND_OP_REV_SUBTRACT, BLEND_OP_MIN,
                                       BLEND_OP_MAX};
  return o;
}

static std::vector<Triple> Triples(const std::vector<BLEND>& factors) {
  std::vector<Triple> out;
  for (BLEND_OP op : AllOps())
    for (BLEND s : factors)
      for (BLEND d : factors) out.push_back({s, d, op});
  return out;
}
std::vector<Triple> RgbTriples() { return Triples(AllFactors()); }
std::vector<Triple> AlphaTriples() { return Triples(AlphaFactors()); }

const std::vector<DXGI_FORMAT>& MatrixFormats() {
  static const std::vector<DXGI_FORMAT> f{
      DXGI_FORMAT_R8G8B8A8_UNORM,     DXGI_FORMAT_R8G8B8A8_UNORM_SRGB, DXGI_FORMAT_B8G8R8A8_UNORM,
      DXGI_FORMAT_B8G8R8X8_UNORM,     DXGI_FORMAT_R10G10B10A2_UNORM,   DXGI_FORMAT_R16G16B16A16_FLOAT,
      DXGI_FORMAT_R32G32B32A32_FLOAT, DXGI_FORMAT_R16G16_FLOAT,        DXGI_FORMAT_R8_UNORM,
      DXGI_FORMAT_R16_FLOAT,          DXGI_FORMAT_R32_FLOAT,           DXGI_FORMAT_R32_UINT,
      DXGI_FORMAT_R32G32B32A32_UINT};
  return f;
}

const char* FormatName(DXGI_FORMAT format) {
  switch (format) {
    case DXGI_FORMAT_R8G8B8A8_UNORM: return "R8G8B8A8_UNORM";
    case DXGI_FORMAT_R8G8B8A8_UNORM_SRGB: return "R8G8B8A8_UNORM_SRGB";
    case DXGI_FORMAT_B8G8R8A8_UNORM: return "B8G8R8A8_UNORM";
    case DXGI_FORMAT_B8G8R8X8_UNORM: return "B8G8R8X8_UNORM";
    case DXGI_FORMAT_R10G10B10A2_UNORM: return "R10G10B10A2_UNORM";
    case DXGI_FORMAT_R16G16B16A16_FLOAT: return "R16G16B16A16_FLOAT";
    case DXGI_FORMAT_R32G32B32A32_FLOAT: return "R32G32B32A32_FLOAT";
    case DXGI_FORMAT_R16G16_FLOAT: return "R16G16_FLOAT";
    case DXGI_FORMAT_R8_UNORM: return "R8_UNORM";
    case DXGI_FORMAT_R16_FLOAT: return "R16_FLOAT";
    case DXGI_FORMAT_R32_FLOAT: return "R32_FLOAT";
    case DXGI_FORMAT_R32_UINT: return "R32_UINT";
    case DXGI_FORMAT_R32G32B32A32_UINT: return "R32G32B32A32_UINT";
    case DXGI_FORMAT_D32_FLOAT: return "D32_FLOAT";
    case DXGI_FORMAT_D24_UNORM_S8_UINT: return "D24_UNORM_S8_UINT";
    default: return "?";
  }
}

const char* FactorName(BLEND factor) {
  switch (factor) {
    case BLEND_ZERO: return "ZERO";
    case BLEND_ONE: return "ONE";
    case BLEND_SRC_COLOR: return "SRC_COLOR";
    case BLEND_INV_SRC_COLOR: return "INV_SRC_COLOR";
    case BLEND_SRC_ALPHA: return "SRC_ALPHA";
    case BLEND_INV_SRC_ALPHA: return "INV_SRC_ALPHA";
    case BLEND_DEST_ALPHA: return "DEST_ALPHA";
    case BLEND_INV_DEST_ALPHA: return "INV_DEST_ALPHA";
    case BLEND_DEST_COLOR: return "DEST_COLOR";
    case BLEND_INV_DEST_COLOR: return "INV_DEST_COLOR";
    case BLEND_SRC_ALPHA_SAT: return "SRC_ALPHA_SAT";
    case BLEND_BLEND_FACTOR: return "BLEND_FACTOR";
    case BLEND_INV_BLEND_FACTOR: return "INV_BLEND_FACTOR";
    case BLEND_SRC1_COLOR: return "SRC1_COLOR";
    case BLEND_INV_SRC1_COLOR: return "INV_SRC1_COLOR";
    case BLEND_SRC1_ALPHA: return "SRC1_ALPHA";
    case BLEND_INV_SRC1_ALPHA: return "INV_SRC1_ALPHA";
  }
  return "?";
}

const char* OpName(BLEND_OP op) {
  switch (op) {
    case BLEND_OP_ADD: return "ADD";
    case BLEND_OP_SUBTRACT: return "SUBTRACT";
    case BLEND_OP_REV_SUBTRACT: return "REV_SUBTRACT";
    case BLEND_OP_MIN: return "MIN";
    case BLEND_OP_MAX: return "MAX";
  }
  return "?";
}

uint64_t MatrixResult::TotalCases() const {
  uint64_t n = 0;
  for (const FormatStats& f : formats) n += f.tally.cases;
  return n;
}

namespace {

constexpr UINT kSize = 256;

bool IsDual(BLEND f) { return f >= BLEND_SRC1_COLOR && f <= BLEND_INV_SRC1_ALPHA; }

bool UsesDual(const RENDER_TARGET_BLEND_DESC& b) {
  return IsDual(b.SrcBlend) || IsDual(b.DestBlend) || IsDual(b.SrcBlendAlpha) || IsDual(b.DestBlendAlpha);
}

std::string VertexShaderSource(UINT casesPerDraw) {
  // Draw k (StartVertexLocation = 6k; SV_VertexID includes it) covers pixels
  // [k*N, k*N+N) of the row-major 256x256 target: a N x 1 rectangle.
  std::ostringstream s;
  s << "static const uint W = " << kSize << "; static const uint N = " << casesPerDraw << ";\n"
    << R"(float4 main(uint vid : SV_VertexID) : SV_Position {
  uint rect = vid / 6; uint corner = vid % 6;
  uint first = rect * N;
  float x = float(first % W) + ((corner == 1 || corner == 4 || corner == 5) ? float(N) : 0.0);
  float y = float(first / W) + ((corner == 2 || corner == 3 || corner == 5) ? 1.0 : 0.0);
  return float4(x / W * 2.0 - 1.0, 1.0 - y / W * 2.0, 0.0, 1.0);
})";
  return s.str();
}

std::string PixelShaderSource(bool uintTarget, bool dual) {
  std::ostringstream s;
  const char* type = uintTarget ? "uint4" : "float4";
  s << "static const uint W = " << kSize << ";\n"
    << "StructuredBuffer<" << type << "> Src0 : register(t0);\n"
    << "StructuredBuffer<" << type << "> Src1 : register(t1);\n"
    << "struct Out { " << type << " c0 : SV_Target0; " << (dual ? std::string(type) + " c1 : SV_Target1; " : "")
    << "};\n"
    << "Out main(float4 pos : SV_Position) { uint i = uint(pos.y) * W + uint(pos.x); Out o; o.c0 = Src0[i]; "
    << (dual ? "o.c1 = Src1[i]; " : "") << "return o; }\n";
  return s.str();
}

struct Rng {
  std::mt19937 engine;
  explicit Rng(uint32_t seed) : engine(seed) {}
  float Uniform(float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(engine); }
  uint32_t Bits() { return engine(); }
  uint32_t Below(uint32_t n) { return std::uniform_int_distribution<uint32_t>(0, n - 1)(engine); }
};

// A shader output value: for UNORM targets in [-0.5, 1.5] (so the clamp before
// blending matters), for float targets in [-2, 3] with one in eight in [-40, 40];
// one in eight snapped to an exact 0 or 1.
float SourceValue(Rng& rng, bool normalized) {
  const uint32_t pick = rng.Below(16);
  if (pick == 0) return 0.0f;
  if (pick == 1) return 1.0f;
  if (normalized) return rng.Uniform(-0.5f, 1.5f);
  if (pick == 2 || pick == 3) return rng.Uniform(-40.0f, 40.0f);
  return rng.Uniform(-2.0f, 3.0f);
}

StoredColor RandomDest(Rng& rng, DXGI_FORMAT format) {
  StoredColor c;
  for (int ch = 0; ch < 4; ++ch) {
    switch (ref::KindOf(format, ch)) {
      case ref::ChannelKind::Absent: c.bits[ch] = 0; break;
      case ref::ChannelKind::Unorm:
      case ref::ChannelKind::Srgb: c.bits[ch] = rng.Bits() & ((1u << ref::UnormBits(format, ch)) - 1u); break;
      case ref::ChannelKind::Uint: c.bits[ch] = rng.Bits(); break;
      case ref::ChannelKind::Float16:
      case ref::ChannelKind::Float32: {
        Float4 v{};
        v[ch] = rng.Uniform(-2.0f, 3.0f);
        c.bits[ch] = ref::Encode(format, v).bits[ch];
        break;
      }
    }
  }
  return c;
}

std::string F4(const Float4& v) {
  std::ostringstream s;
  s.precision(9);
  s << "(" << v[0] << ", " << v[1] << ", " << v[2] << ", " << v[3] << ")";
  return s.str();
}

std::string Bits(const StoredColor& c) {
  std::ostringstream s;
  s << std::hex << "[" << c.bits[0] << " " << c.bits[1] << " " << c.bits[2] << " " << c.bits[3] << "]";
  return s.str();
}

}  // namespace

std::string CaseFailure::Describe() const {
  std::ostringstream s;
  s << FormatName(format) << " RGB " << FactorName(blend.SrcBlend) << "/" << FactorName(blend.DestBlend) << "/"
    << OpName(blend.BlendOp) << " A " << FactorName(blend.SrcBlendAlpha) << "/"
    << FactorName(blend.DestBlendAlpha) << "/" << OpName(blend.BlendOpAlpha) << ": src0 " << F4(src0)
    << " src1 " << F4(src1) << " factor " << F4(factor) << " dest " << Bits(dest) << " expected "
    << Bits(expected) << " actual " << Bits(actual) << " steps (";
  for (int c = 0; c < 4; ++c)
    s << (steps[c] == ref::kIncomparable ? std::string("inc") : std::to_string(steps[c])) << (c < 3 ? "," : ")");
  s.precision(3);
  s << " term bound (|err| / bound @ m):";
  for (int c = 0; c < 4; ++c) {
    if (bound[c] > 0) s << " " << "RGBA"[c] << " " << error[c] << "/" << bound[c] << "@" << magnitude[c];
  }
  if (hadSaturatedReading) s << "; SRC_ALPHA_SAT f outside [0,1], saturated reading " << Bits(saturatedExpected) << " also rejected";
  if (withinOperandBound) s << "; within k*unit(max operand)";
  return s.str();
}

MatrixResult RunBlendMatrix(Gpu& gpu, const MatrixOptions& options) {
  const UINT n = options.casesPerTriple;
  if (n == 0 || kSize % n != 0) throw std::invalid_argument("casesPerTriple must divide 256");
  const std::vector<Triple> rgb = RgbTriples();
  const std::vector<Triple> alpha = AlphaTriples();
  const UINT draws = static_cast<UINT>(rgb.size());
  if (static_cast<uint64_t>(draws) * n > kSize * kSize) throw std::invalid_argument("too many cases for 256x256");

  MatrixResult result;
  DeviceContext* ctx = gpu.context();
  auto vs = gpu.VS(VertexShaderSource(n));
  auto psFloat = gpu.PS(PixelShaderSource(false, false));
  auto psFloatDual = gpu.PS(PixelShaderSource(false, true));
  auto psUint = gpu.PS(PixelShaderSource(true, false));
  auto psUintDual = gpu.PS(PixelShaderSource(true, true));

  // The blend states: one per draw, shared by every format.
  std::vector<RENDER_TARGET_BLEND_DESC> descs(draws);
  std::vector<ComPtr<BlendState>> states(draws);
  for (UINT k = 0; k < draws; ++k) {
    const Triple& c = rgb[k];
    const Triple& a = alpha[(static_cast<uint64_t>(k) * 263u) % alpha.size()];
    BLEND_DESC desc;
    RENDER_TARGET_BLEND_DESC& rt = desc.RenderTarget[0];
    rt.BlendEnable = TRUE;
    rt.SrcBlend = c.src;
    rt.DestBlend = c.dest;
    rt.BlendOp = c.op;
    rt.SrcBlendAlpha = a.src;
    rt.DestBlendAlpha = a.dest;
    rt.BlendOpAlpha = a.op;
    rt.RenderTargetWriteMask = COLOR_WRITE_ENABLE_ALL;
    descs[k] = rt;
    if (gpu.device()->CreateBlendState(&desc, states[k].GetAddressOf()) != S_OK)
      throw std::runtime_error("CreateBlendState refused a legal state");
  }

  Rng rng(options.seed);
  const UINT stride = std::max(1u, options.tripleStride);
  for (size_t formatIndex = 0; formatIndex < options.formats.size(); ++formatIndex) {
    const DXGI_FORMAT format = options.formats[formatIndex];
    UINT formatSlot = 0;  // position in MatrixFormats(), so a single-format run picks the same triples
    for (UINT m = 0; m < MatrixFormats().size(); ++m)
      if (MatrixFormats()[m] == format) formatSlot = m;
    auto drawn = [&](UINT k) { return k % stride == (options.tripleOffset + formatSlot) % stride; };
    const bool isUint = ref::IsUintFormat(format);
    const bool normalized = ref::IsNormalizedFormat(format);
    const size_t bpp = ref::BytesPerPixel(format);
    const UINT pixels = kSize * kSize;

    std::vector<Float4> src0(pixels), src1(pixels);
    std::vector<StoredColor> dest(pixels);
    std::vector<Float4> factors(draws);
    for (UINT i = 0; i < pixels; ++i) {
      for (int ch = 0; ch < 4; ++ch) {
        if (isUint) {
          src0[i][ch] = std::bit_cast<float>(rng.Bits());
          src1[i][ch] = std::bit_cast<float>(rng.Bits());
        } else {
          src0[i][ch] = SourceValue(rng, normalized);
          src1[i][ch] = SourceValue(rng, normalized);
        }
      }
      dest[i] = RandomDest(rng, format);
    }
    for (UINT k = 0; k < draws; ++k)
      for (int ch = 0; ch < 4; ++ch) factors[k][ch] = normalized ? rng.Uniform(-0.5f, 1.5f) : rng.Uniform(-2.0f, 3.0f);

    std::vector<uint8_t> destBytes(pixels * bpp);
    for (UINT i = 0; i < pixels; ++i) {
      std::vector<uint8_t> p = ref::PackPixel(format, dest[i]);
      std::memcpy(destBytes.data() + i * bpp, p.data(), bpp);
    }

    auto target = gpu.Texture(kSize, kSize, format, BIND_RENDER_TARGET);
    auto rtv = gpu.RTV(target.Get());
    ctx->UpdateSubresource(target.Get(), 0, nullptr, destBytes.data(), static_cast<UINT>(kSize * bpp), 0);
    auto s0 = gpu.StructuredSRV(src0.data(), 16, pixels);
    auto s1 = gpu.StructuredSRV(src1.data(), 16, pixels);

    ctx->ClearState();
    ctx->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    ctx->VSSetShader(vs.Get(), nullptr, 0);
    ShaderResourceView* srvs[] = {s0.Get(), s1.Get()};
    ctx->PSSetShaderResources(0, 2, srvs);
    RenderTargetView* rtvs[] = {rtv.Get()};
    ctx->OMSetRenderTargets(1, rtvs, nullptr);
    gpu.Viewport(kSize, kSize);
    for (UINT k = 0; k < draws; ++k) {
      if (!drawn(k)) continue;
      const bool dual = UsesDual(descs[k]);
      ctx->PSSetShader(isUint ? (dual ? psUintDual : psUint).Get() : (dual ? psFloatDual : psFloat).Get(), nullptr, 0);
      ctx->OMSetBlendState(states[k].Get(), factors[k].data(), DEFAULT_SAMPLE_MASK);
      ctx->Draw(6, 6 * k);
    }
    ctx->OMSetRenderTargets(0, nullptr, nullptr);
    const std::vector<uint8_t> bytes = gpu.Read(target.Get(), static_cast<UINT>(bpp));

    FormatStats stats{format};
    stats.toleranceSteps = ref::Tolerance(format).steps;
    for (int ch = 0; ch < 4; ++ch) {
      stats.termK[ch] = ref::BlendTermK(format, ch).k;
      stats.termPropagated[ch] = ref::BlendTermK(format, ch).propagated;
    }
    for (UINT k = 0; k < draws; ++k) {
      if (!drawn(k)) continue;
      ++stats.draws;
      const RENDER_TARGET_BLEND_DESC& rt = descs[k];
      for (UINT j = 0; j < n; ++j) {
        const UINT i = k * n + j;
        const ref::BlendOutput out = ref::BlendResult(format, rt, factors[k], src0[i], src1[i], dest[i]);
        const StoredColor& expected = out.stored;
        const StoredColor actual =
            ref::UnpackPixel(format, std::span<const uint8_t>(bytes.data() + i * bpp, bpp));
        const ref::BlendVerdict verdict = ref::CompareBlend(format, out, actual);
        const bool ok = verdict.ok;
        std::array<uint32_t, 4> steps{};
        std::array<double, 4> error{}, magnitude{}, bound{};
        for (int ch = 0; ch < 4; ++ch) {
          const ref::ChannelVerdict& v = verdict.channels[ch];
          steps[ch] = ref::StoredDistance(format, ch, expected.bits[ch], actual.bits[ch]);
          if (steps[ch] != ref::kIncomparable) stats.maxSteps[ch] = std::max(stats.maxSteps[ch], steps[ch]);
          if (v.termBoundApplies) {
            error[ch] = v.error;
            magnitude[ch] = v.m;
            bound[ch] = v.bound;
            if (v.bound > 0) stats.maxTermRatio[ch] = std::max(stats.maxTermRatio[ch], v.error / v.bound);
          }
        }
        double caseRatio = 0;
        for (int ch = 0; ch < 4; ++ch)
          if (bound[ch] > 0) caseRatio = std::max(caseRatio, error[ch] / bound[ch]);
        if (caseRatio > stats.closestRatio) {
          stats.closestRatio = caseRatio;
          stats.closestCase = CaseFailure{format, rt, factors[k], src0[i], src1[i], dest[i], expected, actual, steps,
                                          error, magnitude, bound, out.hasSaturatedReading, out.saturated.stored,
                                          false}
                                  .Describe();
        }
        stats.tally.Add(ok);
        if (ok && verdict.usedTermBound) ++stats.neededTermBound;
        if (out.hasSaturatedReading) {
          ++stats.satOutOfRange;
          if (ok && verdict.usedSaturatedReading) ++stats.satSaturatedOnly;
        }
        for (BLEND f : AllFactors())
          if (rt.SrcBlend == f || rt.DestBlend == f || rt.SrcBlendAlpha == f || rt.DestBlendAlpha == f)
            result.perFactor[f].Add(ok);
        result.perOp[rt.BlendOp].Add(ok);
        if (rt.BlendOpAlpha != rt.BlendOp) result.perOp[rt.BlendOpAlpha].Add(ok);
        if (!ok) {
          // Would a bound at the unscaled operands' magnitude cover it? (reported, not applied)
          bool withinOperand = true;
          for (int ch = 0; ch < 4; ++ch) {
            const ref::ChannelVerdict& v = verdict.channels[ch];
            if (v.ok()) continue;
            if (!v.termBoundApplies || ref::BlendTermK(format, ch).propagated) { withinOperand = false; break; }
            const double big = std::max({v.m, std::fabs(static_cast<double>(out.terms.srcOperand[ch])),
                                         std::fabs(static_cast<double>(out.terms.destOperand[ch]))});
            withinOperand = withinOperand && v.error <= ref::BlendTermK(format, ch).k * ref::BlendUnit(format, ch, big);
          }
          if (withinOperand) ++result.failuresWithinOperandBound;
          ++result.failureCount;
          if (result.failures.size() < MatrixResult::kMaxKeptFailures)
            result.failures.push_back(
                {format, rt, factors[k], src0[i], src1[i], dest[i], expected, actual, steps, error, magnitude, bound,
                 out.hasSaturatedReading, out.saturated.stored, withinOperand});
        }
      }
    }
    result.formats.push_back(stats);
  }
  result.validation = gpu.validation();
  result.refusals = gpu.refusals();
  return result;
}

std::vector<std::string> CheckAlphaColorFactorsRefused(Gpu& gpu) {
  std::vector<std::string> accepted;
  for (BLEND f : ColorOnlyFactors()) {
    for (int field = 0; field < 2; ++field) {
      BLEND_DESC desc;
      desc.RenderTarget[0].BlendEnable = TRUE;
      (field == 0 ? desc.RenderTarget[0].SrcBlendAlpha : desc.RenderTarget[0].DestBlendAlpha) = f;
      ComPtr<BlendState> state;
      if (gpu.device()->CreateBlendState(&desc, state.GetAddressOf()) != E_INVALIDARG || state)
        accepted.push_back(std::string(field == 0 ? "SrcBlendAlpha = " : "DestBlendAlpha = ") + FactorName(f));
    }
  }
  return accepted;
}

}  // namespace conf
