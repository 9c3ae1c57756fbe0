// Deferred contexts, command lists and ExecuteCommandList (deferred_context.h
// says how they work).
#include "deferred_context.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <memory>
#include <string>

#include "context.h"
#include "rhi/format_info.h"
#include "rhi/stage_methods.h"

namespace rhi::vk {

namespace {

template <class T>
std::vector<ComPtr<T>> Hold(T* const* objects, UINT count) {
  std::vector<ComPtr<T>> held;
  for (UINT i = 0; i < count; ++i) held.emplace_back(objects ? objects[i] : nullptr);
  return held;
}

template <class T>
std::vector<T*> Raw(const std::vector<ComPtr<T>>& held) {
  std::vector<T*> raw;
  for (const ComPtr<T>& object : held) raw.push_back(object.Get());
  return raw;
}

// `count` values, zeros where `values` is null (D3D11 reads null arrays as zeros).
std::vector<UINT> Values(const UINT* values, UINT count, UINT fallback = 0) {
  std::vector<UINT> copy(count, fallback);
  if (values) std::copy(values, values + count, copy.begin());
  return copy;
}

// A getter's result: the object with a reference for the caller.
template <class T>
T* Give(const ComPtr<T>& object) {
  if (object) object->AddRef();
  return object.Get();
}

template <class T, size_t N, class U>
void SetSlots(std::array<ComPtr<T>, N>& slots, UINT start, UINT count, U* const* objects) {
  for (UINT i = 0; i < count && start + i < N; ++i) slots[start + i] = objects ? objects[i] : nullptr;
}

template <class T, size_t N>
void GetSlots(const std::array<ComPtr<T>, N>& slots, UINT start, UINT count, T** out) {
  for (UINT i = 0; out && i < count; ++i) out[i] = start + i < N ? Give(slots[start + i]) : nullptr;
}

template <class T, size_t N>
std::vector<T*> RawSlots(const std::array<ComPtr<T>, N>& slots) {
  std::vector<T*> raw;
  for (const ComPtr<T>& object : slots) raw.push_back(object.Get());
  return raw;
}

static_assert(std::size(kStageMethods) == kShaderStageCount, "rhi/stage_methods.h lists every stage");

template <class T, size_t N>
void CaptureSlots(DeviceContext* c, void (DeviceContext::*get)(UINT, UINT, T**), std::array<ComPtr<T>, N>& slots) {
  std::array<T*, N> raw{};
  (c->*get)(0, N, raw.data());
  for (size_t i = 0; i < N; ++i) slots[i].Attach(raw[i]);
}

}  // namespace

void ContextState::Capture(DeviceContext* c) {
  c->IAGetInputLayout(inputLayout.ReleaseAndGetAddressOf());
  std::array<Buffer*, IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT> buffers{};
  c->IAGetVertexBuffers(0, IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT, buffers.data(), strides.data(), offsets.data());
  for (size_t i = 0; i < buffers.size(); ++i) vertexBuffers[i].Attach(buffers[i]);
  c->IAGetIndexBuffer(indexBuffer.ReleaseAndGetAddressOf(), &indexFormat, &indexOffset);
  c->IAGetPrimitiveTopology(&topology);
  VertexShader* vs = nullptr;
  HullShader* hs = nullptr;
  DomainShader* ds = nullptr;
  GeometryShader* gs = nullptr;
  PixelShader* ps = nullptr;
  ComputeShader* cs = nullptr;
  c->VSGetShader(&vs, nullptr, nullptr);
  c->HSGetShader(&hs, nullptr, nullptr);
  c->DSGetShader(&ds, nullptr, nullptr);
  c->GSGetShader(&gs, nullptr, nullptr);
  c->PSGetShader(&ps, nullptr, nullptr);
  c->CSGetShader(&cs, nullptr, nullptr);
  stages[0].shader.Attach(vs);
  stages[1].shader.Attach(hs);
  stages[2].shader.Attach(ds);
  stages[3].shader.Attach(gs);
  stages[4].shader.Attach(ps);
  stages[5].shader.Attach(cs);
  for (size_t s = 0; s < kShaderStageCount; ++s) {
    CaptureSlots(c, kStageMethods[s].getConstantBuffers, stages[s].constantBuffers);
    CaptureSlots(c, kStageMethods[s].getShaderResources, stages[s].shaderResources);
    CaptureSlots(c, kStageMethods[s].getSamplers, stages[s].samplers);
  }
  CaptureSlots(c, &DeviceContext::CSGetUnorderedAccessViews, computeUavs);
  std::array<Buffer*, SO_BUFFER_SLOT_COUNT> targets{};
  c->SOGetTargets(SO_BUFFER_SLOT_COUNT, targets.data());
  for (size_t i = 0; i < targets.size(); ++i) streamOut[i].Attach(targets[i]);
  c->RSGetState(rasterizer.ReleaseAndGetAddressOf());
  UINT count = 0;
  c->RSGetViewports(&count, nullptr);
  viewports.resize(count);
  if (count) c->RSGetViewports(&count, viewports.data());
  c->RSGetScissorRects(&count, nullptr);
  scissors.resize(count);
  if (count) c->RSGetScissorRects(&count, scissors.data());
  std::array<RenderTargetView*, SIMULTANEOUS_RENDER_TARGET_COUNT> rtvs{};
  std::array<UnorderedAccessView*, PS_CS_UAV_REGISTER_COUNT> uavs{};
  c->OMGetRenderTargetsAndUnorderedAccessViews(SIMULTANEOUS_RENDER_TARGET_COUNT, rtvs.data(),
                                               depthStencil.ReleaseAndGetAddressOf(), 0, PS_CS_UAV_REGISTER_COUNT,
                                               uavs.data());
  for (size_t i = 0; i < rtvs.size(); ++i) renderTargets[i].Attach(rtvs[i]);
  for (size_t i = 0; i < uavs.size(); ++i) graphicsUavs[i].Attach(uavs[i]);
  c->OMGetBlendState(blend.ReleaseAndGetAddressOf(), blendFactor.data(), &sampleMask);
  c->OMGetDepthStencilState(depthStencilState.ReleaseAndGetAddressOf(), &stencilRef);
  c->GetPredication(predicate.ReleaseAndGetAddressOf(), &predicateValue);
}

void ContextState::Apply(DeviceContext* c) const {
  c->IASetInputLayout(inputLayout.Get());
  const std::vector<Buffer*> buffers = RawSlots(vertexBuffers);
  c->IASetVertexBuffers(0, IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT, buffers.data(), strides.data(), offsets.data());
  c->IASetIndexBuffer(indexBuffer.Get(), indexFormat, indexOffset);
  c->IASetPrimitiveTopology(topology);
  c->VSSetShader(static_cast<VertexShader*>(stages[0].shader.Get()), nullptr, 0);
  c->HSSetShader(static_cast<HullShader*>(stages[1].shader.Get()), nullptr, 0);
  c->DSSetShader(static_cast<DomainShader*>(stages[2].shader.Get()), nullptr, 0);
  c->GSSetShader(static_cast<GeometryShader*>(stages[3].shader.Get()), nullptr, 0);
  c->PSSetShader(static_cast<PixelShader*>(stages[4].shader.Get()), nullptr, 0);
  c->CSSetShader(static_cast<ComputeShader*>(stages[5].shader.Get()), nullptr, 0);
  for (size_t s = 0; s < kShaderStageCount; ++s) {
    const Stage& stage = stages[s];
    (c->*kStageMethods[s].setConstantBuffers)(0, stage.constantBuffers.size(), RawSlots(stage.constantBuffers).data());
    (c->*kStageMethods[s].setShaderResources)(0, stage.shaderResources.size(), RawSlots(stage.shaderResources).data());
    (c->*kStageMethods[s].setSamplers)(0, stage.samplers.size(), RawSlots(stage.samplers).data());
  }
  const std::vector<UINT> keepCounts(PS_CS_UAV_REGISTER_COUNT, UINT(-1));
  c->CSSetUnorderedAccessViews(0, PS_CS_UAV_REGISTER_COUNT, RawSlots(computeUavs).data(), keepCounts.data());
  // Offsets are not part of the state the getters return: appending (-1) goes on where stream output stopped.
  const std::vector<UINT> append(SO_BUFFER_SLOT_COUNT, UINT(-1));
  if (std::any_of(streamOut.begin(), streamOut.end(), [](const auto& b) { return static_cast<bool>(b); }))
    c->SOSetTargets(SO_BUFFER_SLOT_COUNT, RawSlots(streamOut).data(), append.data());
  c->RSSetState(rasterizer.Get());
  c->RSSetViewports(static_cast<UINT>(viewports.size()), viewports.data());
  c->RSSetScissorRects(static_cast<UINT>(scissors.size()), scissors.data());
  // Render targets below the first UAV slot, as D3D11 requires of any bound state.
  UINT targetCount = 0;
  for (UINT i = 0; i < SIMULTANEOUS_RENDER_TARGET_COUNT; ++i)
    if (renderTargets[i]) targetCount = i + 1;
  const std::vector<RenderTargetView*> rtvs = RawSlots(renderTargets);
  const std::vector<UnorderedAccessView*> uavs = RawSlots(graphicsUavs);
  c->OMSetRenderTargetsAndUnorderedAccessViews(targetCount, rtvs.data(), depthStencil.Get(), targetCount,
                                               PS_CS_UAV_REGISTER_COUNT - targetCount, uavs.data() + targetCount,
                                               keepCounts.data());
  c->OMSetBlendState(blend.Get(), blendFactor.data(), sampleMask);
  c->OMSetDepthStencilState(depthStencilState.Get(), stencilRef);
  if (predicate) c->SetPredication(predicate.Get(), predicateValue);
}

// ---------------------------------------------------------------------------
// The deferred context

namespace {

class DeferredContext final : public DeviceChildImpl<DeviceContext> {
 public:
  explicit DeferredContext(DeviceImpl* device) : DeviceChildImpl(device) {}

