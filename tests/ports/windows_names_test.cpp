// A port that includes the platform's own Windows definitions before the RHI's
// headers: TRUE, FALSE, SUCCEEDED, FAILED and the HRESULT codes arrive as
// macros, as <windows.h>/<winerror.h> (or DXVK's native windows_base.h) define
// them. The RHI's headers must compile and mean the same values, and the
// names must work unqualified after `using namespace rhi`.
#include <cstdint>
#include <cstdio>

// As DXVK's include/native/windows/windows_base.h and winerror.h spell them.
typedef int32_t HRESULT;
typedef int32_t BOOL;
#define TRUE 1
#define FALSE 0
#define SUCCEEDED(hr) (((HRESULT)(hr)) >= 0)
#define FAILED(hr) (((HRESULT)(hr)) < 0)
#define S_OK ((HRESULT)0L)
#define S_FALSE ((HRESULT)1L)
#define E_FAIL ((HRESULT)0x80004005L)
#define E_INVALIDARG ((HRESULT)0x80070057L)
#define E_OUTOFMEMORY ((HRESULT)0x8007000EL)
#define E_NOTIMPL ((HRESULT)0x80004001L)
#define DXGI_ERROR_UNSUPPORTED ((HRESULT)0x887A0004L)
#define DXGI_ERROR_WAS_STILL_DRAWING ((HRESULT)0x887A000AL)
#define DXGI_ERROR_DEVICE_REMOVED ((HRESULT)0x887A0005L)

#include "rhi/capture.h"
#include "rhi/format_info.h"
#include "rhi/query_wait.h"
#include "rhi/rhi.h"
#include "rhi/shader_bindings.h"
#include "rhi/swap_chain.h"
#include "rhi/trace.h"

using namespace rhi;

static_assert(FAILED(E_INVALIDARG) && FAILED(E_FAIL) && FAILED(DXGI_ERROR_DEVICE_REMOVED));
static_assert(SUCCEEDED(S_OK) && SUCCEEDED(S_FALSE) && TRUE == 1 && FALSE == 0);

// The RHI's refusal is the platform's E_INVALIDARG, tested with the platform's FAILED.
int main() {
  DEVICE_OPTIONS options;
  options.OnMessage = [](MESSAGE_CATEGORY, MESSAGE_SEVERITY, const char*) {};
  ComPtr<Device> device;
  ComPtr<DeviceContext> context;
  if (FAILED(CreateDevice(&options, device.GetAddressOf(), context.GetAddressOf()))) {
    std::fprintf(stderr, "CreateDevice failed\n");
    return 1;
  }
  ComPtr<BlendState> blend;
  const HRESULT refused = device->CreateBlendState(nullptr, blend.GetAddressOf());
  BLEND_DESC desc;
  desc.AlphaToCoverageEnable = TRUE;
  const HRESULT created = device->CreateBlendState(&desc, blend.GetAddressOf());
  if (refused != E_INVALIDARG || !FAILED(refused) || created != S_OK || !SUCCEEDED(created)) {
    std::fprintf(stderr, "HRESULTs differ: refused 0x%08X, created 0x%08X\n", unsigned(refused), unsigned(created));
    return 1;
  }
  std::printf("platform names and the RHI agree\n");
  return 0;
}
