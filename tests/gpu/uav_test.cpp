// Unordered access views in graphics passes, as order-independent transparency
// uses them: OMSetRenderTargetsAndUnorderedAccessViews, pixel-shader atomics on
// textures and raw buffers, append/consume and counter buffers with their
// hidden counters, CopyStructureCount, [earlydepthstencil], the hazard rules
// that UAVs add, and the ordering D3D11 guarantees between draws and
// dispatches. Expected values are computed here from the drawn rectangles.
#include <algorithm>
#include <functional>

#include "gpu_helpers.h"
#include "rhi/trace.h"

namespace rhi_test {
namespace {

using namespace rhi;

constexpr UINT kSize = 8;

struct Rect {
  UINT x0, y0, x1, y1;
  bool Covers(UINT x, UINT y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
};

// Overlapping rectangles: pixels are covered 0 to 4 times.
const std::vector<Rect> kRects = {{0, 0, 8, 8}, {2, 1, 6, 7}, {4, 0, 8, 4}, {1, 3, 3, 8}};

// How many of `rects` cover each pixel, row by row.
std::vector<uint32_t> CoverageCounts(const std::vector<Rect>& rects) {
  std::vector<uint32_t> counts(kSize * kSize, 0);
  for (UINT y = 0; y < kSize; ++y)
    for (UINT x = 0; x < kSize; ++x)
      for (const Rect& r : rects) counts[y * kSize + x] += r.Covers(x, y) ? 1 : 0;
  return counts;
}

class UavTest : public RhiGpuTest {
 protected:
  void SetUp() override {
    RhiGpuTest::SetUp();
    if (HasFatalFailure()) return;
    target_ = MakeRenderTarget(kSize, kSize);
    BindTarget(target_.rtv.Get(), kSize, kSize);
    UseColorPipeline();
  }

  // A kSize x kSize R32_UINT texture with a UAV, cleared to `value`.
  struct UintTexture {
    ComPtr<Texture2D> texture;
    ComPtr<UnorderedAccessView> uav;
  };
  UintTexture MakeUintTexture(UINT value) {
    TEXTURE2D_DESC desc{};
    desc.Width = desc.Height = kSize;
    desc.MipLevels = desc.ArraySize = 1;
    desc.Format = DXGI_FORMAT_R32_UINT;
    desc.SampleDesc.Count = 1;
    desc.Usage = USAGE_DEFAULT;
    desc.BindFlags = BIND_UNORDERED_ACCESS | BIND_SHADER_RESOURCE;
    UintTexture t;
    EXPECT_EQ(device->CreateTexture2D(&desc, nullptr, t.texture.GetAddressOf()), S_OK);
    EXPECT_EQ(device->CreateUnorderedAccessView(t.texture.Get(), nullptr, t.uav.GetAddressOf()), S_OK);
    const UINT values[4] = {value, value, value, value};
    context->ClearUnorderedAccessViewUint(t.uav.Get(), values);
    return t;
  }
  std::vector<uint32_t> ReadUints(Texture2D* texture) {
    std::vector<uint8_t> bytes = ReadTexture(texture);
    std::vector<uint32_t> values(bytes.size() / 4);
    std::memcpy(values.data(), bytes.data(), values.size() * 4);
    return values;
  }

  // A structured buffer of `count` elements of `stride` bytes with a UAV of `flags`.
  struct StructuredBuffer {
    ComPtr<Buffer> buffer;
    ComPtr<UnorderedAccessView> uav;
  };
  StructuredBuffer MakeStructured(UINT count, UINT stride, UINT flags, const void* data = nullptr) {
    StructuredBuffer b;
    std::vector<uint8_t> zeros(count * stride, 0);
    b.buffer = MakeBuffer(BIND_UNORDERED_ACCESS | BIND_SHADER_RESOURCE, data ? data : zeros.data(), count * stride,
                          USAGE_DEFAULT, RESOURCE_MISC_BUFFER_STRUCTURED, stride);
    UNORDERED_ACCESS_VIEW_DESC desc{};
    desc.Format = DXGI_FORMAT_UNKNOWN;
    desc.ViewDimension = UAV_DIMENSION_BUFFER;
    desc.Buffer = {0, count, flags};
    EXPECT_EQ(device->CreateUnorderedAccessView(b.buffer.Get(), &desc, b.uav.GetAddressOf()), S_OK);
    return b;
  }
  // A raw (byte address) buffer of `words` zeroed 32-bit words with its UAV.
  StructuredBuffer MakeRaw(UINT words) {
    StructuredBuffer b;
    std::vector<uint32_t> zeros(words, 0);
    b.buffer = MakeBuffer(BIND_UNORDERED_ACCESS, zeros.data(), words * 4, USAGE_DEFAULT,
                          RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS);
    UNORDERED_ACCESS_VIEW_DESC desc{};
    desc.Format = DXGI_FORMAT_R32_TYPELESS;
    desc.ViewDimension = UAV_DIMENSION_BUFFER;
    desc.Buffer = {0, words, BUFFER_UAV_FLAG_RAW};
    EXPECT_EQ(device->CreateUnorderedAccessView(b.buffer.Get(), &desc, b.uav.GetAddressOf()), S_OK);
    return b;
  }

  // Binds render target 0 and `uav` at u1 (with an initial count, -1 keeps it).
  void BindUav(UnorderedAccessView* uav, UINT initialCount = UINT(-1)) {
    RenderTargetView* rtvs[] = {target_.rtv.Get()};
    context->OMSetRenderTargetsAndUnorderedAccessViews(1, rtvs, nullptr, 1, 1, &uav, &initialCount);
  }
  // One draw per rectangle, the rectangle's index in the colour's red channel.
  void DrawRects(const std::vector<Rect>& rects) {
    for (size_t i = 0; i < rects.size(); ++i) {
      const Rect& r = rects[i];
      DrawVertices(Quad(float(r.x0), float(r.y0), float(r.x1), float(r.y1), {float(i), 0, 0, 1}, kSize, kSize));
    }
  }
  // The output merger's render target 0 and UAV `slot`, as OMGetRenderTargetsAndUnorderedAccessViews returns them.
  ComPtr<RenderTargetView> BoundTarget0() {
    RenderTargetView* rtv = nullptr;
    context->OMGetRenderTargetsAndUnorderedAccessViews(1, &rtv, nullptr, 0, 0, nullptr);
    ComPtr<RenderTargetView> held;
    held.Attach(rtv);
    return held;
  }
  ComPtr<UnorderedAccessView> BoundUav(UINT slot) {
    UnorderedAccessView* uav = nullptr;
    context->OMGetRenderTargetsAndUnorderedAccessViews(0, nullptr, nullptr, slot, 1, &uav);
    ComPtr<UnorderedAccessView> held;
    held.Attach(uav);
    return held;
  }
  UINT StructureCount(UnorderedAccessView* uav) {
    const UINT sentinel = 0xdeadbeef;
    ComPtr<Buffer> count = MakeBuffer(0, &sentinel, 4);
    context->CopyStructureCount(count.Get(), 0, uav);
    return ReadBufferAs<uint32_t>(count.Get())[0];
  }
  void Dispatch(const char* source, UnorderedAccessView* uav, UINT groups, UINT initialCount = UINT(-1)) {
    ComPtr<ComputeShader> cs = CS(source);
    context->CSSetShader(cs.Get(), nullptr, 0);
    context->CSSetUnorderedAccessViews(0, 1, &uav, &initialCount);
    context->Dispatch(groups, 1, 1);
  }