  // Input assembler
  void IASetInputLayout(InputLayout* layout) override {
    state_.inputLayout = layout;
    ComPtr<InputLayout> held(layout);
    Record([held](DeviceContext* c) { c->IASetInputLayout(held.Get()); });
  }
  void IASetVertexBuffers(UINT start, UINT n, Buffer* const* buffers, const UINT* strides,
                          const UINT* offsets) override {
    for (UINT i = 0; i < n && start + i < IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT; ++i) {
      state_.vertexBuffers[start + i] = buffers ? buffers[i] : nullptr;
      state_.strides[start + i] = strides ? strides[i] : 0;
      state_.offsets[start + i] = offsets ? offsets[i] : 0;
    }
    auto held = Hold(buffers, n);
    auto s = Values(strides, n), o = Values(offsets, n);
    Record([=](DeviceContext* c) { c->IASetVertexBuffers(start, n, Raw(held).data(), s.data(), o.data()); });
  }
  void IASetIndexBuffer(Buffer* buffer, DXGI_FORMAT format, UINT offset) override {
    state_.indexBuffer = buffer;
    state_.indexFormat = format;
    state_.indexOffset = offset;
    ComPtr<Buffer> held(buffer);
    Record([=](DeviceContext* c) { c->IASetIndexBuffer(held.Get(), format, offset); });
  }
  void IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY topology) override {
    state_.topology = topology;
    Record([=](DeviceContext* c) { c->IASetPrimitiveTopology(topology); });
  }
  void IAGetInputLayout(InputLayout** layout) override {
    if (layout) *layout = Give(state_.inputLayout);
  }
  void IAGetVertexBuffers(UINT start, UINT n, Buffer** buffers, UINT* strides, UINT* offsets) override {
    for (UINT i = 0; i < n; ++i) {
      const bool in = start + i < IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT;
      if (buffers) buffers[i] = in ? Give(state_.vertexBuffers[start + i]) : nullptr;
      if (strides) strides[i] = in ? state_.strides[start + i] : 0;
      if (offsets) offsets[i] = in ? state_.offsets[start + i] : 0;
    }
  }
  void IAGetIndexBuffer(Buffer** buffer, DXGI_FORMAT* format, UINT* offset) override {
    if (buffer) *buffer = Give(state_.indexBuffer);
    if (format) *format = state_.indexFormat;
    if (offset) *offset = state_.indexOffset;
  }
  void IAGetPrimitiveTopology(PRIMITIVE_TOPOLOGY* topology) override {
    if (topology) *topology = state_.topology;
  }

