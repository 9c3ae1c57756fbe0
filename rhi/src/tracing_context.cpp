// The tracing DeviceContext of rhi/trace.h: forwards every call to the wrapped
// context and records it. It lives outside the Vulkan backend's context files
// and touches nothing on their draw path.
#include <cstdio>
#include <string>

#include "rhi/trace.h"

namespace rhi {
namespace {

std::string Obj(const void* p) { return p ? "obj" : "null"; }

template <class... T>
std::string Format(const char* format, T... values) {
  char text[256];
  std::snprintf(text, sizeof text, format, values...);
  return text;
}

template <class T>
std::string Objects(UINT n, T* const* objects) {
  std::string s;
  for (UINT i = 0; i < n; ++i) s += std::string(i ? " " : "") + Obj(objects ? objects[i] : nullptr);
  return s;
}

class TracingContext final : public DeviceContext {
 public:
  TracingContext(DeviceContext* inner, Trace* trace) : inner_(inner), trace_(trace) {}

  void GetDevice(Device** ppDevice) override { inner_->GetDevice(ppDevice); }

  void IASetInputLayout(InputLayout* p) override {
    Record("IASetInputLayout", Obj(p));
    inner_->IASetInputLayout(p);
  }
  void IASetVertexBuffers(UINT start, UINT n, Buffer* const* buffers, const UINT* strides,
                          const UINT* offsets) override {
    if (trace_->enabled) {
      std::string args = Format("%u, %u", start, n);
      for (UINT i = 0; i < n; ++i)
        args += Format(", %s/%u/%u", Obj(buffers ? buffers[i] : nullptr).c_str(), strides ? strides[i] : 0,
                       offsets ? offsets[i] : 0);
      Record("IASetVertexBuffers", args);
    }
    inner_->IASetVertexBuffers(start, n, buffers, strides, offsets);
  }
  void IASetIndexBuffer(Buffer* b, DXGI_FORMAT format, UINT offset) override {
    Record("IASetIndexBuffer", Format("%s, %d, %u", Obj(b).c_str(), int(format), offset));
    inner_->IASetIndexBuffer(b, format, offset);
  }
  void IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY t) override {
    Record("IASetPrimitiveTopology", Format("%d", int(t)));
    inner_->IASetPrimitiveTopology(t);
  }

#define TRACE_SHADER(Prefix, Type)                                                   \
  void Prefix##SetShader(Type* s, ClassInstance* const* c, UINT n) override {        \
    Record(#Prefix "SetShader", Obj(s));                                             \
    inner_->Prefix##SetShader(s, c, n);                                              \
  }                                                                                  \
  void Prefix##SetConstantBuffers(UINT start, UINT n, Buffer* const* b) override {  \
    Record(#Prefix "SetConstantBuffers", Format("%u, %u, ", start, n) + Objects(n, b)); \
    inner_->Prefix##SetConstantBuffers(start, n, b);                                 \
  }                                                                                  \
  void Prefix##SetShaderResources(UINT start, UINT n, ShaderResourceView* const* v) override { \
    Record(#Prefix "SetShaderResources", Format("%u, %u, ", start, n) + Objects(n, v)); \
    inner_->Prefix##SetShaderResources(start, n, v);                                 \
  }                                                                                  \
  void Prefix##SetSamplers(UINT start, UINT n, SamplerState* const* s) override {   \
    Record(#Prefix "SetSamplers", Format("%u, %u, ", start, n) + Objects(n, s));    \
    inner_->Prefix##SetSamplers(start, n, s);                                        \
  }
  TRACE_SHADER(VS, VertexShader)
  TRACE_SHADER(HS, HullShader)
  TRACE_SHADER(DS, DomainShader)
  TRACE_SHADER(GS, GeometryShader)
  TRACE_SHADER(PS, PixelShader)
  TRACE_SHADER(CS, ComputeShader)
#undef TRACE_SHADER