  Target target_;
};

// ---------------------------------------------------------------------------
// Pixel-shader atomics

TEST_F(UavTest, InterlockedAddCountsFragmentsPerPixel) {
  UintTexture counts = MakeUintTexture(0);
  BindUav(counts.uav.Get());
  ComPtr<PixelShader> ps = PS(R"(
    RWTexture2D<uint> counts : register(u1);
    float4 main(float4 pos : SV_Position, nointerpolation float4 color : COLOR) : SV_Target {
      InterlockedAdd(counts[uint2(pos.xy)], 1);
      return color;
    })");
  context->PSSetShader(ps.Get(), nullptr, 0);
  DrawRects(kRects);
  EXPECT_EQ(ReadUints(counts.texture.Get()), CoverageCounts(kRects));
}

// One atomic per fragment with the value of the draw's rectangle index + 3;
// D3D11 orders the draws, so even Exchange has one result.
struct AtomicCase {
  const char* name;
  const char* statement;  // on `dest` (a uint lvalue) and `value`
  uint32_t initial;
  std::function<uint32_t(uint32_t, uint32_t)> fold;  // the pixel's new value from the old one and `value`
};

class UavAtomicTest : public UavTest, public ::testing::WithParamInterface<AtomicCase> {};

TEST_P(UavAtomicTest, TextureAtomicMatchesSequentialFold) {
  const AtomicCase& c = GetParam();
  UintTexture values = MakeUintTexture(c.initial);
  BindUav(values.uav.Get());
  ComPtr<PixelShader> ps = PS(std::string(R"(
    RWTexture2D<uint> values : register(u1);
    float4 main(float4 pos : SV_Position, nointerpolation float4 color : COLOR) : SV_Target {
      uint value = uint(color.r) + 3;
      uint old;
      )") + c.statement + R"(
      return color;
    })");
  context->PSSetShader(ps.Get(), nullptr, 0);
  DrawRects(kRects);
  std::vector<uint32_t> expected(kSize * kSize, c.initial);
  for (size_t i = 0; i < kRects.size(); ++i)
    for (UINT y = 0; y < kSize; ++y)
      for (UINT x = 0; x < kSize; ++x)
        if (kRects[i].Covers(x, y)) expected[y * kSize + x] = c.fold(expected[y * kSize + x], uint32_t(i) + 3);
  EXPECT_EQ(ReadUints(values.texture.Get()), expected);
}

INSTANTIATE_TEST_SUITE_P(
    Ops, UavAtomicTest,
    ::testing::Values(
        AtomicCase{"Add", "InterlockedAdd(values[uint2(pos.xy)], value, old);", 100,
                   [](uint32_t a, uint32_t v) { return a + v; }},
        AtomicCase{"Min", "InterlockedMin(values[uint2(pos.xy)], value, old);", 5,
                   [](uint32_t a, uint32_t v) { return std::min(a, v); }},
        AtomicCase{"Max", "InterlockedMax(values[uint2(pos.xy)], value, old);", 4,
                   [](uint32_t a, uint32_t v) { return std::max(a, v); }},
        AtomicCase{"Or", "InterlockedOr(values[uint2(pos.xy)], 1u << value, old);", 1,
                   [](uint32_t a, uint32_t v) { return a | (1u << v); }},
        AtomicCase{"Exchange", "InterlockedExchange(values[uint2(pos.xy)], value, old);", 77,
                   [](uint32_t, uint32_t v) { return v; }},
        // Replaces the initial value only: the first rectangle over a pixel wins.
        AtomicCase{"CompareExchange", "InterlockedCompareExchange(values[uint2(pos.xy)], 9, value, old);", 9,
                   [](uint32_t a, uint32_t v) { return a == 9 ? v : a; }}),
    [](const ::testing::TestParamInfo<AtomicCase>& info) { return std::string(info.param.name); });

TEST_F(UavTest, ByteAddressBufferAtomicsInPixelShader) {
  StructuredBuffer raw = MakeRaw(4);
  BindUav(raw.uav.Get());
  ComPtr<PixelShader> ps = PS(R"(
    RWByteAddressBuffer raw : register(u1);
    float4 main(float4 pos : SV_Position, nointerpolation float4 color : COLOR) : SV_Target {
      uint2 p = uint2(pos.xy);
      raw.InterlockedAdd(0, 1);                       // fragments
      raw.InterlockedMax(4, p.y * 8 + p.x);           // the last pixel index reached
      raw.InterlockedOr(8, 1u << (p.x + 8 * (p.y & 3)));  // rows y and y + 4 share bits
      uint previous;
      raw.InterlockedCompareExchange(12, 0, 1000 + p.y * 8 + p.x, previous);  // one fragment wins
      return color;
    })");
  context->PSSetShader(ps.Get(), nullptr, 0);
  const std::vector<Rect> rects = {{1, 2, 5, 6}, {3, 0, 7, 3}};
  DrawRects(rects);
  uint32_t fragments = 0, lastIndex = 0, bits = 0;
  for (const Rect& r : rects)
    for (UINT y = r.y0; y < r.y1; ++y)
      for (UINT x = r.x0; x < r.x1; ++x) {
        ++fragments;
        lastIndex = std::max(lastIndex, y * 8 + x);
        bits |= 1u << (x + 8 * (y & 3));
      }
  std::vector<uint32_t> words = ReadBufferAs<uint32_t>(raw.buffer.Get());
  EXPECT_EQ(words[0], fragments);
  EXPECT_EQ(words[1], lastIndex);
  EXPECT_EQ(words[2], bits);
  // The first rectangle's fragments come first: one of them won.
  EXPECT_TRUE(words[3] >= 1000 && rects[0].Covers((words[3] - 1000) % 8, (words[3] - 1000) / 8)) << words[3];
}

// Typed UAVs next to each other from u1: a float texture stored to, and a
// typed buffer (a storage texel buffer) counted into.
TEST_F(UavTest, TypedTextureAndBufferUavsInPixelShader) {
  TEXTURE2D_DESC desc{};
  desc.Width = desc.Height = kSize;
  desc.MipLevels = desc.ArraySize = 1;
  desc.Format = DXGI_FORMAT_R32G32B32A32_FLOAT;
  desc.SampleDesc.Count = 1;
  desc.BindFlags = BIND_UNORDERED_ACCESS;
  ComPtr<Texture2D> colors;
  ASSERT_EQ(device->CreateTexture2D(&desc, nullptr, colors.GetAddressOf()), S_OK);
  ComPtr<UnorderedAccessView> colorsUav;
  ASSERT_EQ(device->CreateUnorderedAccessView(colors.Get(), nullptr, colorsUav.GetAddressOf()), S_OK);
  const FLOAT clear[4] = {-1, -1, -1, -1};
  context->ClearUnorderedAccessViewFloat(colorsUav.Get(), clear);
  std::vector<uint32_t> zeros(kSize * kSize, 0);
  ComPtr<Buffer> hits = MakeBuffer(BIND_UNORDERED_ACCESS, zeros.data(), kSize * kSize * 4);
  UNORDERED_ACCESS_VIEW_DESC hitsDesc{};
  hitsDesc.Format = DXGI_FORMAT_R32_UINT;
  hitsDesc.ViewDimension = UAV_DIMENSION_BUFFER;
  hitsDesc.Buffer = {0, kSize * kSize, 0};
  ComPtr<UnorderedAccessView> hitsUav;
  ASSERT_EQ(device->CreateUnorderedAccessView(hits.Get(), &hitsDesc, hitsUav.GetAddressOf()), S_OK);

  RenderTargetView* rtvs[] = {target_.rtv.Get()};
  UnorderedAccessView* uavs[] = {colorsUav.Get(), hitsUav.Get()};
  context->OMSetRenderTargetsAndUnorderedAccessViews(1, rtvs, nullptr, 1, 2, uavs, nullptr);
  ComPtr<PixelShader> ps = PS(R"(
    RWTexture2D<float4> colors : register(u1);
    RWBuffer<uint> hits : register(u2);
    float4 main(float4 pos : SV_Position, nointerpolation float4 color : COLOR) : SV_Target {
      uint2 p = uint2(pos.xy);
      colors[p] = float4(p.x, p.y, color.r, 0.5);
      InterlockedAdd(hits[p.y * 8 + p.x], 1);
      return color;
    })");
  context->PSSetShader(ps.Get(), nullptr, 0);
  DrawRects(kRects);
  EXPECT_EQ(ReadBufferAs<uint32_t>(hits.Get()), CoverageCounts(kRects));
  // Each pixel holds the last rectangle over it (draws are ordered), or the clear value.
  std::vector<uint8_t> bytes = ReadTexture(colors.Get());
  std::vector<float> texels(bytes.size() / 4);
  std::memcpy(texels.data(), bytes.data(), bytes.size());
  for (UINT y = 0; y < kSize; ++y)
    for (UINT x = 0; x < kSize; ++x) {
      std::vector<float> expected = {-1, -1, -1, -1};
      for (size_t i = 0; i < kRects.size(); ++i)
        if (kRects[i].Covers(x, y)) expected = {float(x), float(y), float(i), 0.5f};
      const float* got = &texels[(y * kSize + x) * 4];
      EXPECT_EQ(std::vector<float>(got, got + 4), expected) << x << "," << y;
    }
}

// A pixel shader writes the arguments of the next draw: the indirect draw
// waits for the writes (D3D11 orders them; synchronization validation checks
// the barrier).
TEST_F(UavTest, PixelShaderWritesIndirectArgumentsOfTheNextDraw) {
  std::vector<uint32_t> zeros(4, 0);
  ComPtr<Buffer> args = MakeBuffer(BIND_UNORDERED_ACCESS, zeros.data(), 16, USAGE_DEFAULT,
                                   RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS | RESOURCE_MISC_DRAWINDIRECT_ARGS);
  UNORDERED_ACCESS_VIEW_DESC desc{};
  desc.Format = DXGI_FORMAT_R32_TYPELESS;
  desc.ViewDimension = UAV_DIMENSION_BUFFER;
  desc.Buffer = {0, 4, BUFFER_UAV_FLAG_RAW};
  ComPtr<UnorderedAccessView> uav;
  ASSERT_EQ(device->CreateUnorderedAccessView(args.Get(), &desc, uav.GetAddressOf()), S_OK);
  BindUav(uav.Get());
  ComPtr<PixelShader> writer = PS(R"(
    RWByteAddressBuffer args : register(u1);
    float4 main(float4 pos : SV_Position, nointerpolation float4 color : COLOR) : SV_Target {
      args.InterlockedAdd(0, 1u);  // VertexCountPerInstance: one per fragment
      args.InterlockedMax(4, 1u);  // InstanceCount
      return color;
    })");
  context->PSSetShader(writer.Get(), nullptr, 0);
  DrawRects({{0, 0, 3, 1}});  // 3 fragments: a 3-vertex draw

  BindTarget(target_.rtv.Get(), kSize, kSize);
  ComPtr<VertexShader> vs = VS(R"(float4 main(uint id : SV_VertexID) : SV_Position {
      return float4(id == 1 ? 3 : -1, id == 2 ? -3 : 1, 0.5, 1); })");
  ComPtr<PixelShader> green = PS("float4 main() : SV_Target { return float4(0, 1, 0, 1); }");
  context->IASetInputLayout(nullptr);
  context->VSSetShader(vs.Get(), nullptr, 0);
  context->PSSetShader(green.Get(), nullptr, 0);
  context->DrawInstancedIndirect(args.Get(), 0);
  EXPECT_EQ(CountPixels(ReadTexture(target_.texture.Get()), kGreenPx), int(kSize * kSize));
  EXPECT_EQ(ReadBufferAs<uint32_t>(args.Get()), (std::vector<uint32_t>{3, 1, 0, 0}));
}

// ---------------------------------------------------------------------------
// Hidden counters

// The linked-list / fragment-buffer pattern: one element per fragment.
TEST_F(UavTest, AppendBufferCollectsOneElementPerFragment) {
  const std::vector<uint32_t> coverage = CoverageCounts(kRects);
  uint32_t fragments = 0;
  for (uint32_t c : coverage) fragments += c;
  StructuredBuffer list = MakeStructured(fragments + 4, 8, BUFFER_UAV_FLAG_APPEND);
  BindUav(list.uav.Get(), 0);
  ComPtr<PixelShader> ps = PS(R"(
    AppendStructuredBuffer<uint2> fragments : register(u1);
    float4 main(float4 pos : SV_Position, nointerpolation float4 color : COLOR) : SV_Target {
      uint2 p = uint2(pos.xy);
      fragments.Append(uint2(p.y * 8 + p.x, uint(color.r)));
      return color;
    })");
  context->PSSetShader(ps.Get(), nullptr, 0);
  DrawRects(kRects);
  EXPECT_EQ(StructureCount(list.uav.Get()), fragments);

  std::vector<std::pair<uint32_t, uint32_t>> expected, stored;
  for (size_t i = 0; i < kRects.size(); ++i)
    for (UINT y = 0; y < kSize; ++y)
      for (UINT x = 0; x < kSize; ++x)
        if (kRects[i].Covers(x, y)) expected.push_back({y * kSize + x, uint32_t(i)});
  std::vector<uint32_t> words = ReadBufferAs<uint32_t>(list.buffer.Get());
  for (uint32_t i = 0; i < fragments; ++i) stored.push_back({words[2 * i], words[2 * i + 1]});
  std::sort(expected.begin(), expected.end());
  std::sort(stored.begin(), stored.end());
  EXPECT_EQ(stored, expected);
  // Nothing was appended past the count.
  for (uint32_t i = 2 * fragments; i < words.size(); ++i) EXPECT_EQ(words[i], 0u) << i;
}

// pUAVInitialCounts sets the count; -1 keeps what the last draw left.
TEST_F(UavTest, InitialCountsSetAndKeepTheHiddenCounter) {
  StructuredBuffer list = MakeStructured(64, 4, BUFFER_UAV_FLAG_APPEND);
  ComPtr<PixelShader> ps = PS(R"(
    AppendStructuredBuffer<uint> fragments : register(u1);
    float4 main(float4 pos : SV_Position, nointerpolation float4 color : COLOR) : SV_Target {
      fragments.Append(7);
      return color;
    })");
  context->PSSetShader(ps.Get(), nullptr, 0);
  BindUav(list.uav.Get(), 5);
  EXPECT_EQ(StructureCount(list.uav.Get()), 5u);
  DrawRects({{0, 0, 2, 2}});
  EXPECT_EQ(StructureCount(list.uav.Get()), 9u);
  BindUav(list.uav.Get(), UINT(-1));
  DrawRects({{0, 0, 3, 1}});
  EXPECT_EQ(StructureCount(list.uav.Get()), 12u);
  // Elements 5..11 were appended; 0..4 were skipped by the initial count.
  std::vector<uint32_t> words = ReadBufferAs<uint32_t>(list.buffer.Get());
  for (UINT i = 0; i < 12; ++i) EXPECT_EQ(words[i], i < 5 ? 0u : 7u) << i;
}

TEST_F(UavTest, ConsumeTakesElementsFromTheTop) {
  std::vector<uint32_t> values(16);
  for (uint32_t i = 0; i < 16; ++i) values[i] = 100 + i;
  StructuredBuffer stack = MakeStructured(16, 4, BUFFER_UAV_FLAG_APPEND, values.data());
  StructuredBuffer taken = MakeStructured(16, 4, 0);
  ComPtr<ComputeShader> cs = CS(R"(
    ConsumeStructuredBuffer<uint> stack : register(u0);
    RWStructuredBuffer<uint> taken : register(u1);
    [numthreads(10, 1, 1)] void main(uint i : SV_GroupIndex) { taken[i] = stack.Consume(); })");
  context->CSSetShader(cs.Get(), nullptr, 0);
  UnorderedAccessView* uavs[] = {stack.uav.Get(), taken.uav.Get()};
  const UINT counts[] = {16, UINT(-1)};
  context->CSSetUnorderedAccessViews(0, 2, uavs, counts);
  context->Dispatch(1, 1, 1);
  EXPECT_EQ(StructureCount(stack.uav.Get()), 6u);
  std::vector<uint32_t> got = ReadBufferAs<uint32_t>(taken.buffer.Get());
  got.resize(10);
  std::sort(got.begin(), got.end());
  std::vector<uint32_t> expected(values.begin() + 6, values.end());
  EXPECT_EQ(got, expected);
}

TEST_F(UavTest, IncrementAndDecrementCounter) {
  StructuredBuffer slots = MakeStructured(64, 4, BUFFER_UAV_FLAG_COUNTER);
  Dispatch(R"(
    RWStructuredBuffer<uint> slots : register(u0);
    [numthreads(64, 1, 1)] void main(uint i : SV_GroupIndex) { slots[slots.IncrementCounter()] += 1; })",
           slots.uav.Get(), 1, 0);
  EXPECT_EQ(StructureCount(slots.uav.Get()), 64u);
  // Each of the 64 threads got its own slot.
  EXPECT_EQ(ReadBufferAs<uint32_t>(slots.buffer.Get()), std::vector<uint32_t>(64, 1));
  // DecrementCounter returns the count after the decrement: slots 48..63.
  Dispatch(R"(
    RWStructuredBuffer<uint> slots : register(u0);
    [numthreads(16, 1, 1)] void main() { slots[slots.DecrementCounter()] += 10; })",
           slots.uav.Get(), 1);
  EXPECT_EQ(StructureCount(slots.uav.Get()), 48u);
  std::vector<uint32_t> expected(64, 1);
  std::fill(expected.begin() + 48, expected.end(), 11);
  EXPECT_EQ(ReadBufferAs<uint32_t>(slots.buffer.Get()), expected);
}

// D3D11's debug layer reports the draw and runs it; the counter reads 0.
TEST_F(UavTest, CounterUseThroughAViewWithoutOneIsReported) {
  StructuredBuffer plain = MakeStructured(4, 4, 0);
  BindUav(plain.uav.Get());
  ComPtr<PixelShader> ps = PS(R"(
    AppendStructuredBuffer<uint> fragments : register(u1);
    float4 main(float4 pos : SV_Position, nointerpolation float4 color : COLOR) : SV_Target {
      fragments.Append(5);
      return color;
    })");
  context->PSSetShader(ps.Get(), nullptr, 0);
  DrawRects({{0, 0, 2, 1}});
  EXPECT_TRUE(RefusedWith("Draw: the shader uses the hidden counter of UAV u1 (Append, Consume, IncrementCounter, "
                          "DecrementCounter), but that view was created without BUFFER_UAV_FLAG_APPEND"));
}

// glslang drops a UAV used only through its counter, so its register is lost.
TEST_F(UavTest, CounterOnlyUseIsRefusedWithTheReason) {
  std::vector<uint32_t> code = CompileHlsl(R"(
    RWStructuredBuffer<uint> slots : register(u0);
    [numthreads(16, 1, 1)] void main() { slots.DecrementCounter(); })",
                                           "main", "cs_5_0");
  ComPtr<ComputeShader> cs;
  EXPECT_EQ(device->CreateComputeShader(code.data(), code.size() * 4, nullptr, cs.GetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("CreateComputeShader: the hidden counter 'slots@count' is not linked to its UAV"));
}

// Order-independent transparency with per-pixel linked lists, end to end:
// the build pass links one node per fragment (IncrementCounter for the node,
// InterlockedExchange on the pixel's head), the resolve pass reads the lists
// as shader resources, sorts each by depth and blends back to front. Colours
// and alpha 0.5 keep every blend exact, so the CPU reference matches bit for bit.
TEST_F(UavTest, PerPixelLinkedListsResolveToTheSortedBlend) {
  struct Layer {
    Rect rect;
    float depth;
    Color color;
  };
  // Drawn in this order, which is not the depth order.
  const std::vector<Layer> layers = {{{0, 0, 6, 6}, 0.5f, {1, 0, 0, 0.5f}},
                                     {{2, 2, 8, 8}, 0.25f, {0, 1, 0, 0.5f}},
                                     {{1, 3, 7, 5}, 0.75f, {0, 0, 1, 0.5f}},
                                     {{4, 0, 8, 4}, 0.125f, {1, 1, 1, 0.5f}}};
  UintTexture heads = MakeUintTexture(0xffffffffu);
  StructuredBuffer nodes = MakeStructured(kSize * kSize * 4, 24, BUFFER_UAV_FLAG_COUNTER);
  RenderTargetView* rtvs[] = {target_.rtv.Get()};
  UnorderedAccessView* uavs[] = {heads.uav.Get(), nodes.uav.Get()};
  const UINT counts[] = {UINT(-1), 0};
  context->OMSetRenderTargetsAndUnorderedAccessViews(1, rtvs, nullptr, 1, 2, uavs, counts);
  ComPtr<PixelShader> build = PS(R"(
    struct Node { float4 color; float depth; uint next; };
    RWTexture2D<uint> heads : register(u1);
    RWStructuredBuffer<Node> nodes : register(u2);
    float4 main(float4 pos : SV_Position, nointerpolation float4 color : COLOR) : SV_Target {
      uint node = nodes.IncrementCounter();
      uint next;
      InterlockedExchange(heads[uint2(pos.xy)], node, next);
      Node n; n.color = color; n.depth = pos.z; n.next = next;
      nodes[node] = n;
      return color;
    })");
  context->PSSetShader(build.Get(), nullptr, 0);
  for (const Layer& l : layers)
    DrawVertices(Quad(float(l.rect.x0), float(l.rect.y0), float(l.rect.x1), float(l.rect.y1), l.color, kSize, kSize,
                      l.depth));

  Target resolved = MakeRenderTarget(kSize, kSize, DXGI_FORMAT_R32G32B32A32_FLOAT);
  BindTarget(resolved.rtv.Get(), kSize, kSize);  // unbinds the UAVs
  ComPtr<ShaderResourceView> headsSrv, nodesSrv;
  ASSERT_EQ(device->CreateShaderResourceView(heads.texture.Get(), nullptr, headsSrv.GetAddressOf()), S_OK);
  ASSERT_EQ(device->CreateShaderResourceView(nodes.buffer.Get(), nullptr, nodesSrv.GetAddressOf()), S_OK);
  ShaderResourceView* srvs[] = {headsSrv.Get(), nodesSrv.Get()};
  context->PSSetShaderResources(0, 2, srvs);
  ComPtr<VertexShader> fullScreen = VS(R"(float4 main(uint id : SV_VertexID) : SV_Position {
      return float4(id == 1 ? 3 : -1, id == 2 ? -3 : 1, 0.5, 1); })");
  ComPtr<PixelShader> resolve = PS(R"(
    struct Node { float4 color; float depth; uint next; };
    Texture2D<uint> heads : register(t0);
    StructuredBuffer<Node> nodes : register(t1);
    float4 main(float4 pos : SV_Position) : SV_Target {
      Node list[8];
      uint count = 0;
      for (uint at = heads.Load(int3(pos.xy, 0)); at != 0xffffffff && count < 8; at = nodes[at].next)
        list[count++] = nodes[at];
      for (uint i = 1; i < count; ++i)  // insertion sort, farthest first
        for (uint j = i; j > 0 && list[j - 1].depth < list[j].depth; --j) {
          Node t = list[j]; list[j] = list[j - 1]; list[j - 1] = t;
        }
      float3 c = float3(0, 0, 0);
      for (uint k = 0; k < count; ++k) c = c * (1 - list[k].color.a) + list[k].color.rgb * list[k].color.a;
      return float4(c, count);
    })");
  context->IASetInputLayout(nullptr);
  context->VSSetShader(fullScreen.Get(), nullptr, 0);
  context->PSSetShader(resolve.Get(), nullptr, 0);
  context->Draw(3, 0);