  // Shader stages
#define RHI_DEFERRED_STAGE(Prefix, Index, Interface)                                                          \
  void Prefix##SetShader(Interface* shader, ClassInstance* const*, UINT) override {                           \
    state_.stages[Index].shader = shader;                                                                     \
    ComPtr<Interface> held(shader);                                                                           \
    Record([held](DeviceContext* c) { c->Prefix##SetShader(held.Get(), nullptr, 0); });                       \
  }                                                                                                           \
  void Prefix##GetShader(Interface** shader, ClassInstance**, UINT* count) override {                         \
    if (count) *count = 0;                                                                                    \
    if (shader) *shader = static_cast<Interface*>(Give(state_.stages[Index].shader));                         \
  }                                                                                                           \
  void Prefix##SetConstantBuffers(UINT start, UINT n, Buffer* const* buffers) override {                      \
    SetSlots(state_.stages[Index].constantBuffers, start, n, buffers);                                        \
    auto held = Hold(buffers, n);                                                                             \
    Record([=](DeviceContext* c) { c->Prefix##SetConstantBuffers(start, n, Raw(held).data()); });             \
  }                                                                                                           \
  void Prefix##SetShaderResources(UINT start, UINT n, ShaderResourceView* const* views) override {             \
    SetSlots(state_.stages[Index].shaderResources, start, n, views);                                          \
    auto held = Hold(views, n);                                                                               \
    Record([=](DeviceContext* c) { c->Prefix##SetShaderResources(start, n, Raw(held).data()); });             \
  }                                                                                                           \
  void Prefix##SetSamplers(UINT start, UINT n, SamplerState* const* samplers) override {                      \
    SetSlots(state_.stages[Index].samplers, start, n, samplers);                                              \
    auto held = Hold(samplers, n);                                                                            \
    Record([=](DeviceContext* c) { c->Prefix##SetSamplers(start, n, Raw(held).data()); });                    \
  }                                                                                                           \
  void Prefix##GetConstantBuffers(UINT start, UINT n, Buffer** buffers) override {                            \
    GetSlots(state_.stages[Index].constantBuffers, start, n, buffers);                                        \
  }                                                                                                           \
  void Prefix##GetShaderResources(UINT start, UINT n, ShaderResourceView** views) override {                  \
    GetSlots(state_.stages[Index].shaderResources, start, n, views);                                          \
  }                                                                                                           \
  void Prefix##GetSamplers(UINT start, UINT n, SamplerState** samplers) override {                            \
    GetSlots(state_.stages[Index].samplers, start, n, samplers);                                              \
  }
  RHI_DEFERRED_STAGE(VS, 0, VertexShader)
  RHI_DEFERRED_STAGE(HS, 1, HullShader)
  RHI_DEFERRED_STAGE(DS, 2, DomainShader)
  RHI_DEFERRED_STAGE(GS, 3, GeometryShader)
  RHI_DEFERRED_STAGE(PS, 4, PixelShader)
  RHI_DEFERRED_STAGE(CS, 5, ComputeShader)
#undef RHI_DEFERRED_STAGE

