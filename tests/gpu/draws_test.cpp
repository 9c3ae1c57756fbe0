// Every draw and dispatch kind, with exact expected pixels / buffer words.
//
// Coverage follows D3D11 rasterization: pixel centres at (x + .5, y + .5); a
// centre exactly on an edge is inside only for a top or left edge. Quads whose
// edges lie on integer pixel coordinates cover exactly the pixels between them.
#include <cstring>

#include "gpu_helpers.h"

namespace rhi_test {
namespace {

using namespace rhi;

class DrawTest : public RhiGpuTest {};

TEST_F(DrawTest, DrawFullScreenTriangleCoversEveryPixelWithExactUnormColor) {
  Target target = MakeRenderTarget(8, 8);
  BindTarget(target.rtv.Get(), 8, 8);
  Clear(target.rtv.Get(), kBlack);
  // Vertices (-1,1), (3,1), (-1,-3): clockwise on screen, so the default
  // rasterizer state (CULL_BACK, FrontCounterClockwise FALSE) keeps it.
  auto vs = VS(R"(float4 main(uint id : SV_VertexID) : SV_Position {
      return float4(float(id & 1) * 4 - 1, 1 - float(id & 2) * 2, 0.5, 1); })");
  // 1 -> 255, 0.25 -> 63.75 -> 64, 0 -> 0. 0.5 -> 127.5 lies exactly between two
  // codes: D3D11 allows 0.6 ULP in float -> UNORM conversion (FS 3.2.3.6), so
  // 127 (NVIDIA) and 128 (lavapipe) both conform.
  auto ps = PS("float4 main() : SV_Target { return float4(1, 0.5, 0.25, 0); }");
  context->VSSetShader(vs.Get(), nullptr, 0);
  context->PSSetShader(ps.Get(), nullptr, 0);
  context->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  context->Draw(3, 0);
  auto pixels = ReadTexture(target.texture.Get());
  EXPECT_EQ(CountPixels(pixels, RGBA(255, 128, 64, 0)) + CountPixels(pixels, RGBA(255, 127, 64, 0)), 64);
}

TEST_F(DrawTest, TopLeftRuleIncludesCentresOnLeftAndTopEdgesOnly) {
  Target target = MakeRenderTarget(8, 8);
  BindTarget(target.rtv.Get(), 8, 8);
  Clear(target.rtv.Get(), kBlack);
  UseColorPipeline();
  // Edges through pixel centres: x = 1.5 (left edge: centres included), x = 4.5
  // (right edge: excluded), y = 2.5 (top: included), y = 5.5 (bottom: excluded).
  // Covered: x in {1,2,3}, y in {2,3,4}.
  DrawVertices(Quad(1.5f, 2.5f, 4.5f, 5.5f, kWhite, 8, 8));
  EXPECT_EQ(CoverageMap(ReadTexture(target.texture.Get()), 8, 8, kWhitePx, kBlackPx),
            (std::vector<std::string>{"........",
                                      "........",
                                      ".XXX....",
                                      ".XXX....",
                                      ".XXX....",
                                      "........",
                                      "........",
                                      "........"}));
}

// Vertices 0..3 would cover the whole target in red; 4..7 cover [2,6) x [1,3) in green.
std::vector<Vertex> TwoQuadCorners() {
  std::vector<Vertex> v = Corners(0, 0, 8, 8, kRed, 8, 8);
  std::vector<Vertex> b = Corners(2, 1, 6, 3, kGreen, 8, 8);
  v.insert(v.end(), b.begin(), b.end());
  return v;
}

const std::vector<std::string> kGreenQuadPicture = {"........", "..GGGG..", "..GGGG..", "........",
                                                    "........", "........", "........", "........"};

TEST_F(DrawTest, DrawIndexed16BitAppliesStartIndexAndBaseVertex) {
  Target target = MakeRenderTarget(8, 8);
  BindTarget(target.rtv.Get(), 8, 8);
  Clear(target.rtv.Get(), kBlack);
  UseColorPipeline();
  ComPtr<Buffer> vb = VertexBuffer(TwoQuadCorners());
  // Indices from StartIndexLocation 3 are {0,1,2,2,1,3} + BaseVertexLocation 4:
  // the green quad. Ignoring the start index would draw only its first triangle,
  // ignoring the base vertex would fill the target red.
  const uint16_t indices[] = {0, 1, 2, 0, 1, 2, 2, 1, 3};
  ComPtr<Buffer> ib = MakeBuffer(BIND_INDEX_BUFFER, indices, sizeof indices, USAGE_IMMUTABLE);
  const UINT stride = sizeof(Vertex), offset = 0;
  Buffer* vbs[] = {vb.Get()};
  context->IASetVertexBuffers(0, 1, vbs, &stride, &offset);
  context->IASetIndexBuffer(ib.Get(), DXGI_FORMAT_R16_UINT, 0);
  context->DrawIndexed(6, 3, 4);
  EXPECT_EQ(Picture(ReadTexture(target.texture.Get()), 8, 8, kLegend), kGreenQuadPicture);
}

TEST_F(DrawTest, DrawIndexed32BitReadsFullWidthIndicesWithNegativeBaseVertexAndOffset) {
  Target target = MakeRenderTarget(8, 8);
  BindTarget(target.rtv.Get(), 8, 8);
  Clear(target.rtv.Get(), kBlack);
  UseColorPipeline();
  ComPtr<Buffer> vb = VertexBuffer(TwoQuadCorners());
  // The first index is skipped by the 4-byte index buffer offset. Indices above
  // 65535 plus BaseVertexLocation -69996 address vertices 4..7: the green quad.
  const uint32_t indices[] = {0, 70000, 70001, 70002, 70002, 70001, 70003};
  ComPtr<Buffer> ib = MakeBuffer(BIND_INDEX_BUFFER, indices, sizeof indices, USAGE_IMMUTABLE);
  const UINT stride = sizeof(Vertex), offset = 0;
  Buffer* vbs[] = {vb.Get()};
  context->IASetVertexBuffers(0, 1, vbs, &stride, &offset);
  context->IASetIndexBuffer(ib.Get(), DXGI_FORMAT_R32_UINT, 4);
  context->DrawIndexed(6, 0, -69996);
  EXPECT_EQ(Picture(ReadTexture(target.texture.Get()), 8, 8, kLegend), kGreenQuadPicture);
}

TEST_F(DrawTest, DrawInstancedReadsPerInstanceDataFromItsOwnSlot) {
  Target target = MakeRenderTarget(8, 8);
  BindTarget(target.rtv.Get(), 8, 8);
  Clear(target.rtv.Get(), kBlack);
  const INPUT_ELEMENT_DESC elements[] = {
      {"POSITION", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
      {"OFFSET", 0, DXGI_FORMAT_R32_FLOAT, 1, 0, INPUT_PER_INSTANCE_DATA, 1},
      {"COLOR", 0, DXGI_FORMAT_R32G32B32A32_FLOAT, 1, 4, INPUT_PER_INSTANCE_DATA, 1},
  };
  ComPtr<InputLayout> layout;
  auto vs = VSWithLayout(R"(
      struct VSIn { float3 pos : POSITION; float offset : OFFSET; nointerpolation float4 color : COLOR; };
      struct VSOut { float4 pos : SV_Position; nointerpolation float4 color : COLOR; };
      VSOut main(VSIn i) { VSOut o; o.pos = float4(i.pos.x + i.offset, i.pos.y, i.pos.z, 1); o.color = i.color; return o; })",
                         elements, 3, &layout);
  auto ps = PS(kColorPS);
  // Per vertex: column 0 ([0,1) x [0,8)). Per instance: an x offset in clip
  // units (one column = 2/8 = 0.25) and a colour.
  ComPtr<Buffer> quad = VertexBuffer(Quad(0, 0, 1, 8, kBlack, 8, 8));
  struct Instance {
    float offset;
    Color color;
  };
  const Instance instances[] = {{1 * 0.25f, kRed}, {3 * 0.25f, kGreen}, {4 * 0.25f, kBlue}, {6 * 0.25f, kWhite}};
  ComPtr<Buffer> ib = MakeBuffer(BIND_VERTEX_BUFFER, instances, sizeof instances, USAGE_IMMUTABLE);
  Buffer* vbs[] = {quad.Get(), ib.Get()};
  const UINT strides[] = {sizeof(Vertex), sizeof(Instance)}, offsets[] = {0, 0};
  context->IASetVertexBuffers(0, 2, vbs, strides, offsets);
  context->IASetInputLayout(layout.Get());
  context->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  context->VSSetShader(vs.Get(), nullptr, 0);
  context->PSSetShader(ps.Get(), nullptr, 0);
  context->DrawInstanced(6, 4, 0, 0);
  EXPECT_EQ(Picture(ReadTexture(target.texture.Get()), 8, 8, kLegend), Rows(8, ".R.GB.W."));
}

// Instanced draws whose column is SV_InstanceID and whose colour is per-instance
// data: instance data element i is {red, green, blue, white}[i].
class InstanceIdTest : public RhiGpuTest {
 protected:
  void SetUp() override {
    RhiGpuTest::SetUp();
    if (HasFatalFailure()) return;
    target_ = MakeRenderTarget(8, 8);
    BindTarget(target_.rtv.Get(), 8, 8);
    Clear(target_.rtv.Get(), kBlack);
    const INPUT_ELEMENT_DESC elements[] = {
        {"POSITION", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
        {"COLOR", 0, DXGI_FORMAT_R32G32B32A32_FLOAT, 1, 0, INPUT_PER_INSTANCE_DATA, 1},
    };
    vs_ = VSWithLayout(R"(
        struct VSIn { float3 pos : POSITION; nointerpolation float4 color : COLOR; uint id : SV_InstanceID; };
        struct VSOut { float4 pos : SV_Position; nointerpolation float4 color : COLOR; };
        VSOut main(VSIn i) {
          VSOut o; o.pos = float4(i.pos.x + 0.25 * i.id, i.pos.y, i.pos.z, 1); o.color = i.color; return o; })",
                       elements, 2, &layout_);
    ps_ = PS(kColorPS);
    // Column 0 as corners (indexed draws) followed by the same column as a list.
    std::vector<Vertex> vertices = Corners(0, 0, 1, 8, kBlack, 8, 8);
    std::vector<Vertex> list = Quad(0, 0, 1, 8, kBlack, 8, 8);
    vertices.insert(vertices.end(), list.begin(), list.end());
    vb_ = VertexBuffer(vertices);
    const Color colors[] = {kRed, kGreen, kBlue, kWhite};
    instances_ = MakeBuffer(BIND_VERTEX_BUFFER, colors, sizeof colors, USAGE_IMMUTABLE);
    const uint16_t indices[] = {0, 1, 2, 2, 1, 3};
    ib_ = MakeBuffer(BIND_INDEX_BUFFER, indices, sizeof indices, USAGE_IMMUTABLE);
    Buffer* vbs[] = {vb_.Get(), instances_.Get()};
    const UINT strides[] = {sizeof(Vertex), sizeof(Color)}, offsets[] = {0, 0};
    context->IASetVertexBuffers(0, 2, vbs, strides, offsets);
    context->IASetIndexBuffer(ib_.Get(), DXGI_FORMAT_R16_UINT, 0);
    context->IASetInputLayout(layout_.Get());
    context->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    context->VSSetShader(vs_.Get(), nullptr, 0);
    context->PSSetShader(ps_.Get(), nullptr, 0);
  }
  std::vector<std::string> Result() { return Picture(ReadTexture(target_.texture.Get()), 8, 8, kLegend); }

