// Depth-stencil conformance against rhi::reference::DepthStencilResult.
//
// A 16x16 grid, one case per pixel: an init pass writes each pixel's stored
// depth (quad z, ALWAYS, writes on) and stored stencil (REPLACE with one of four
// reference values, one draw per group); the stored values are then read back
// (depth: staging copy; stencil: eight EQUAL probes with ReadMask = 1<<bit), so
// the model is fed exactly what the GPU holds. The test pass draws one quad per
// pixel at the case's fragment depth, front- or back-facing (two-sided stencil),
// with the state under test; afterwards pass/fail (a colour write), depth and
// stencil are read back and compared with the model. D24 depth written by a
// fragment may differ from the model's round-to-nearest by one code (the
// float->24-bit conversion); everything else is exact.
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <sstream>

#include "blend_matrix.h"
#include "conformance_gpu.h"
#include "rhi_reference/depth_stencil.h"

namespace {

using namespace rhi;
using conf::ComPtr;
using conf::Gpu;
namespace ref = rhi::reference;

constexpr UINT kW = 16;
constexpr UINT kPixels = kW * kW;
constexpr uint8_t kInitStencil[4] = {0x00, 0x5A, 0xFF, 0x81};
constexpr float kStored[5] = {0.0f, 0.25f, 0.5f, 0.75f, 1.0f};
constexpr float kFragment[6] = {0.0f, 0.25f, 0.5f, 0.5000001f, 0.75f, 1.0f};

struct Case {
  float stored, fragment;
  int group;
  bool back;
};

Case CaseOf(UINT i) { return {kStored[i % 5], kFragment[(i / 5) % 6], int((i / 30) % 4), ((i / 7) % 2) == 1}; }

const char* kVS = R"(
StructuredBuffer<float4> Quads : register(t0);   // x, y, z, back-facing
float4 main(uint vid : SV_VertexID) : SV_Position {
  float4 q = Quads[vid / 6]; uint c = vid % 6;
  if (q.w > 0.5) { if (c == 1) c = 2; else if (c == 2) c = 1; else if (c == 4) c = 3; else if (c == 3) c = 4; }
  float x = q.x + ((c == 1 || c == 4 || c == 5) ? 1.0 : 0.0);
  float y = q.y + ((c == 2 || c == 3 || c == 5) ? 1.0 : 0.0);
  return float4(x / 8.0 - 1.0, 1.0 - y / 8.0, q.z, 1.0);
})";
const char* kPS = "float4 main() : SV_Target { return float4(1, 1, 1, 1); }";

class DepthStencil {
 public:
  explicit DepthStencil(DXGI_FORMAT format) : format_(format), gpu_(nullptr, true) {
    depth_ = gpu_.Texture(kW, kW, format, BIND_DEPTH_STENCIL);
    gpu_.device()->CreateDepthStencilView(depth_.Get(), nullptr, dsv_.GetAddressOf());
    color_ = gpu_.Texture(kW, kW, DXGI_FORMAT_R8_UNORM, BIND_RENDER_TARGET);
    rtv_ = gpu_.RTV(color_.Get());
    vs_ = gpu_.VS(kVS);
    ps_ = gpu_.PS(kPS);
    RASTERIZER_DESC rs;
    rs.CullMode = CULL_NONE;
    gpu_.device()->CreateRasterizerState(&rs, rs_.GetAddressOf());
  }
  Gpu& gpu() { return gpu_; }

  // Draws quads[first, first+count) (x, y, z, back) with `state` (null: NULL state).
  void DrawQuads(const std::vector<std::array<float, 4>>& quads, UINT first, UINT count, DepthStencilState* state,
                 UINT ref, bool colour) {
    auto srv = gpu_.StructuredSRV(quads.data(), 16, static_cast<UINT>(quads.size()));
    DeviceContext* ctx = gpu_.context();
    ctx->ClearState();
    ctx->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    ctx->VSSetShader(vs_.Get(), nullptr, 0);
    ShaderResourceView* srvs[] = {srv.Get()};
    ctx->VSSetShaderResources(0, 1, srvs);
    ctx->PSSetShader(ps_.Get(), nullptr, 0);
    ctx->RSSetState(rs_.Get());
    gpu_.Viewport(kW, kW);
    RenderTargetView* rtvs[] = {rtv_.Get()};
    ctx->OMSetRenderTargets(colour ? 1 : 0, rtvs, dsv_.Get());
    ctx->OMSetDepthStencilState(state, ref);
    ctx->Draw(6 * count, 6 * first);
    ctx->ClearState();
  }