  void CSSetUnorderedAccessViews(UINT start, UINT n, UnorderedAccessView* const* uavs, const UINT* counts) override {
    SetSlots(state_.computeUavs, start, n, uavs);
    auto held = Hold(uavs, n);
    auto initial = Values(counts, n, UINT(-1));
    Record([=](DeviceContext* c) { c->CSSetUnorderedAccessViews(start, n, Raw(held).data(), initial.data()); });
  }
  void CSGetUnorderedAccessViews(UINT start, UINT n, UnorderedAccessView** uavs) override {
    GetSlots(state_.computeUavs, start, n, uavs);
  }

  // Stream output
  void SOSetTargets(UINT n, Buffer* const* targets, const UINT* offsets) override {
    for (UINT i = 0; i < SO_BUFFER_SLOT_COUNT; ++i) state_.streamOut[i] = i < n && targets ? targets[i] : nullptr;
    auto held = Hold(targets, n);
    auto o = Values(offsets, n);
    Record([=](DeviceContext* c) { c->SOSetTargets(n, Raw(held).data(), o.data()); });
  }
  void SOGetTargets(UINT n, Buffer** targets) override { GetSlots(state_.streamOut, 0, n, targets); }

  // Rasterizer
  void RSSetState(RasterizerState* rs) override {
    state_.rasterizer = rs;
    ComPtr<RasterizerState> held(rs);
    Record([held](DeviceContext* c) { c->RSSetState(held.Get()); });
  }
  void RSSetViewports(UINT n, const VIEWPORT* viewports) override {
    state_.viewports.assign(viewports, viewports + std::min(n, VIEWPORT_AND_SCISSORRECT_OBJECT_COUNT_PER_PIPELINE));
    auto copy = state_.viewports;
    Record([copy](DeviceContext* c) { c->RSSetViewports(static_cast<UINT>(copy.size()), copy.data()); });
  }
  void RSSetScissorRects(UINT n, const RECT* rects) override {
    state_.scissors.assign(rects, rects + std::min(n, VIEWPORT_AND_SCISSORRECT_OBJECT_COUNT_PER_PIPELINE));
    auto copy = state_.scissors;
    Record([copy](DeviceContext* c) { c->RSSetScissorRects(static_cast<UINT>(copy.size()), copy.data()); });
  }
  void RSGetState(RasterizerState** rs) override {
    if (rs) *rs = Give(state_.rasterizer);
  }
  void RSGetViewports(UINT* n, VIEWPORT* viewports) override { GetRects(state_.viewports, n, viewports); }
  void RSGetScissorRects(UINT* n, RECT* rects) override { GetRects(state_.scissors, n, rects); }