  std::vector<uint8_t> bytes = ReadTexture(resolved.texture.Get());
  std::vector<float> texels(bytes.size() / 4);
  std::memcpy(texels.data(), bytes.data(), bytes.size());
  for (UINT y = 0; y < kSize; ++y)
    for (UINT x = 0; x < kSize; ++x) {
      std::vector<Layer> over;
      for (const Layer& l : layers)
        if (l.rect.Covers(x, y)) over.push_back(l);
      std::sort(over.begin(), over.end(), [](const Layer& a, const Layer& b) { return a.depth > b.depth; });
      std::vector<float> expected = {0, 0, 0, float(over.size())};
      for (const Layer& l : over) {
        expected[0] = expected[0] * (1 - l.color.a) + l.color.r * l.color.a;
        expected[1] = expected[1] * (1 - l.color.a) + l.color.g * l.color.a;
        expected[2] = expected[2] * (1 - l.color.a) + l.color.b * l.color.a;
      }
      const float* got = &texels[(y * kSize + x) * 4];
      EXPECT_EQ(std::vector<float>(got, got + 4), expected) << x << "," << y;
    }
}

// ---------------------------------------------------------------------------
// [earlydepthstencil]

// A near quad over the left half; then a far quad over everything whose PS
// counts its invocations. With early tests the hidden half never runs the PS;
// without them the PS runs (its UAV write is a side effect) and the late test
// discards only its colour.
class EarlyDepthTest : public UavTest, public ::testing::WithParamInterface<bool> {};