  void CSSetUnorderedAccessViews(UINT start, UINT n, UnorderedAccessView* const* v, const UINT* counts) override {
    Record("CSSetUnorderedAccessViews", Format("%u, %u, ", start, n) + Objects(n, v));
    inner_->CSSetUnorderedAccessViews(start, n, v, counts);
  }

  void SOSetTargets(UINT n, Buffer* const* targets, const UINT* offsets) override {
    if (trace_->enabled) {
      std::string args = Format("%u", n);
      for (UINT i = 0; i < n; ++i)
        args += Format(", %s/%d", Obj(targets ? targets[i] : nullptr).c_str(), offsets ? int(offsets[i]) : 0);
      Record("SOSetTargets", args);
    }
    inner_->SOSetTargets(n, targets, offsets);
  }
  void SOGetTargets(UINT n, Buffer** targets) override {
    Record("SOGetTargets", Format("%u", n));
    inner_->SOGetTargets(n, targets);
  }

  void RSSetState(RasterizerState* s) override {
    Record("RSSetState", Obj(s));
    inner_->RSSetState(s);
  }
  void RSSetViewports(UINT n, const VIEWPORT* v) override {
    if (trace_->enabled) {
      std::string args = Format("%u", n);
      for (UINT i = 0; i < n && v; ++i)
        args += Format(", %g %g %g %g %g %g", v[i].TopLeftX, v[i].TopLeftY, v[i].Width, v[i].Height, v[i].MinDepth,
                       v[i].MaxDepth);
      Record("RSSetViewports", args);
    }
    inner_->RSSetViewports(n, v);
  }
  void RSSetScissorRects(UINT n, const RECT* r) override {
    Record("RSSetScissorRects", Format("%u", n));
    inner_->RSSetScissorRects(n, r);
  }

  void OMSetRenderTargets(UINT n, RenderTargetView* const* rtvs, DepthStencilView* dsv) override {
    Record("OMSetRenderTargets", Format("%u, ", n) + Objects(n, rtvs) + ", " + Obj(dsv));
    inner_->OMSetRenderTargets(n, rtvs, dsv);
  }
  void OMSetRenderTargetsAndUnorderedAccessViews(UINT n, RenderTargetView* const* rtvs, DepthStencilView* dsv,
                                                 UINT uavStart, UINT uavCount, UnorderedAccessView* const* uavs,
                                                 const UINT* counts) override {
    if (trace_->enabled) {
      // KEEP_* counts (0xffffffff) print as -1 and list no views.
      const bool keepTargets = n == KEEP_RENDER_TARGETS_AND_DEPTH_STENCIL;
      const bool keepUavs = uavCount == KEEP_UNORDERED_ACCESS_VIEWS;
      std::string args = Format("%d, ", int(n)) + (keepTargets ? "" : Objects(n, rtvs) + ", ") + Obj(dsv) +
                         Format(", %u, %d", uavStart, int(uavCount));
      for (UINT i = 0; !keepUavs && i < uavCount; ++i)
        args += Format(", %s/%d", Obj(uavs ? uavs[i] : nullptr).c_str(), counts ? int(counts[i]) : -1);
      Record("OMSetRenderTargetsAndUnorderedAccessViews", args);
    }
    inner_->OMSetRenderTargetsAndUnorderedAccessViews(n, rtvs, dsv, uavStart, uavCount, uavs, counts);
  }
  void OMGetRenderTargetsAndUnorderedAccessViews(UINT n, RenderTargetView** rtvs, DepthStencilView** dsv,
                                                 UINT uavStart, UINT uavCount, UnorderedAccessView** uavs) override {
    inner_->OMGetRenderTargetsAndUnorderedAccessViews(n, rtvs, dsv, uavStart, uavCount, uavs);
  }
  void OMSetBlendState(BlendState* s, const FLOAT factor[4], UINT mask) override {
    Record("OMSetBlendState", Obj(s) + Format(", 0x%08X", mask));
    inner_->OMSetBlendState(s, factor, mask);
  }
  void OMSetDepthStencilState(DepthStencilState* s, UINT ref) override {
    Record("OMSetDepthStencilState", Obj(s) + Format(", %u", ref));
    inner_->OMSetDepthStencilState(s, ref);
  }