  // Output merger
  void OMSetRenderTargets(UINT n, RenderTargetView* const* rtvs, DepthStencilView* dsv) override {
    SetTargets(n, rtvs, dsv);
    state_.graphicsUavs = {};
    auto held = Hold(rtvs, n);
    ComPtr<DepthStencilView> depth(dsv);
    Record([=](DeviceContext* c) { c->OMSetRenderTargets(n, Raw(held).data(), depth.Get()); });
  }
  void OMSetRenderTargetsAndUnorderedAccessViews(UINT nRtvs, RenderTargetView* const* rtvs, DepthStencilView* dsv,
                                                 UINT uavStart, UINT nUavs, UnorderedAccessView* const* uavs,
                                                 const UINT* counts) override {
    const bool keepTargets = nRtvs == KEEP_RENDER_TARGETS_AND_DEPTH_STENCIL;
    const bool keepUavs = nUavs == KEEP_UNORDERED_ACCESS_VIEWS;
    if (!keepTargets) SetTargets(nRtvs, rtvs, dsv);
    if (!keepUavs)
      for (UINT i = 0; i < PS_CS_UAV_REGISTER_COUNT; ++i)
        state_.graphicsUavs[i] = i >= uavStart && i - uavStart < nUavs && uavs ? uavs[i - uavStart] : nullptr;
    auto heldRtvs = Hold(rtvs, keepTargets ? 0 : nRtvs);
    auto heldUavs = Hold(uavs, keepUavs ? 0 : nUavs);
    auto initial = Values(counts, keepUavs ? 0 : nUavs, UINT(-1));
    ComPtr<DepthStencilView> depth(dsv);
    Record([=](DeviceContext* c) {
      c->OMSetRenderTargetsAndUnorderedAccessViews(nRtvs, Raw(heldRtvs).data(), depth.Get(), uavStart, nUavs,
                                                   Raw(heldUavs).data(), initial.data());
    });
  }
  void OMGetRenderTargetsAndUnorderedAccessViews(UINT nRtvs, RenderTargetView** rtvs, DepthStencilView** dsv,
                                                 UINT uavStart, UINT nUavs, UnorderedAccessView** uavs) override {
    GetSlots(state_.renderTargets, 0, nRtvs, rtvs);
    if (dsv) *dsv = Give(state_.depthStencil);
    GetSlots(state_.graphicsUavs, uavStart, nUavs, uavs);
  }
  void OMGetRenderTargets(UINT n, RenderTargetView** rtvs, DepthStencilView** dsv) override {
    OMGetRenderTargetsAndUnorderedAccessViews(n, rtvs, dsv, 0, 0, nullptr);
  }
  void OMSetBlendState(BlendState* blend, const FLOAT factor[4], UINT mask) override {
    state_.blend = blend;
    state_.blendFactor = factor ? std::array<FLOAT, 4>{factor[0], factor[1], factor[2], factor[3]}
                                : std::array<FLOAT, 4>{1, 1, 1, 1};
    state_.sampleMask = mask;
    ComPtr<BlendState> held(blend);
    const std::array<FLOAT, 4> f = state_.blendFactor;
    Record([=](DeviceContext* c) { c->OMSetBlendState(held.Get(), f.data(), mask); });
  }
  void OMSetDepthStencilState(DepthStencilState* dss, UINT ref) override {
    state_.depthStencilState = dss;
    state_.stencilRef = ref;
    ComPtr<DepthStencilState> held(dss);
    Record([=](DeviceContext* c) { c->OMSetDepthStencilState(held.Get(), ref); });
  }
  void OMGetBlendState(BlendState** blend, FLOAT factor[4], UINT* mask) override {
    if (blend) *blend = Give(state_.blend);
    if (factor) std::copy(state_.blendFactor.begin(), state_.blendFactor.end(), factor);
    if (mask) *mask = state_.sampleMask;
  }
  void OMGetDepthStencilState(DepthStencilState** dss, UINT* ref) override {
    if (dss) *dss = Give(state_.depthStencilState);
    if (ref) *ref = state_.stencilRef;
  }

  // Draws and dispatches
  void Draw(UINT count, UINT start) override {
    Record([=](DeviceContext* c) { c->Draw(count, start); });
  }
  void DrawIndexed(UINT count, UINT start, INT base) override {
    Record([=](DeviceContext* c) { c->DrawIndexed(count, start, base); });
  }
  void DrawInstanced(UINT count, UINT instances, UINT start, UINT startInstance) override {
    Record([=](DeviceContext* c) { c->DrawInstanced(count, instances, start, startInstance); });
  }
  void DrawIndexedInstanced(UINT count, UINT instances, UINT start, INT base, UINT startInstance) override {
    Record([=](DeviceContext* c) { c->DrawIndexedInstanced(count, instances, start, base, startInstance); });
  }
  void DrawInstancedIndirect(Buffer* args, UINT offset) override {
    ComPtr<Buffer> held(args);
    Record([=](DeviceContext* c) { c->DrawInstancedIndirect(held.Get(), offset); });
  }
  void DrawIndexedInstancedIndirect(Buffer* args, UINT offset) override {
    ComPtr<Buffer> held(args);
    Record([=](DeviceContext* c) { c->DrawIndexedInstancedIndirect(held.Get(), offset); });
  }
  void DrawAuto() override {
    Record([](DeviceContext* c) { c->DrawAuto(); });
  }
  void Dispatch(UINT x, UINT y, UINT z) override {
    Record([=](DeviceContext* c) { c->Dispatch(x, y, z); });
  }
  void DispatchIndirect(Buffer* args, UINT offset) override {
    ComPtr<Buffer> held(args);
    Record([=](DeviceContext* c) { c->DispatchIndirect(held.Get(), offset); });
  }