TEST_P(EarlyDepthTest, FailingFragmentsRunThePixelShaderOnlyWithoutEarlyTests) {
  const bool early = GetParam();
  DepthTarget depth = MakeDepthTarget(kSize, kSize, DXGI_FORMAT_D32_FLOAT);
  context->ClearDepthStencilView(depth.dsv.Get(), CLEAR_DEPTH, 1.0f, 0);
  StructuredBuffer invocations = MakeRaw(1);
  RenderTargetView* rtvs[] = {target_.rtv.Get()};
  UnorderedAccessView* uavs[] = {invocations.uav.Get()};
  context->OMSetRenderTargetsAndUnorderedAccessViews(1, rtvs, depth.dsv.Get(), 1, 1, uavs, nullptr);
  DrawVertices(Quad(0, 0, 4, kSize, kRed, kSize, kSize, 0.2f));
  ComPtr<PixelShader> ps = PS(std::string(R"(
    RWByteAddressBuffer invocations : register(u1);
    )") + (early ? "[earlydepthstencil]" : "") + R"(
    float4 main(float4 pos : SV_Position, nointerpolation float4 color : COLOR) : SV_Target {
      invocations.InterlockedAdd(0, 1u);
      return color;
    })");
  context->PSSetShader(ps.Get(), nullptr, 0);
  DrawVertices(Quad(0, 0, kSize, kSize, kGreen, kSize, kSize, 0.8f));
  EXPECT_EQ(ReadBufferAs<uint32_t>(invocations.buffer.Get())[0], early ? 32u : 64u);
  // Either way the depth test kept the near quad's colour.
  EXPECT_EQ(CountPixels(ReadTexture(target_.texture.Get()), kRedPx), 32);
}

INSTANTIATE_TEST_SUITE_P(Attribute, EarlyDepthTest, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& info) {
                           return info.param ? "EarlyDepthStencil" : "LateDepthTest";
                         });

