// Deferred contexts: threads record parts of a frame into command lists that
// the immediate context executes, giving the image the serial recording gives;
// a command list inherits nothing; the immediate context's state after
// ExecuteCommandList is restored or cleared; FinishCommandList keeps or clears
// the deferred context's state.
#include <thread>

#include "gpu_helpers.h"

namespace rhi_test {
namespace {

using namespace rhi;

constexpr UINT kSize = 8;

class DeferredContextTest : public RhiGpuTest {
 protected:
  // The objects one recording thread binds. Each thread gets its own, so no
  // two threads AddRef one object at once.
  struct Kit {
    ComPtr<VertexShader> vs;
    ComPtr<PixelShader> ps;
    ComPtr<InputLayout> layout;
    ComPtr<RenderTargetView> rtv;
    ComPtr<Buffer> vertices;
  };
  Kit MakeKit(Texture2D* target, const std::vector<Vertex>& quad) {
    static const INPUT_ELEMENT_DESC kElements[] = {
        {"POSITION", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
        {"COLOR", 0, DXGI_FORMAT_R32G32B32A32_FLOAT, 0, 12, INPUT_PER_VERTEX_DATA, 0},
    };
    Kit kit;
    kit.vs = VSWithLayout(kColorVS, kElements, 2, &kit.layout);
    kit.ps = PS(kColorPS);
    EXPECT_EQ(device->CreateRenderTargetView(target, nullptr, kit.rtv.GetAddressOf()), S_OK);
    kit.vertices = VertexBuffer(quad);
    return kit;
  }
  // Binds `kit` on `c` and draws its quad: the same calls on any context.
  static void DrawKit(DeviceContext* c, const Kit& kit) {
    RenderTargetView* rtv = kit.rtv.Get();
    c->OMSetRenderTargets(1, &rtv, nullptr);
    const VIEWPORT viewport{0, 0, float(kSize), float(kSize), 0, 1};
    c->RSSetViewports(1, &viewport);
    c->IASetInputLayout(kit.layout.Get());
    c->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    c->VSSetShader(kit.vs.Get(), nullptr, 0);
    c->PSSetShader(kit.ps.Get(), nullptr, 0);
    Buffer* buffers[] = {kit.vertices.Get()};
    const UINT stride = sizeof(Vertex), offset = 0;
    c->IASetVertexBuffers(0, 1, buffers, &stride, &offset);
    c->Draw(6, 0);
  }
  ComPtr<DeviceContext> Deferred() {
    ComPtr<DeviceContext> deferred;
    EXPECT_EQ(device->CreateDeferredContext(0, deferred.GetAddressOf()), S_OK);
    return deferred;
  }
  std::vector<std::string> Image(Texture2D* texture) {
    return Picture(ReadTexture(texture), kSize, kSize, kLegend);
  }
};

TEST_F(DeferredContextTest, ThreadsRecordingPartsOfAFrameGiveTheSeriallyRecordedImage) {
  // Four overlapping bands, so the order the lists run in shows in the image.
  constexpr int kThreads = 4;
  const Color colors[kThreads] = {kRed, kGreen, kBlue, kWhite};
  Target serial = MakeRenderTarget(kSize, kSize), parallel = MakeRenderTarget(kSize, kSize);
  std::vector<Kit> serialKits, parallelKits;
  for (int i = 0; i < kThreads; ++i) {
    const auto band = Quad(0, float(2 * i), float(kSize), float(2 * i + 3), colors[i], kSize, kSize);
    serialKits.push_back(MakeKit(serial.texture.Get(), band));
    parallelKits.push_back(MakeKit(parallel.texture.Get(), band));
  }
  Clear(serial.rtv.Get(), kBlack);
  for (const Kit& kit : serialKits) DrawKit(context.Get(), kit);

  std::vector<ComPtr<DeviceContext>> deferred;
  for (int i = 0; i < kThreads; ++i) deferred.push_back(Deferred());
  std::vector<ComPtr<CommandList>> lists(kThreads);
  std::vector<std::thread> threads;
  for (int i = 0; i < kThreads; ++i)
    threads.emplace_back([&, i] {
      DrawKit(deferred[i].Get(), parallelKits[i]);
      deferred[i]->FinishCommandList(FALSE, lists[i].GetAddressOf());
    });
  for (std::thread& t : threads) t.join();
  context->ClearState();
  Clear(parallel.rtv.Get(), kBlack);
  for (const auto& list : lists) {
    ASSERT_TRUE(list);
    context->ExecuteCommandList(list.Get(), FALSE);
  }
  const std::vector<std::string> expected = {"RRRRRRRR", "RRRRRRRR", "GGGGGGGG", "GGGGGGGG",
                                             "BBBBBBBB", "BBBBBBBB", "WWWWWWWW", "WWWWWWWW"};
  EXPECT_EQ(Image(serial.texture.Get()), expected);
  EXPECT_EQ(Image(parallel.texture.Get()), Image(serial.texture.Get()));
}

TEST_F(DeferredContextTest, ACommandListInheritsNothingAndExecutionRestoresOrClearsTheState) {
  Target target = MakeRenderTarget(kSize, kSize);
  Kit kit = MakeKit(target.texture.Get(), Quad(0, 0, kSize, kSize, kGreen, kSize, kSize));
  // A list with a draw and nothing bound: it must not draw with the immediate context's state.
  ComPtr<DeviceContext> deferred = Deferred();
  deferred->Draw(6, 0);
  ComPtr<CommandList> drawOnly;
  ASSERT_EQ(deferred->FinishCommandList(FALSE, drawOnly.GetAddressOf()), S_OK);

  Clear(target.rtv.Get(), kBlack);
  DrawKit(context.Get(), kit);
  Clear(target.rtv.Get(), kBlack);
  ClearMessages();
  context->ExecuteCommandList(drawOnly.Get(), TRUE);
  EXPECT_TRUE(RefusedWith("no vertex shader is bound")) << "the list ran from the default state";
  // TRUE: the state is the one from before; a draw shows it.
  InputLayout* layout = nullptr;
  context->IAGetInputLayout(&layout);
  EXPECT_EQ(layout, kit.layout.Get());
  if (layout) layout->Release();
  context->Draw(6, 0);
  EXPECT_EQ(Image(target.texture.Get()), Rows(kSize, "GGGGGGGG"));
  // FALSE: the default state, as after ClearState.
  context->ExecuteCommandList(drawOnly.Get(), FALSE);
  VertexShader* vs = kit.vs.Get();
  context->VSGetShader(&vs, nullptr, nullptr);
  EXPECT_EQ(vs, nullptr);
  RenderTargetView* rtv = kit.rtv.Get();
  context->OMGetRenderTargets(1, &rtv, nullptr);
  EXPECT_EQ(rtv, nullptr);
}

TEST_F(DeferredContextTest, FinishCommandListKeepsOrClearsTheDeferredContextsState) {
  Target target = MakeRenderTarget(kSize, kSize);
  Kit kit = MakeKit(target.texture.Get(), Quad(0, 0, kSize / 2, kSize, kRed, kSize, kSize));
  ComPtr<Buffer> right = VertexBuffer(Quad(kSize / 2, 0, kSize, kSize, kBlue, kSize, kSize));
  ComPtr<DeviceContext> deferred = Deferred();
  EXPECT_EQ(deferred->GetType(), DEVICE_CONTEXT_DEFERRED);
  DrawKit(deferred.Get(), kit);
  ComPtr<CommandList> first, second;
  ASSERT_EQ(deferred->FinishCommandList(TRUE, first.GetAddressOf()), S_OK);
  // Kept: the second list draws with the first one's bindings, only the vertices change.
  VertexShader* vs = nullptr;
  deferred->VSGetShader(&vs, nullptr, nullptr);
  EXPECT_EQ(vs, kit.vs.Get());
  if (vs) vs->Release();
  Buffer* buffers[] = {right.Get()};
  const UINT stride = sizeof(Vertex), offset = 0;
  deferred->IASetVertexBuffers(0, 1, buffers, &stride, &offset);
  deferred->Draw(6, 0);
  ASSERT_EQ(deferred->FinishCommandList(FALSE, second.GetAddressOf()), S_OK);
  deferred->VSGetShader(&vs, nullptr, nullptr);
  EXPECT_EQ(vs, nullptr) << "FALSE: the deferred context is back at the default state";

  Clear(target.rtv.Get(), kBlack);
  context->ExecuteCommandList(first.Get(), FALSE);
  context->ExecuteCommandList(second.Get(), FALSE);
  EXPECT_EQ(Image(target.texture.Get()), Rows(kSize, "RRRRBBBB"));
}

TEST_F(DeferredContextTest, CallsForTheOtherKindOfContextAreRefusedAsD3D11Does) {
  ComPtr<CommandList> list;
  EXPECT_EQ(context->FinishCommandList(FALSE, list.GetAddressOf()), DXGI_ERROR_INVALID_CALL);
  ComPtr<DeviceContext> deferred = Deferred();
  const QUERY_DESC desc{QUERY_EVENT, 0};
  ComPtr<Query> query;
  ASSERT_EQ(device->CreateQuery(&desc, query.GetAddressOf()), S_OK);
  BOOL done = FALSE;
  EXPECT_EQ(deferred->GetData(query.Get(), &done, sizeof done, 0), DXGI_ERROR_INVALID_CALL);
  ComPtr<DeviceContext> flagged;
  EXPECT_EQ(device->CreateDeferredContext(1, flagged.GetAddressOf()), E_INVALIDARG);
  // Map: only WRITE_DISCARD of a dynamic buffer; its bytes reach the buffer when the list runs.
  const uint32_t zeros[4] = {};
  ComPtr<Buffer> dynamic = MakeBuffer(BIND_CONSTANT_BUFFER, zeros, 16, USAGE_DYNAMIC);
  MAPPED_SUBRESOURCE mapped{};
  EXPECT_EQ(deferred->Map(dynamic.Get(), 0, MAP_WRITE, 0, &mapped), E_INVALIDARG);
  ASSERT_EQ(deferred->Map(dynamic.Get(), 0, MAP_WRITE_DISCARD, 0, &mapped), S_OK);
  const uint32_t values[4] = {1, 2, 3, 4};
  std::memcpy(mapped.pData, values, sizeof values);
  deferred->Unmap(dynamic.Get(), 0);
  ComPtr<Buffer> copy = MakeBuffer(0, zeros, 16);
  deferred->CopyResource(copy.Get(), dynamic.Get());
  ASSERT_EQ(deferred->FinishCommandList(FALSE, list.GetAddressOf()), S_OK);
  context->ExecuteCommandList(list.Get(), FALSE);
  EXPECT_EQ(ReadBufferAs<uint32_t>(copy.Get()), std::vector<uint32_t>({1, 2, 3, 4}));
}

}  // namespace
}  // namespace rhi_test