  // Clears
  void ClearRenderTargetView(RenderTargetView* rtv, const FLOAT color[4]) override {
    ComPtr<RenderTargetView> held(rtv);
    const std::array<FLOAT, 4> rgba{color[0], color[1], color[2], color[3]};
    Record([=](DeviceContext* c) { c->ClearRenderTargetView(held.Get(), rgba.data()); });
  }
  void ClearDepthStencilView(DepthStencilView* dsv, UINT flags, FLOAT depth, UINT8 stencil) override {
    ComPtr<DepthStencilView> held(dsv);
    Record([=](DeviceContext* c) { c->ClearDepthStencilView(held.Get(), flags, depth, stencil); });
  }
  void ClearUnorderedAccessViewUint(UnorderedAccessView* uav, const UINT values[4]) override {
    ComPtr<UnorderedAccessView> held(uav);
    const std::array<UINT, 4> v{values[0], values[1], values[2], values[3]};
    Record([=](DeviceContext* c) { c->ClearUnorderedAccessViewUint(held.Get(), v.data()); });
  }
  void ClearUnorderedAccessViewFloat(UnorderedAccessView* uav, const FLOAT values[4]) override {
    ComPtr<UnorderedAccessView> held(uav);
    const std::array<FLOAT, 4> v{values[0], values[1], values[2], values[3]};
    Record([=](DeviceContext* c) { c->ClearUnorderedAccessViewFloat(held.Get(), v.data()); });
  }

  // Resource access. A deferred context maps only with MAP_WRITE_DISCARD (D3D11's
  // rule): the bytes go into the list and are written by a map at execution.
  HRESULT Map(Resource* resource, UINT subresource, MAP type, UINT, MAPPED_SUBRESOURCE* mapped) override {
    RESOURCE_DIMENSION dimension = RESOURCE_DIMENSION_UNKNOWN;
    if (resource) resource->GetType(&dimension);
    if (type != MAP_WRITE_DISCARD || dimension != RESOURCE_DIMENSION_BUFFER || !mapped)
      return device().gpu().Refuse("Map on a deferred context: only MAP_WRITE_DISCARD of a dynamic buffer is allowed");
    BUFFER_DESC desc;
    static_cast<Buffer*>(resource)->GetDesc(&desc);
    auto& bytes = mapped_[{resource, subresource}];
    bytes = std::make_shared<std::vector<uint8_t>>(desc.ByteWidth);
    *mapped = {bytes->data(), desc.ByteWidth, desc.ByteWidth};
    return S_OK;
  }
  void Unmap(Resource* resource, UINT subresource) override {
    auto it = mapped_.find({resource, subresource});
    if (it == mapped_.end()) return;
    auto bytes = it->second;
    mapped_.erase(it);
    ComPtr<Resource> held(resource);
    Record([=](DeviceContext* c) {
      MAPPED_SUBRESOURCE target{};
      if (c->Map(held.Get(), subresource, MAP_WRITE_DISCARD, 0, &target) != S_OK) return;
      std::memcpy(target.pData, bytes->data(), bytes->size());
      c->Unmap(held.Get(), subresource);
    });
  }
  void UpdateSubresource(Resource* dst, UINT sub, const BOX* box, const void* data, UINT rowPitch,
                         UINT depthPitch) override {
    auto bytes = std::make_shared<std::vector<uint8_t>>(UpdateSize(dst, sub, box, rowPitch, depthPitch));
    if (data) std::memcpy(bytes->data(), data, bytes->size());
    ComPtr<Resource> held(dst);
    const bool hasBox = box != nullptr;
    const BOX b = box ? *box : BOX{};
    Record([=](DeviceContext* c) {
      c->UpdateSubresource(held.Get(), sub, hasBox ? &b : nullptr, bytes->data(), rowPitch, depthPitch);
    });
  }
  void CopyResource(Resource* dst, Resource* src) override {
    ComPtr<Resource> d(dst), s(src);
    Record([=](DeviceContext* c) { c->CopyResource(d.Get(), s.Get()); });
  }
  void CopySubresourceRegion(Resource* dst, UINT dstSub, UINT x, UINT y, UINT z, Resource* src, UINT srcSub,
                             const BOX* box) override {
    ComPtr<Resource> d(dst), s(src);
    const bool hasBox = box != nullptr;
    const BOX b = box ? *box : BOX{};
    Record([=](DeviceContext* c) {
      c->CopySubresourceRegion(d.Get(), dstSub, x, y, z, s.Get(), srcSub, hasBox ? &b : nullptr);
    });
  }
  void ResolveSubresource(Resource* dst, UINT dstSub, Resource* src, UINT srcSub, DXGI_FORMAT format) override {
    ComPtr<Resource> d(dst), s(src);
    Record([=](DeviceContext* c) { c->ResolveSubresource(d.Get(), dstSub, s.Get(), srcSub, format); });
  }
  void CopyStructureCount(Buffer* dst, UINT offset, UnorderedAccessView* src) override {
    ComPtr<Buffer> d(dst);
    ComPtr<UnorderedAccessView> s(src);
    Record([=](DeviceContext* c) { c->CopyStructureCount(d.Get(), offset, s.Get()); });
  }
  void GenerateMips(ShaderResourceView* srv) override {
    ComPtr<ShaderResourceView> held(srv);
    Record([=](DeviceContext* c) { c->GenerateMips(held.Get()); });
  }
  void SetResourceMinLOD(Resource* resource, FLOAT minLod) override {
    ComPtr<Resource> held(resource);
    Record([=](DeviceContext* c) { c->SetResourceMinLOD(held.Get(), minLod); });
  }
  // The clamp belongs to the resource: what the immediate context last set.
  FLOAT GetResourceMinLOD(Resource* resource) override { return device().context().GetResourceMinLOD(resource); }