// ---------------------------------------------------------------------------
// Ordering: a UAV write is visible to the next draw or dispatch

// The PS writes each pixel's index into a structured buffer; a compute shader
// then reads the buffer as an SRV. Without the backend's barrier the dispatch
// could read before the draw's writes land, and synchronization validation
// (on in every GPU test) reports the hazard.
TEST_F(UavTest, PixelShaderWritesAreVisibleToTheNextDispatch) {
  StructuredBuffer written = MakeStructured(kSize * kSize, 4, 0);
  BindUav(written.uav.Get());
  ComPtr<PixelShader> ps = PS(R"(
    RWStructuredBuffer<uint> written : register(u1);
    float4 main(float4 pos : SV_Position, nointerpolation float4 color : COLOR) : SV_Target {
      uint2 p = uint2(pos.xy);
      written[p.y * 8 + p.x] = p.y * 8 + p.x + 1;
      return color;
    })");
  context->PSSetShader(ps.Get(), nullptr, 0);
  DrawRects({{0, 0, kSize, kSize}});

  // D3D11: the buffer leaves the output merger before it can be read.
  BindTarget(target_.rtv.Get(), kSize, kSize);
  ComPtr<ShaderResourceView> srv;
  ASSERT_EQ(device->CreateShaderResourceView(written.buffer.Get(), nullptr, srv.GetAddressOf()), S_OK);
  StructuredBuffer doubled = MakeStructured(kSize * kSize, 4, 0);
  ComPtr<ComputeShader> cs = CS(R"(
    StructuredBuffer<uint> written : register(t0);
    RWStructuredBuffer<uint> doubled : register(u0);
    [numthreads(64, 1, 1)] void main(uint i : SV_GroupIndex) { doubled[i] = written[i] * 2; })");
  context->CSSetShader(cs.Get(), nullptr, 0);
  ShaderResourceView* srvs[] = {srv.Get()};
  context->CSSetShaderResources(0, 1, srvs);
  UnorderedAccessView* uavs[] = {doubled.uav.Get()};
  context->CSSetUnorderedAccessViews(0, 1, uavs, nullptr);
  context->Dispatch(1, 1, 1);
  std::vector<uint32_t> expected(kSize * kSize);
  for (uint32_t i = 0; i < expected.size(); ++i) expected[i] = (i + 1) * 2;
  EXPECT_EQ(ReadBufferAs<uint32_t>(doubled.buffer.Get()), expected);
  EXPECT_TRUE(Refusals().empty()) << Refusals().front();
}