  void ClearColour() {
    const float zero[4] = {0, 0, 0, 0};
    gpu_.context()->ClearRenderTargetView(rtv_.Get(), zero);
  }

  std::vector<uint8_t> ReadColour() { return gpu_.Read(color_.Get(), 1); }

  std::vector<uint32_t> ReadDepth() {
    std::vector<uint8_t> bytes = gpu_.Read(depth_.Get(), 4);
    std::vector<uint32_t> d(kPixels);
    std::memcpy(d.data(), bytes.data(), kPixels * 4);
    if (format_ == DXGI_FORMAT_D24_UNORM_S8_UINT)
      for (uint32_t& v : d) v &= 0xFFFFFFu;
    return d;
  }

  // Stencil through eight EQUAL probes (depth off).
  std::vector<uint8_t> ReadStencil() {
    std::vector<uint8_t> s(kPixels, 0);
    std::vector<std::array<float, 4>> full;
    for (UINT i = 0; i < kPixels; ++i) full.push_back({float(i % kW), float(i / kW), 0.5f, 0.0f});
    for (int bit = 0; bit < 8; ++bit) {
      DEPTH_STENCIL_DESC d;
      d.DepthEnable = FALSE;
      d.StencilEnable = TRUE;
      d.StencilReadMask = static_cast<UINT8>(1u << bit);
      d.StencilWriteMask = 0;
      d.FrontFace.StencilFunc = d.BackFace.StencilFunc = COMPARISON_EQUAL;
      ComPtr<DepthStencilState> st;
      gpu_.device()->CreateDepthStencilState(&d, st.GetAddressOf());
      ClearColour();
      DrawQuads(full, 0, kPixels, st.Get(), 1u << bit, true);
      std::vector<uint8_t> c = ReadColour();
      for (UINT i = 0; i < kPixels; ++i)
        if (c[i] == 255) s[i] |= static_cast<uint8_t>(1u << bit);
    }
    return s;
  }

