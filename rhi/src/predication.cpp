// Predicated rendering (CreatePredicate, SetPredication, GetPredication).
//
// The predicate's result is read on the CPU when SetPredication is called,
// waiting for the GPU unless the predicate has QUERY_MISC_PREDICATEHINT. Vulkan's
// conditional rendering (VK_EXT_conditional_rendering) is not used: a query's
// result is the sum of several Vulkan queries (queries.h), which no single GPU
// value holds. The commands after SetPredication are recorded after the
// predicate's End, so its result is final by then, and reading it once is the
// same as D3D11's evaluation at each predicated call.
#include "context.h"
#include "queries.h"

namespace rhi::vk {

namespace {

bool IsPredicateKind(QUERY query) {
  return query == QUERY_OCCLUSION_PREDICATE || query == QUERY_SO_OVERFLOW_PREDICATE ||
         (query >= QUERY_SO_OVERFLOW_PREDICATE_STREAM0 && query <= QUERY_SO_OVERFLOW_PREDICATE_STREAM3);
}

}  // namespace

HRESULT DeviceImpl::CreatePredicate(const QUERY_DESC* pPredicateDesc, Predicate** ppPredicate) {
  if (!pPredicateDesc) return gpu_->Refuse("CreatePredicate: pPredicateDesc is NULL");
  if (!IsPredicateKind(pPredicateDesc->Query))
    return gpu_->Refuse("CreatePredicate: Query " + std::to_string(pPredicateDesc->Query) +
                        " is not QUERY_OCCLUSION_PREDICATE or QUERY_SO_OVERFLOW_PREDICATE[_STREAMn]");
  QueryImpl* query = nullptr;
  HRESULT hr = QueryImpl::Create(this, *pPredicateDesc, &query);
  if (SUCCEEDED(hr)) *ppPredicate = query;
  return hr;
}

void ContextImpl::SetPredication(Predicate* pPredicate, BOOL PredicateValue) {
  auto* predicate = static_cast<QueryImpl*>(pPredicate);
  predicate_ = predicate;
  predicateValue_ = PredicateValue;
  predicationSkips_ = false;
  if (!predicate) return;
  if (!IsPredicateKind(predicate->desc().Query)) {
    ReportDrawError("SetPredication: pPredicate is not a predicate (QUERY_OCCLUSION_PREDICATE or "
                    "QUERY_SO_OVERFLOW_PREDICATE*); rendering is not predicated");
    return;
  }
  if (predicate->active || !predicate->issued) {
    ReportDrawError("SetPredication: the predicate has not been ended since its last Begin; rendering is not "
                    "predicated");
    return;
  }
  Gpu& gpu = device_->gpu();
  if (!(predicate->desc().MiscFlags & QUERY_MISC_PREDICATEHINT)) gpu.WaitFor(predicate->endSerial);
  BOOL result = FALSE;
  // S_FALSE (not known yet, allowed by the hint, or a lost device): rendering goes ahead.
  if (predicate->GetData(&result, sizeof result, 0, *this) == S_OK) predicationSkips_ = result == PredicateValue;
}

void ContextImpl::GetPredication(Predicate** ppPredicate, BOOL* pPredicateValue) {
  if (ppPredicate) {
    *ppPredicate = predicate_.Get();
    if (*ppPredicate) (*ppPredicate)->AddRef();
  }
  if (pPredicateValue) *pPredicateValue = predicateValue_;
}

}  // namespace rhi::vk