// ---------------------------------------------------------------------------
// Binding rules

TEST_F(UavTest, KeepConstantsLeaveTheOtherBindingsAlone) {
  UintTexture counts = MakeUintTexture(0);
  UnorderedAccessView* uav = counts.uav.Get();
  context->OMSetRenderTargetsAndUnorderedAccessViews(KEEP_RENDER_TARGETS_AND_DEPTH_STENCIL, nullptr, nullptr, 1, 1,
                                                     &uav, nullptr);
  EXPECT_EQ(BoundTarget0().Get(), target_.rtv.Get()) << "KEEP_RENDER_TARGETS_AND_DEPTH_STENCIL kept RT0";
  EXPECT_EQ(BoundUav(0).Get(), nullptr);
  EXPECT_EQ(BoundUav(1).Get(), uav);

  Target other = MakeRenderTarget(kSize, kSize);
  RenderTargetView* rtvs[] = {other.rtv.Get()};
  context->OMSetRenderTargetsAndUnorderedAccessViews(1, rtvs, nullptr, 0, KEEP_UNORDERED_ACCESS_VIEWS, nullptr,
                                                     nullptr);
  EXPECT_EQ(BoundTarget0().Get(), other.rtv.Get());
  EXPECT_EQ(BoundUav(1).Get(), uav) << "KEEP_UNORDERED_ACCESS_VIEWS kept u1";

  // Plain OMSetRenderTargets binds no UAVs (D3D11: NumUAVs 0).
  context->OMSetRenderTargets(1, rtvs, nullptr);
  EXPECT_EQ(BoundUav(1).Get(), nullptr);
  EXPECT_TRUE(Refusals().empty()) << Refusals().front();
}