  void Draw(UINT count, UINT start) override {
    Record("Draw", Format("%u, %u", count, start));
    inner_->Draw(count, start);
  }
  void DrawIndexed(UINT count, UINT start, INT base) override {
    Record("DrawIndexed", Format("%u, %u, %d", count, start, base));
    inner_->DrawIndexed(count, start, base);
  }
  void DrawInstanced(UINT count, UINT instances, UINT start, UINT startInstance) override {
    Record("DrawInstanced", Format("%u, %u, %u, %u", count, instances, start, startInstance));
    inner_->DrawInstanced(count, instances, start, startInstance);
  }
  void DrawIndexedInstanced(UINT count, UINT instances, UINT start, INT base, UINT startInstance) override {
    Record("DrawIndexedInstanced", Format("%u, %u, %u, %d, %u", count, instances, start, base, startInstance));
    inner_->DrawIndexedInstanced(count, instances, start, base, startInstance);
  }
  void DrawInstancedIndirect(Buffer* args, UINT offset) override {
    Record("DrawInstancedIndirect", Obj(args) + Format(", %u", offset));
    inner_->DrawInstancedIndirect(args, offset);
  }
  void DrawIndexedInstancedIndirect(Buffer* args, UINT offset) override {
    Record("DrawIndexedInstancedIndirect", Obj(args) + Format(", %u", offset));
    inner_->DrawIndexedInstancedIndirect(args, offset);
  }
  void DrawAuto() override {
    Record("DrawAuto", "");
    inner_->DrawAuto();
  }
  void Dispatch(UINT x, UINT y, UINT z) override {
    Record("Dispatch", Format("%u, %u, %u", x, y, z));
    inner_->Dispatch(x, y, z);
  }
  void DispatchIndirect(Buffer* args, UINT offset) override {
    Record("DispatchIndirect", Obj(args) + Format(", %u", offset));
    inner_->DispatchIndirect(args, offset);
  }

  void ClearRenderTargetView(RenderTargetView* v, const FLOAT c[4]) override {
    Record("ClearRenderTargetView", Obj(v) + Format(", %g %g %g %g", c[0], c[1], c[2], c[3]));
    inner_->ClearRenderTargetView(v, c);
  }
  void ClearDepthStencilView(DepthStencilView* v, UINT flags, FLOAT depth, UINT8 stencil) override {
    Record("ClearDepthStencilView", Obj(v) + Format(", %u, %g, %u", flags, depth, unsigned(stencil)));
    inner_->ClearDepthStencilView(v, flags, depth, stencil);
  }
  void ClearUnorderedAccessViewUint(UnorderedAccessView* v, const UINT values[4]) override {
    Record("ClearUnorderedAccessViewUint", Obj(v));
    inner_->ClearUnorderedAccessViewUint(v, values);
  }
  void ClearUnorderedAccessViewFloat(UnorderedAccessView* v, const FLOAT values[4]) override {
    Record("ClearUnorderedAccessViewFloat", Obj(v));
    inner_->ClearUnorderedAccessViewFloat(v, values);
  }

