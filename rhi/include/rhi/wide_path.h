// Wide-character file names (the LPCWSTR paths D3D11 programs pass to D3DX and DirectXTK
// loaders) as the UTF-8 paths Linux opens. std::filesystem::path converts wchar_t through
// the C locale and throws for any non-ASCII character under the default "C" locale; this
// does not depend on the locale.
#pragma once

#include <string>

namespace rhi {

// `path` (UTF-32, as wchar_t is on Linux) in UTF-8; an invalid code point becomes U+FFFD.
std::string WidePathToUtf8(const wchar_t* path);

}  // namespace rhi