// Arguments D3D11's debug layer rejects; the call is ignored and the bound
// views stay as they were.
struct OutputMergerCase {
  const char* name;
  UINT numRtvs, uavStart, numUavs;
  bool uavIsRenderTarget;  // bind a UAV of render target 0's texture
  const char* reason;
};

// An RGBA8 texture bound both as a render target and as a UAV, with a view of each.
void MakeTargetAndUav(rhi::Device* device, ComPtr<RenderTargetView>* rtv, ComPtr<UnorderedAccessView>* uav) {
  TEXTURE2D_DESC desc{};
  desc.Width = desc.Height = kSize;
  desc.MipLevels = desc.ArraySize = 1;
  desc.Format = DXGI_FORMAT_R8G8B8A8_UNORM;
  desc.SampleDesc.Count = 1;
  desc.BindFlags = BIND_RENDER_TARGET | BIND_UNORDERED_ACCESS;
  ComPtr<Texture2D> both;
  ASSERT_EQ(device->CreateTexture2D(&desc, nullptr, both.GetAddressOf()), S_OK);
  ASSERT_EQ(device->CreateRenderTargetView(both.Get(), nullptr, rtv->GetAddressOf()), S_OK);
  ASSERT_EQ(device->CreateUnorderedAccessView(both.Get(), nullptr, uav->GetAddressOf()), S_OK);
}

class OutputMergerRefusalTest : public UavTest, public ::testing::WithParamInterface<OutputMergerCase> {};

TEST_P(OutputMergerRefusalTest, IsRefusedWithTheReason) {
  const OutputMergerCase& c = GetParam();
  ComPtr<RenderTargetView> bothRtv;
  ComPtr<UnorderedAccessView> bothUav;
  ASSERT_NO_FATAL_FAILURE(MakeTargetAndUav(device.Get(), &bothRtv, &bothUav));
  UintTexture counts = MakeUintTexture(0);

  RenderTargetView* rtvs[8] = {bothRtv.Get()};
  std::vector<UnorderedAccessView*> uavs(8, counts.uav.Get());
  if (c.uavIsRenderTarget) uavs[0] = bothUav.Get();
  ClearMessages();
  context->OMSetRenderTargetsAndUnorderedAccessViews(c.numRtvs, rtvs, nullptr, c.uavStart, c.numUavs, uavs.data(),
                                                     nullptr);
  EXPECT_TRUE(RefusedWith(c.reason)) << (Refusals().empty() ? "no refusal" : Refusals().front());
  EXPECT_EQ(BoundTarget0().Get(), target_.rtv.Get()) << "the refused call changed render target 0";
  EXPECT_EQ(BoundUav(c.uavStart % 8).Get(), nullptr) << "the refused call bound a UAV";
}

INSTANTIATE_TEST_SUITE_P(
    Cases, OutputMergerRefusalTest,
    ::testing::Values(
        OutputMergerCase{"UavOverlapsRenderTarget", 2, 1, 1, false, "UAVStartSlot (1) must be at least NumRTVs (2)"},
        OutputMergerCase{"UavAtSlotZeroWithOneTarget", 1, 0, 2, false, "UAVStartSlot (0) must be at least NumRTVs (1)"},
        OutputMergerCase{"PastSlotSeven", 1, 4, 5, false, "UAVStartSlot (4) + NumUAVs (5) exceeds the 8 UAV slots"},
        OutputMergerCase{"TooManyTargets", 9, 9, 0, false, "NumRTVs (9) exceeds SIMULTANEOUS_RENDER_TARGET_COUNT"},
        OutputMergerCase{"SameResourceAsTargetAndUav", 1, 1, 1, true,
                         "a resource cannot be a render target and an unordered access view at once"}),
    [](const ::testing::TestParamInfo<OutputMergerCase>& info) { return std::string(info.param.name); });

// The views a call keeps meet the rules too: new render targets may neither
// reach a kept UAV's slot nor be a kept UAV's resource.
TEST_F(UavTest, KeptViewsAreCheckedAgainstNewOnes) {
  ComPtr<RenderTargetView> bothRtv;
  ComPtr<UnorderedAccessView> bothUav;
  ASSERT_NO_FATAL_FAILURE(MakeTargetAndUav(device.Get(), &bothRtv, &bothUav));
  BindUav(bothUav.Get());

  RenderTargetView* two[] = {target_.rtv.Get(), nullptr};
  context->OMSetRenderTargetsAndUnorderedAccessViews(2, two, nullptr, 0, KEEP_UNORDERED_ACCESS_VIEWS, nullptr, nullptr);
  EXPECT_TRUE(RefusedWith("UAVStartSlot (1) must be at least NumRTVs (2)"));
  RenderTargetView* same[] = {bothRtv.Get()};
  context->OMSetRenderTargetsAndUnorderedAccessViews(1, same, nullptr, 0, KEEP_UNORDERED_ACCESS_VIEWS, nullptr, nullptr);
  EXPECT_TRUE(RefusedWith("the resource of UAV slot 1 is also render target 0"));
  EXPECT_EQ(BoundTarget0().Get(), target_.rtv.Get());
  EXPECT_EQ(BoundUav(1).Get(), bothUav.Get());
}

TEST_F(UavTest, BindingAUavUnbindsItsResourceFromShaderResourceSlots) {
  StructuredBuffer buffer = MakeStructured(4, 4, 0);
  ComPtr<ShaderResourceView> srv;
  ASSERT_EQ(device->CreateShaderResourceView(buffer.buffer.Get(), nullptr, srv.GetAddressOf()), S_OK);
  ShaderResourceView* srvs[] = {srv.Get()};
  context->VSSetShaderResources(2, 1, srvs);
  context->PSSetShaderResources(0, 1, srvs);
  BindUav(buffer.uav.Get());
  EXPECT_TRUE(RefusedWith("OMSetRenderTargetsAndUnorderedAccessViews: the resource being bound for output is still bound on input; forcing VS shader resource slot 2 to NULL"));
  EXPECT_TRUE(RefusedWith("OMSetRenderTargetsAndUnorderedAccessViews: the resource being bound for output is still bound on input; forcing PS shader resource slot 0 to NULL"));
  // While it is a UAV, an SRV of it binds NULL, with the warning.
  ClearMessages();
  context->PSSetShaderResources(3, 1, srvs);
  EXPECT_TRUE(RefusedWith("PSSetShaderResources: the resource of shader resource slot 3 is bound as an unordered access view"));
  // The compute stage takes the UAV away from the output merger.
  context->CSSetUnorderedAccessViews(0, 1, buffer.uav.GetAddressOf(), nullptr);
  EXPECT_EQ(BoundUav(1).Get(), nullptr);
}