  HRESULT Map(Resource* r, UINT sub, MAP type, UINT flags, MAPPED_SUBRESOURCE* mapped) override {
    Record("Map", Obj(r) + Format(", %u, %d", sub, int(type)));
    return inner_->Map(r, sub, type, flags, mapped);
  }
  void Unmap(Resource* r, UINT sub) override {
    Record("Unmap", Obj(r) + Format(", %u", sub));
    inner_->Unmap(r, sub);
  }
  void UpdateSubresource(Resource* r, UINT sub, const BOX* box, const void* data, UINT row, UINT depth) override {
    Record("UpdateSubresource", Obj(r) + Format(", %u", sub));
    inner_->UpdateSubresource(r, sub, box, data, row, depth);
  }
  void CopyResource(Resource* dst, Resource* src) override {
    Record("CopyResource", Obj(dst) + ", " + Obj(src));
    inner_->CopyResource(dst, src);
  }
  void CopySubresourceRegion(Resource* dst, UINT dstSub, UINT x, UINT y, UINT z, Resource* src, UINT srcSub,
                             const BOX* box) override {
    Record("CopySubresourceRegion", Obj(dst) + Format(", %u, %u, %u, %u, ", dstSub, x, y, z) + Obj(src) +
                                        Format(", %u", srcSub));
    inner_->CopySubresourceRegion(dst, dstSub, x, y, z, src, srcSub, box);
  }
  void ResolveSubresource(Resource* dst, UINT dstSub, Resource* src, UINT srcSub, DXGI_FORMAT format) override {
    Record("ResolveSubresource", Obj(dst) + Format(", %u, ", dstSub) + Obj(src) + Format(", %u, %d", srcSub, int(format)));
    inner_->ResolveSubresource(dst, dstSub, src, srcSub, format);
  }
  void CopyStructureCount(Buffer* dst, UINT offset, UnorderedAccessView* src) override {
    Record("CopyStructureCount", Obj(dst) + Format(", %u, ", offset) + Obj(src));
    inner_->CopyStructureCount(dst, offset, src);
  }

  void Begin(Asynchronous* a) override {
    Record("Begin", Obj(a));
    inner_->Begin(a);
  }
  void End(Asynchronous* a) override {
    Record("End", Obj(a));
    inner_->End(a);
  }
  HRESULT GetData(Asynchronous* a, void* data, UINT size, UINT flags) override {
    // Polling loops would flood the trace: GetData is forwarded, not recorded.
    return inner_->GetData(a, data, size, flags);
  }

  void ClearState() override {
    Record("ClearState", "");
    inner_->ClearState();
  }
  void Flush() override {
    Record("Flush", "");
    inner_->Flush();
  }

  void BeginEvent(const char* name) override {
    Record("BeginEvent", name ? name : "");
    inner_->BeginEvent(name);
  }
  void EndEvent() override {
    Record("EndEvent", "");
    inner_->EndEvent();
  }
  void SetMarker(const char* name) override {
    Record("SetMarker", name ? name : "");
    inner_->SetMarker(name);
  }

  void GenerateMips(ShaderResourceView* v) override {
    Record("GenerateMips", Obj(v));
    inner_->GenerateMips(v);
  }
  void SetResourceMinLOD(Resource* r, FLOAT minLod) override {
    Record("SetResourceMinLOD", Obj(r) + Format(", %g", double(minLod)));
    inner_->SetResourceMinLOD(r, minLod);
  }
  FLOAT GetResourceMinLOD(Resource* r) override { return inner_->GetResourceMinLOD(r); }

  void SetPredication(Predicate* p, BOOL value) override {
    Record("SetPredication", Format("%s, %d", Obj(p).c_str(), value));
    inner_->SetPredication(p, value);
  }
  void GetPredication(Predicate** p, BOOL* value) override { inner_->GetPredication(p, value); }

  void ExecuteCommandList(CommandList* list, BOOL restore) override {
    Record("ExecuteCommandList", Format("%s, %d", Obj(list).c_str(), restore));
    inner_->ExecuteCommandList(list, restore);
  }
  HRESULT FinishCommandList(BOOL restore, CommandList** list) override {
    Record("FinishCommandList", Format("%d", restore));
    return inner_->FinishCommandList(restore, list);
  }