  // Queries and predication
  void Begin(Asynchronous* async) override {
    ComPtr<Asynchronous> held(async);
    Record([=](DeviceContext* c) { c->Begin(held.Get()); });
  }
  void End(Asynchronous* async) override {
    ComPtr<Asynchronous> held(async);
    Record([=](DeviceContext* c) { c->End(held.Get()); });
  }
  HRESULT GetData(Asynchronous*, void*, UINT, UINT) override {
    device().gpu().Report(MESSAGE_CATEGORY_EXECUTION, MESSAGE_SEVERITY_ERROR,
                          "GetData on a deferred context: query data is read on the immediate context");
    return DXGI_ERROR_INVALID_CALL;
  }
  void SetPredication(Predicate* predicate, BOOL value) override {
    state_.predicate = predicate;
    state_.predicateValue = value;
    ComPtr<Predicate> held(predicate);
    Record([=](DeviceContext* c) { c->SetPredication(held.Get(), value); });
  }
  void GetPredication(Predicate** predicate, BOOL* value) override {
    if (predicate) *predicate = Give(state_.predicate);
    if (value) *value = state_.predicateValue;
  }

  void ClearState() override {
    state_ = {};
    Record([](DeviceContext* c) { c->ClearState(); });
  }
  void Flush() override {}  // D3D11 ignores Flush on a deferred context
  DEVICE_CONTEXT_TYPE GetType() override { return DEVICE_CONTEXT_DEFERRED; }
  UINT GetContextFlags() override { return 0; }

  void BeginEvent(const char* name) override {
    const std::string text = name ? name : "";
    Record([=](DeviceContext* c) { c->BeginEvent(text.c_str()); });
  }
  void EndEvent() override {
    Record([](DeviceContext* c) { c->EndEvent(); });
  }
  void SetMarker(const char* name) override {
    const std::string text = name ? name : "";
    Record([=](DeviceContext* c) { c->SetMarker(text.c_str()); });
  }

  // A command list inside a command list, as D3D11 allows.
  void ExecuteCommandList(CommandList* list, BOOL restore) override {
    if (!restore) state_ = {};
    ComPtr<CommandList> held(list);
    Record([=](DeviceContext* c) { c->ExecuteCommandList(held.Get(), restore); });
  }

  HRESULT FinishCommandList(BOOL restore, CommandList** out) override {
    if (!out) return device().gpu().Refuse("FinishCommandList: ppCommandList is NULL");
    *out = new CommandListImpl(&device(), std::move(commands_));
    commands_.clear();
    if (restore) {
      // The next list starts, as every list does, from the default state: it
      // first binds the state this context keeps.
      auto kept = std::make_shared<ContextState>(state_);
      Record([kept](DeviceContext* c) { kept->Apply(c); });
    } else {
      state_ = {};
    }
    return S_OK;
  }

 private:
  void Record(CommandListImpl::Command command) { commands_.push_back(std::move(command)); }

  void SetTargets(UINT n, RenderTargetView* const* rtvs, DepthStencilView* dsv) {
    for (UINT i = 0; i < SIMULTANEOUS_RENDER_TARGET_COUNT; ++i)
      state_.renderTargets[i] = i < n && rtvs ? rtvs[i] : nullptr;
    state_.depthStencil = dsv;
  }