TEST_F(UavTest, UnboundShaderResourceReadsZeroAfterUavBinding) {
  std::vector<uint32_t> ones(kSize * kSize, 1);
  StructuredBuffer buffer = MakeStructured(kSize * kSize, 4, 0, ones.data());
  ComPtr<ShaderResourceView> srv;
  ASSERT_EQ(device->CreateShaderResourceView(buffer.buffer.Get(), nullptr, srv.GetAddressOf()), S_OK);
  StructuredBuffer out = MakeStructured(kSize * kSize, 4, 0);
  ComPtr<ComputeShader> cs = CS(R"(
    StructuredBuffer<uint> input : register(t0);
    RWStructuredBuffer<uint> output : register(u0);
    [numthreads(64, 1, 1)] void main(uint i : SV_GroupIndex) { output[i] = input[i] + 5; })");
  context->CSSetShader(cs.Get(), nullptr, 0);
  ShaderResourceView* srvs[] = {srv.Get()};
  context->CSSetShaderResources(0, 1, srvs);
  BindUav(buffer.uav.Get());  // t0's buffer becomes an OM UAV: t0 is NULL and reads 0
  context->CSSetUnorderedAccessViews(0, 1, out.uav.GetAddressOf(), nullptr);
  context->Dispatch(1, 1, 1);
  EXPECT_EQ(ReadBufferAs<uint32_t>(out.buffer.Get()), std::vector<uint32_t>(kSize * kSize, 5));
}

// ---------------------------------------------------------------------------
// Refusals of counters and CopyStructureCount

TEST_F(UavTest, CounterFlagsNeedAStructuredBuffer) {
  ComPtr<Buffer> typed = MakeBuffer(BIND_UNORDERED_ACCESS, nullptr, 64);
  UNORDERED_ACCESS_VIEW_DESC desc{};
  desc.Format = DXGI_FORMAT_R32_UINT;
  desc.ViewDimension = UAV_DIMENSION_BUFFER;
  desc.Buffer = {0, 16, BUFFER_UAV_FLAG_APPEND};
  ComPtr<UnorderedAccessView> uav;
  EXPECT_EQ(device->CreateUnorderedAccessView(typed.Get(), &desc, uav.GetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("BUFFER_UAV_FLAG_APPEND needs a structured buffer"));
  desc.Buffer.Flags = BUFFER_UAV_FLAG_COUNTER;
  EXPECT_EQ(device->CreateUnorderedAccessView(typed.Get(), &desc, uav.GetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("BUFFER_UAV_FLAG_COUNTER needs a structured buffer"));

  ComPtr<Buffer> structured =
      MakeBuffer(BIND_UNORDERED_ACCESS, nullptr, 64, USAGE_DEFAULT, RESOURCE_MISC_BUFFER_STRUCTURED, 4);
  desc.Format = DXGI_FORMAT_UNKNOWN;
  desc.Buffer.Flags = BUFFER_UAV_FLAG_APPEND | BUFFER_UAV_FLAG_COUNTER;
  EXPECT_EQ(device->CreateUnorderedAccessView(structured.Get(), &desc, uav.GetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("BUFFER_UAV_FLAG_APPEND and BUFFER_UAV_FLAG_COUNTER exclude each other"));
}

TEST_F(UavTest, CopyStructureCountRefusals) {
  StructuredBuffer plain = MakeStructured(4, 4, 0);
  StructuredBuffer counted = MakeStructured(4, 4, BUFFER_UAV_FLAG_COUNTER);
  const UINT sentinel[2] = {11, 22};
  ComPtr<Buffer> dst = MakeBuffer(0, sentinel, 8);
  context->CopyStructureCount(dst.Get(), 0, plain.uav.Get());
  EXPECT_TRUE(RefusedWith("CopyStructureCount: pSrcView has no hidden counter"));
  context->CopyStructureCount(dst.Get(), 2, counted.uav.Get());
  EXPECT_TRUE(RefusedWith("CopyStructureCount: DstAlignedByteOffset (2) must be a multiple of 4"));
  context->CopyStructureCount(dst.Get(), 8, counted.uav.Get());
  EXPECT_TRUE(RefusedWith("CopyStructureCount: DstAlignedByteOffset (8) must be a multiple of 4 with 4 bytes"));
  EXPECT_EQ(ReadBufferAs<uint32_t>(dst.Get()), (std::vector<uint32_t>{11, 22})) << "a refused copy wrote";
  context->CopyStructureCount(dst.Get(), 4, counted.uav.Get());
  EXPECT_EQ(ReadBufferAs<uint32_t>(dst.Get()), (std::vector<uint32_t>{11, 0})) << "a new counter counts from 0";
}

// rhi/trace.h records the new calls and forwards them unchanged.
TEST_F(UavTest, TracingContextRecordsAndForwardsTheUavCalls) {
  Trace trace;
  ComPtr<DeviceContext> traced;
  ASSERT_EQ(CreateTracingContext(context.Get(), &trace, traced.GetAddressOf()), S_OK);
  StructuredBuffer list = MakeStructured(4, 4, BUFFER_UAV_FLAG_APPEND);
  UnorderedAccessView* uavs[] = {list.uav.Get()};
  const UINT counts[] = {3};
  traced->OMSetRenderTargetsAndUnorderedAccessViews(KEEP_RENDER_TARGETS_AND_DEPTH_STENCIL, nullptr, nullptr, 2, 1,
                                                    uavs, counts);
  const UINT sentinel = 0;
  ComPtr<Buffer> count = MakeBuffer(0, &sentinel, 4);
  traced->CopyStructureCount(count.Get(), 0, list.uav.Get());
  EXPECT_EQ(trace.Filter({"OMSetRenderTargetsAndUnorderedAccessViews", "CopyStructureCount"}),
            (std::vector<std::string>{"OMSetRenderTargetsAndUnorderedAccessViews(-1, null, 2, 1, obj/3)",
                                      "CopyStructureCount(obj, 0, obj)"}));
  EXPECT_EQ(ReadBufferAs<uint32_t>(count.Get())[0], 3u);
  EXPECT_EQ(BoundUav(2).Get(), list.uav.Get());
}

}  // namespace
}  // namespace rhi_test