  // Init pass, test pass, readbacks, model comparison. Returns failure descriptions.
  std::vector<std::string> Run(const DEPTH_STENCIL_DESC* desc, UINT stencilRef) {
    const bool stencil = format_ == DXGI_FORMAT_D24_UNORM_S8_UINT;
    gpu_.context()->ClearDepthStencilView(dsv_.Get(), CLEAR_DEPTH | CLEAR_STENCIL, 1.0f, 0);
    std::vector<std::array<float, 4>> init, test;
    for (int g = 0; g < 4; ++g)
      for (UINT i = 0; i < kPixels; ++i)
        if (CaseOf(i).group == g) init.push_back({float(i % kW), float(i / kW), CaseOf(i).stored, 0.0f});
    DEPTH_STENCIL_DESC initDesc;
    initDesc.DepthFunc = COMPARISON_ALWAYS;
    initDesc.StencilEnable = stencil ? TRUE : FALSE;
    initDesc.FrontFace = {STENCIL_OP_REPLACE, STENCIL_OP_REPLACE, STENCIL_OP_REPLACE, COMPARISON_ALWAYS};
    initDesc.BackFace = initDesc.FrontFace;
    ComPtr<DepthStencilState> initState;
    gpu_.device()->CreateDepthStencilState(&initDesc, initState.GetAddressOf());
    UINT first = 0;
    for (int g = 0; g < 4; ++g) {
      UINT count = 0;
      for (UINT i = 0; i < kPixels; ++i) count += CaseOf(i).group == g;
      DrawQuads(init, first, count, initState.Get(), kInitStencil[g], false);
      first += count;
    }
    const std::vector<uint32_t> storedDepth = ReadDepth();
    const std::vector<uint8_t> storedStencil = stencil ? ReadStencil() : std::vector<uint8_t>(kPixels, 0);
    std::vector<std::string> failures;
    // The init pass itself is checked: ALWAYS + REPLACE must leave the group's
    // reference and the quad's depth (D24: within one code of round-to-nearest).
    for (UINT i = 0; i < kPixels; ++i) {
      const uint32_t want = ref::DepthToStored(format_, CaseOf(i).stored);
      const uint32_t diff = want > storedDepth[i] ? want - storedDepth[i] : storedDepth[i] - want;
      if ((stencil && storedStencil[i] != kInitStencil[CaseOf(i).group]) ||
          diff > (format_ == DXGI_FORMAT_D32_FLOAT ? 0u : 1u))
        failures.push_back("init pass: pixel " + std::to_string(i) + " stencil " + std::to_string(storedStencil[i]) +
                           " depth " + std::to_string(storedDepth[i]) + " (want " + std::to_string(want) + ")");
    }

    for (UINT i = 0; i < kPixels; ++i)
      test.push_back({float(i % kW), float(i / kW), CaseOf(i).fragment, CaseOf(i).back ? 1.0f : 0.0f});
    ComPtr<DepthStencilState> state;
    if (desc) gpu_.device()->CreateDepthStencilState(desc, state.GetAddressOf());
    ClearColour();
    DrawQuads(test, 0, kPixels, state.Get(), stencilRef, true);
    const std::vector<uint8_t> colour = ReadColour();
    const std::vector<uint32_t> depthAfter = ReadDepth();
    const std::vector<uint8_t> stencilAfter = stencil ? ReadStencil() : std::vector<uint8_t>(kPixels, 0);

    const DEPTH_STENCIL_DESC nullDesc;  // the D3D11 defaults: LESS, writes on, stencil off
    for (UINT i = 0; i < kPixels; ++i) {
      const Case c = CaseOf(i);
      const ref::DepthStencilOutcome e = ref::DepthStencilResult(desc ? *desc : nullDesc, stencilRef, !c.back,
                                                                 c.fragment, storedDepth[i], storedStencil[i], format_);
      const bool passed = colour[i] == 255;
      const uint32_t dd = e.depth > depthAfter[i] ? e.depth - depthAfter[i] : depthAfter[i] - e.depth;
      const bool depthOk = format_ == DXGI_FORMAT_D32_FLOAT ? dd == 0 : (e.depth == storedDepth[i] ? dd == 0 : dd <= 1);
      if (passed != e.passed || !depthOk || (stencil && stencilAfter[i] != e.stencil)) {
        std::ostringstream s;
        s << conf::FormatName(format_) << " pixel " << i << (c.back ? " back" : " front") << " stored z "
          << std::hex << storedDepth[i] << " s " << int(storedStencil[i]) << " fragment z " << std::dec << c.fragment
          << " ref " << stencilRef << ": expected pass " << e.passed << " z " << std::hex << e.depth << " s "
          << int(e.stencil) << ", got pass " << passed << " z " << depthAfter[i] << " s " << int(stencilAfter[i]);
        failures.push_back(s.str());
      }
    }
    return failures;
  }

 private:
  DXGI_FORMAT format_;
  Gpu gpu_;
  ComPtr<Texture2D> depth_, color_;
  ComPtr<DepthStencilView> dsv_;
  ComPtr<RenderTargetView> rtv_;
  ComPtr<VertexShader> vs_;
  ComPtr<PixelShader> ps_;
  ComPtr<RasterizerState> rs_;
};

constexpr COMPARISON_FUNC kFuncs[8] = {COMPARISON_NEVER,   COMPARISON_LESS,      COMPARISON_EQUAL,
                                       COMPARISON_LESS_EQUAL, COMPARISON_GREATER, COMPARISON_NOT_EQUAL,
                                       COMPARISON_GREATER_EQUAL, COMPARISON_ALWAYS};
