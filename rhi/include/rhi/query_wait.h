// Waiting for a query's result, the loop every D3D11 program writes: GetData
// returns S_FALSE until the GPU has produced the data (flag 0 flushes the
// context, so the wait always ends).
#pragma once

#include "rhi/rhi.h"

namespace rhi {

// Polls GetData(async, data, sizeof(T), 0) until it stops returning S_FALSE.
// Returns S_OK with *data filled in, or GetData's failure (the reason went to
// the device's message callback), after which *data is not to be used.
template <class T>
HRESULT WaitForData(DeviceContext* context, Asynchronous* async, T* data) {
  HRESULT hr;
  while ((hr = context->GetData(async, data, sizeof(T), 0)) == S_FALSE) {
  }
  return hr;
}

}  // namespace rhi