  // Getters change nothing: forwarded, not recorded.
  DEVICE_CONTEXT_TYPE GetType() override { return inner_->GetType(); }
  UINT GetContextFlags() override { return inner_->GetContextFlags(); }
  void IAGetInputLayout(InputLayout** l) override { inner_->IAGetInputLayout(l); }
  void IAGetVertexBuffers(UINT start, UINT n, Buffer** b, UINT* strides, UINT* offsets) override {
    inner_->IAGetVertexBuffers(start, n, b, strides, offsets);
  }
  void IAGetIndexBuffer(Buffer** b, DXGI_FORMAT* format, UINT* offset) override {
    inner_->IAGetIndexBuffer(b, format, offset);
  }
  void IAGetPrimitiveTopology(PRIMITIVE_TOPOLOGY* t) override { inner_->IAGetPrimitiveTopology(t); }
#define TRACE_STAGE_GETTERS(Prefix, Type)                                                                 \
  void Prefix##GetShader(Type** s, ClassInstance** c, UINT* n) override { inner_->Prefix##GetShader(s, c, n); } \
  void Prefix##GetConstantBuffers(UINT start, UINT n, Buffer** b) override {                              \
    inner_->Prefix##GetConstantBuffers(start, n, b);                                                      \
  }                                                                                                       \
  void Prefix##GetShaderResources(UINT start, UINT n, ShaderResourceView** v) override {                  \
    inner_->Prefix##GetShaderResources(start, n, v);                                                      \
  }                                                                                                       \
  void Prefix##GetSamplers(UINT start, UINT n, SamplerState** s) override { inner_->Prefix##GetSamplers(start, n, s); }
  TRACE_STAGE_GETTERS(VS, VertexShader)
  TRACE_STAGE_GETTERS(HS, HullShader)
  TRACE_STAGE_GETTERS(DS, DomainShader)
  TRACE_STAGE_GETTERS(GS, GeometryShader)
  TRACE_STAGE_GETTERS(PS, PixelShader)
  TRACE_STAGE_GETTERS(CS, ComputeShader)
#undef TRACE_STAGE_GETTERS
  void CSGetUnorderedAccessViews(UINT start, UINT n, UnorderedAccessView** u) override {
    inner_->CSGetUnorderedAccessViews(start, n, u);
  }
  void RSGetState(RasterizerState** s) override { inner_->RSGetState(s); }
  void RSGetViewports(UINT* n, VIEWPORT* v) override { inner_->RSGetViewports(n, v); }
  void RSGetScissorRects(UINT* n, RECT* r) override { inner_->RSGetScissorRects(n, r); }
  void OMGetRenderTargets(UINT n, RenderTargetView** rtvs, DepthStencilView** dsv) override {
    inner_->OMGetRenderTargets(n, rtvs, dsv);
  }
  void OMGetBlendState(BlendState** s, FLOAT factor[4], UINT* mask) override { inner_->OMGetBlendState(s, factor, mask); }
  void OMGetDepthStencilState(DepthStencilState** s, UINT* ref) override { inner_->OMGetDepthStencilState(s, ref); }

 private:
  void Record(const char* name, std::string args) {
    if (trace_->enabled) trace_->calls.push_back({name, std::move(args)});
  }

  DeviceContext* inner_;
  Trace* trace_;
};

}  // namespace

std::vector<std::string> Trace::Filter(const std::vector<std::string>& names) const {
  std::vector<std::string> out;
  for (const TraceCall& c : calls)
    for (const std::string& n : names)
      if (c.name == n) {
        out.push_back(c.name + "(" + c.args + ")");
        break;
      }
  return out;
}

std::string Trace::ToString() const {
  std::string s;
  for (const TraceCall& c : calls) s += c.name + "(" + c.args + ")\n";
  return s;
}

HRESULT CreateTracingContext(DeviceContext* inner, Trace* trace, DeviceContext** ppContext) {
  if (!inner || !trace || !ppContext) return E_INVALIDARG;
  *ppContext = new TracingContext(inner, trace);
  return S_OK;
}

}  // namespace rhi