constexpr STENCIL_OP kOps[8] = {STENCIL_OP_KEEP,     STENCIL_OP_ZERO,   STENCIL_OP_REPLACE, STENCIL_OP_INCR_SAT,
                                STENCIL_OP_DECR_SAT, STENCIL_OP_INVERT, STENCIL_OP_INCR,    STENCIL_OP_DECR};

void Report(DepthStencil& ds, const std::vector<std::string>& failures, const std::string& what) {
  EXPECT_TRUE(failures.empty()) << what << ": " << failures.size() << " of " << kPixels << " pixels differ";
  for (size_t i = 0; i < failures.size() && i < 5; ++i) ADD_FAILURE() << failures[i];
  for (const std::string& m : ds.gpu().validation()) ADD_FAILURE() << "validation layer: " << m;
  for (const std::string& m : ds.gpu().refusals()) ADD_FAILURE() << "refusal: " << m;
  ds.gpu().ClearMessages();
}

class DepthFormats : public ::testing::TestWithParam<DXGI_FORMAT> {};

TEST_P(DepthFormats, EveryComparisonWithAndWithoutDepthWrites) {
  DepthStencil ds(GetParam());
  for (COMPARISON_FUNC func : kFuncs)
    for (DEPTH_WRITE_MASK mask : {DEPTH_WRITE_MASK_ZERO, DEPTH_WRITE_MASK_ALL}) {
      DEPTH_STENCIL_DESC d;
      d.DepthFunc = func;
      d.DepthWriteMask = mask;
      Report(ds, ds.Run(&d, 0), "DepthFunc " + std::to_string(func) + " mask " + std::to_string(mask));
    }
}

TEST_P(DepthFormats, DepthDisabledPassesAndWritesNothing) {
  DepthStencil ds(GetParam());
  DEPTH_STENCIL_DESC d;
  d.DepthEnable = FALSE;
  d.DepthFunc = COMPARISON_NEVER;
  Report(ds, ds.Run(&d, 0), "DepthEnable FALSE");
}

TEST_P(DepthFormats, NullStateIsLessWithWrites) {
  DepthStencil ds(GetParam());
  Report(ds, ds.Run(nullptr, 0x5A), "NULL depth-stencil state");
}

INSTANTIATE_TEST_SUITE_P(Formats, DepthFormats,
                         ::testing::Values(DXGI_FORMAT_D32_FLOAT, DXGI_FORMAT_D24_UNORM_S8_UINT),
                         [](const ::testing::TestParamInfo<DXGI_FORMAT>& info) {
                           return std::string(conf::FormatName(info.param));
                         });

// Two-sided stencil: over 8 configurations every op appears in every role
// (fail / depth-fail / pass) on each face, every comparison on each face, with
// varied read masks, write masks and reference values.
TEST(Stencil, TwoSidedAllOpsMasksAndReference) {
  DepthStencil ds(DXGI_FORMAT_D24_UNORM_S8_UINT);
  const UINT8 readMasks[8] = {0xFF, 0x0F, 0xF0, 0x3C, 0x81, 0xFF, 0x7E, 0x01};
  const UINT8 writeMasks[8] = {0xFF, 0xF0, 0x0F, 0x55, 0xFF, 0xAA, 0x81, 0x7F};
  const UINT refs[8] = {0x5A, 0x81, 0xFF, 0x00, 0x7E, 0x15A /*low 8 bits used*/, 0x01, 0xA5};
  for (int i = 0; i < 8; ++i) {
    DEPTH_STENCIL_DESC d;
    d.DepthFunc = COMPARISON_LESS_EQUAL;
    d.StencilEnable = TRUE;
    d.StencilReadMask = readMasks[i];
    d.StencilWriteMask = writeMasks[i];
    d.FrontFace = {kOps[i], kOps[(i + 1) % 8], kOps[(i + 2) % 8], kFuncs[i]};
    d.BackFace = {kOps[(i + 3) % 8], kOps[(i + 4) % 8], kOps[(i + 5) % 8], kFuncs[(i + 3) % 8]};
    Report(ds, ds.Run(&d, refs[i]), "stencil configuration " + std::to_string(i));
  }
}

}  // namespace
