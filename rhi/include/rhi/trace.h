// A call trace of a DeviceContext, as a decorator: CreateTracingContext wraps a
// context and returns one that forwards every call to it unchanged and appends
// the call (name and key arguments) to a Trace. Nothing is recorded, and
// nothing costs, unless the application draws through the tracing context; the
// real context is not touched.
//
//   rhi::Trace trace;
//   rhi::ComPtr<rhi::DeviceContext> traced;
//   rhi::CreateTracingContext(context, &trace, traced.GetAddressOf());
//   ... render through traced.Get() ...
//   for (const rhi::TraceCall& c : trace.calls) printf("%s(%s)\n", c.name.c_str(), c.args.c_str());
//
// Arguments are recorded as text: counts, offsets, slots, formats and flags as
// numbers, bound objects as null / non-null ("obj"), marker and event names
// verbatim. SetMarker / BeginEvent / EndEvent (ID3DUserDefinedAnnotation) are
// recorded and forwarded like every other call; fx::EffectPass::Apply emits
// SetMarker("technique/pass"), so a trace shows which pass each draw belongs to.
#pragma once

#include <string>
#include <vector>

#include "rhi/rhi.h"

namespace rhi {

struct TraceCall {
  std::string name;  // the DeviceContext method, e.g. "DrawAuto", "SetMarker"
  std::string args;  // its key arguments, comma-separated
};

struct Trace {
  bool enabled = true;  // false: the tracing context forwards without recording
  std::vector<TraceCall> calls;

  void Clear() { calls.clear(); }
  // Calls whose name is one of `names` ({"Draw", "DrawAuto", "SetMarker"}), as
  // "name(args)" strings, in order.
  std::vector<std::string> Filter(const std::vector<std::string>& names) const;
  // Every call as "name(args)\n".
  std::string ToString() const;
};

// Wraps `inner` (which must outlive the returned context; the wrapper holds no
// reference to it, as device children hold none to their device). `trace` must
// outlive the returned context too. Returns E_INVALIDARG when either is null.
HRESULT CreateTracingContext(DeviceContext* inner, Trace* trace, DeviceContext** ppContext);

}  // namespace rhi