  static constexpr UINT kListStart = 4;  // first vertex of the list copy of the column
  Target target_;
  ComPtr<VertexShader> vs_;
  ComPtr<PixelShader> ps_;
  ComPtr<InputLayout> layout_;
  ComPtr<Buffer> vb_, instances_, ib_;
};

TEST_F(InstanceIdTest, DrawInstancedStartsInstanceIdAtZeroWhileInstanceDataStartsAtStartInstanceLocation) {
  // D3D11: SV_InstanceID counts from 0 whatever StartInstanceLocation is; the
  // per-instance data starts at element StartInstanceLocation. Instances 0 and 1
  // land in columns 0 and 1 with colours of elements 2 and 3 (blue, white).
  context->DrawInstanced(6, 2, kListStart, 2);
  EXPECT_EQ(Result(), Rows(8, "BW......"));
}

TEST_F(InstanceIdTest, DrawIndexedInstancedDrawsEachInstanceInItsColumn) {
  // Instances 0..2 in columns 0..2, colours from elements 1..3 (green, blue, white).
  context->DrawIndexedInstanced(6, 3, 0, 0, 1);
  EXPECT_EQ(Result(), Rows(8, "GBW....."));
}

TEST_F(InstanceIdTest, DrawInstancedIndirectUsesArgsWrittenByUpdateSubresourceAtAnOffset) {
  // Args at byte 16: {VertexCountPerInstance 6, InstanceCount 2, StartVertexLocation 4,
  // StartInstanceLocation 1}: columns 0,1 in green, blue. The words before are
  // a decoy (one triangle of 3 vertices, one instance) that would leave half a column.
  BUFFER_DESC desc{32, USAGE_DEFAULT, 0, 0, RESOURCE_MISC_DRAWINDIRECT_ARGS, 0};
  ComPtr<Buffer> args;
  ASSERT_EQ(device->CreateBuffer(&desc, nullptr, args.GetAddressOf()), S_OK);
  const uint32_t words[8] = {3, 1, kListStart, 0, 6, 2, kListStart, 1};
  context->UpdateSubresource(args.Get(), 0, nullptr, words, 0, 0);
  context->DrawInstancedIndirect(args.Get(), 16);
  EXPECT_EQ(Result(), Rows(8, "GB......"));
}

TEST_F(InstanceIdTest, DrawIndexedInstancedIndirectUsesArgsWrittenByComputeShaderThroughUav) {
  // The buffer starts zeroed (a draw of nothing); the compute shader writes
  // {IndexCountPerInstance 6, InstanceCount 3, StartIndexLocation 0,
  // BaseVertexLocation 0, StartInstanceLocation 1}: columns 0..2 in green, blue, white.
  const uint32_t zeros[5] = {};
  ComPtr<Buffer> args = MakeBuffer(BIND_UNORDERED_ACCESS, zeros, sizeof zeros, USAGE_DEFAULT,
                                   RESOURCE_MISC_DRAWINDIRECT_ARGS | RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS);
  UNORDERED_ACCESS_VIEW_DESC uavDesc{};
  uavDesc.Format = DXGI_FORMAT_R32_TYPELESS;
  uavDesc.ViewDimension = UAV_DIMENSION_BUFFER;
  uavDesc.Buffer = {0, 5, BUFFER_UAV_FLAG_RAW};
  ComPtr<UnorderedAccessView> uav;
  ASSERT_EQ(device->CreateUnorderedAccessView(args.Get(), &uavDesc, uav.GetAddressOf()), S_OK);
  auto cs = CS(R"(
      RWByteAddressBuffer args : register(u0);
      [numthreads(1, 1, 1)] void main() { args.Store4(0, uint4(6, 3, 0, 0)); args.Store(16, 1); })");
  context->CSSetShader(cs.Get(), nullptr, 0);
  UnorderedAccessView* uavs[] = {uav.Get()};
  context->CSSetUnorderedAccessViews(0, 1, uavs, nullptr);
  context->Dispatch(1, 1, 1);
  UnorderedAccessView* none[] = {nullptr};
  context->CSSetUnorderedAccessViews(0, 1, none, nullptr);
  context->DrawIndexedInstancedIndirect(args.Get(), 0);
  EXPECT_EQ(Result(), Rows(8, "GBW....."));
}

TEST_F(DrawTest, DispatchWritesRWStructuredBuffer) {
  // 2 groups of 4 threads write element i = 3i + 1 for i in 0..7; elements 8..11 keep 0xDEADBEEF.
  std::vector<uint32_t> initial(12, 0xDEADBEEFu);
  ComPtr<Buffer> buffer = MakeBuffer(BIND_UNORDERED_ACCESS, initial.data(), 48, USAGE_DEFAULT,
                                     RESOURCE_MISC_BUFFER_STRUCTURED, 4);
  UNORDERED_ACCESS_VIEW_DESC uavDesc{};
  uavDesc.Format = DXGI_FORMAT_UNKNOWN;
  uavDesc.ViewDimension = UAV_DIMENSION_BUFFER;
  uavDesc.Buffer = {0, 12, 0};
  ComPtr<UnorderedAccessView> uav;
  ASSERT_EQ(device->CreateUnorderedAccessView(buffer.Get(), &uavDesc, uav.GetAddressOf()), S_OK);
  auto cs = CS(R"(
      RWStructuredBuffer<uint> result : register(u0);
      [numthreads(4, 1, 1)] void main(uint3 id : SV_DispatchThreadID) { result[id.x] = id.x * 3 + 1; })");
  context->CSSetShader(cs.Get(), nullptr, 0);
  UnorderedAccessView* uavs[] = {uav.Get()};
  context->CSSetUnorderedAccessViews(0, 1, uavs, nullptr);
  context->Dispatch(2, 1, 1);
  EXPECT_EQ(ReadBufferAs<uint32_t>(buffer.Get()),
            (std::vector<uint32_t>{1, 4, 7, 10, 13, 16, 19, 22, 0xDEADBEEF, 0xDEADBEEF, 0xDEADBEEF, 0xDEADBEEF}));
}

TEST_F(DrawTest, DispatchIndirectWritesRWByteAddressBufferWithGroupCountFromArgs) {
  // Args at byte 4: {3, 1, 1} groups of 2x2 threads; word g*4 + i = 0x100 * g + i
  // (i = SV_GroupIndex). Words 12..15 keep 0xDEADBEEF. The decoy word 0 (100)
  // would be the X group count if the offset were ignored.
  const uint32_t argWords[4] = {100, 3, 1, 1};
  ComPtr<Buffer> args = MakeBuffer(0, argWords, sizeof argWords, USAGE_DEFAULT, RESOURCE_MISC_DRAWINDIRECT_ARGS);
  std::vector<uint32_t> initial(16, 0xDEADBEEFu);
  ComPtr<Buffer> buffer = MakeBuffer(BIND_UNORDERED_ACCESS, initial.data(), 64, USAGE_DEFAULT,
                                     RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS);
  UNORDERED_ACCESS_VIEW_DESC uavDesc{};
  uavDesc.Format = DXGI_FORMAT_R32_TYPELESS;
  uavDesc.ViewDimension = UAV_DIMENSION_BUFFER;
  uavDesc.Buffer = {0, 16, BUFFER_UAV_FLAG_RAW};
  ComPtr<UnorderedAccessView> uav;
  ASSERT_EQ(device->CreateUnorderedAccessView(buffer.Get(), &uavDesc, uav.GetAddressOf()), S_OK);
  auto cs = CS(R"(
      RWByteAddressBuffer result : register(u0);
      [numthreads(2, 2, 1)] void main(uint3 group : SV_GroupID, uint index : SV_GroupIndex) {
        result.Store((group.x * 4 + index) * 4, group.x * 0x100 + index); })");
  context->CSSetShader(cs.Get(), nullptr, 0);
  UnorderedAccessView* uavs[] = {uav.Get()};
  context->CSSetUnorderedAccessViews(0, 1, uavs, nullptr);
  context->DispatchIndirect(args.Get(), 4);
  EXPECT_EQ(ReadBufferAs<uint32_t>(buffer.Get()),
            (std::vector<uint32_t>{0x000, 0x001, 0x002, 0x003, 0x100, 0x101, 0x102, 0x103, 0x200, 0x201, 0x202,
                                   0x203, 0xDEADBEEF, 0xDEADBEEF, 0xDEADBEEF, 0xDEADBEEF}));
}

}  // namespace
}  // namespace rhi_test