  template <class T>
  static void GetRects(const std::vector<T>& bound, UINT* count, T* out) {
    if (!count) return;
    if (!out) {
      *count = static_cast<UINT>(bound.size());
      return;
    }
    for (UINT i = 0; i < *count; ++i) out[i] = i < bound.size() ? bound[i] : T{};
  }

  // The bytes UpdateSubresource reads from pSrcData: the box (or the whole
  // subresource) of a buffer, or rows of W slices of a texture (the last of each unpadded).
  static size_t UpdateSize(Resource* dst, UINT sub, const BOX* box, UINT rowPitch, UINT depthPitch) {
    RESOURCE_DIMENSION dimension = RESOURCE_DIMENSION_UNKNOWN;
    if (dst) dst->GetType(&dimension);
    if (dimension == RESOURCE_DIMENSION_BUFFER) {
      BUFFER_DESC desc;
      static_cast<Buffer*>(dst)->GetDesc(&desc);
      return box ? box->right - box->left : desc.ByteWidth;
    }
    UINT width = 1, height = 1, depth = 1, mips = 1;
    DXGI_FORMAT format = DXGI_FORMAT_UNKNOWN;
    if (dimension == RESOURCE_DIMENSION_TEXTURE3D) {
      TEXTURE3D_DESC desc;
      static_cast<Texture3D*>(dst)->GetDesc(&desc);
      width = desc.Width, height = desc.Height, depth = desc.Depth, mips = desc.MipLevels, format = desc.Format;
    } else if (dimension == RESOURCE_DIMENSION_TEXTURE2D) {
      TEXTURE2D_DESC desc;
      static_cast<Texture2D*>(dst)->GetDesc(&desc);
      width = desc.Width, height = desc.Height, mips = desc.MipLevels, format = desc.Format;
    } else if (dimension == RESOURCE_DIMENSION_TEXTURE1D) {
      TEXTURE1D_DESC desc;
      static_cast<Texture1D*>(dst)->GetDesc(&desc);
      width = desc.Width, mips = desc.MipLevels, format = desc.Format;
    } else {
      return 0;
    }
    const UINT mip = mips ? sub % mips : 0;
    width = box ? box->right - box->left : std::max(1u, width >> mip);
    height = box ? box->bottom - box->top : std::max(1u, height >> mip);
    depth = dimension != RESOURCE_DIMENSION_TEXTURE3D ? 1 : box ? box->back - box->front : std::max(1u, depth >> mip);
    // Rows count 4x4 blocks in block-compressed formats.
    UINT64 tightRow = 0, tightSlice = 0;
    if (!ComputePitch(format, width, height, &tightRow, &tightSlice) || tightRow == 0) return 0;
    const UINT64 rows = tightSlice / tightRow;
    return size_t(depth - 1) * depthPitch + size_t(rows - 1) * rowPitch + size_t(tightRow);
  }

  ContextState state_;
  std::vector<CommandListImpl::Command> commands_;
  std::map<std::pair<Resource*, UINT>, std::shared_ptr<std::vector<uint8_t>>> mapped_;
};

}  // namespace

HRESULT DeviceImpl::CreateDeferredContext(UINT ContextFlags, DeviceContext** ppDeferredContext) {
  if (ContextFlags != 0) return gpu_->Refuse("CreateDeferredContext: ContextFlags must be 0");
  if (!ppDeferredContext) return gpu_->Refuse("CreateDeferredContext: ppDeferredContext is NULL");
  *ppDeferredContext = new DeferredContext(this);
  return S_OK;
}

// ---------------------------------------------------------------------------
// The immediate context's side

void ContextImpl::ExecuteCommandList(CommandList* pCommandList, BOOL RestoreContextState) {
  if (!pCommandList) {
    ReportDrawError("ExecuteCommandList: pCommandList is NULL; the call is ignored");
    return;
  }
  ContextState saved;
  if (RestoreContextState) saved.Capture(this);
  ClearState();  // a command list inherits nothing
  static_cast<CommandListImpl*>(pCommandList)->Replay(this);
  ClearState();
  if (RestoreContextState) saved.Apply(this);
}

HRESULT ContextImpl::FinishCommandList(BOOL, CommandList** ppCommandList) {
  if (ppCommandList) *ppCommandList = nullptr;
  device_->gpu().Report(MESSAGE_CATEGORY_EXECUTION, MESSAGE_SEVERITY_ERROR,
                        "FinishCommandList: the immediate context records no command list (use a deferred context)");
  return DXGI_ERROR_INVALID_CALL;
}

}  // namespace rhi::vk
