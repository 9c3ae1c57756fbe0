// ID3D11Device's private data: bytes or an interface reference per GUID.
#pragma once

#include <functional>
#include <mutex>
#include <vector>

#include "rhi/rhi.h"

namespace rhi {

class PrivateDataStore {
 public:
  ~PrivateDataStore();
  // D3D11's semantics: a copy of the bytes; null data removes the entry.
  HRESULT Set(REFGUID guid, UINT size, const void* data);
  // Keeps a reference to `object` (null removes the entry); GetPrivateData returns the pointer, AddRef'd.
  HRESULT SetInterface(REFGUID guid, const Unknown* object);
  // null data: the size only; too small a buffer: DXGI_ERROR_MORE_DATA; no entry: DXGI_ERROR_NOT_FOUND.
  HRESULT Get(REFGUID guid, UINT* size, void* data) const;

 private:
  struct Entry {
    GUID guid;
    std::vector<uint8_t> bytes;
    Unknown* object = nullptr;  // SetInterface's reference
  };
  void Remove(REFGUID guid);
  mutable std::mutex mutex_;
  std::vector<Entry> entries_;
};

}  // namespace rhi
