#include "fx/shader_directory.h"

#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace fx {
namespace {

namespace fs = std::filesystem;

const fs::path kRelativeShaderDirectory = fs::path("share") / "d3d11_on_vulkan" / "shaders_hlsl";

fs::path ExecutableDirectory() {
  std::error_code error;
  fs::path exe = fs::read_symlink("/proc/self/exe", error);
  return error ? fs::current_path(error) : exe.parent_path();
}

std::string Locate() {
  if (const char* overridden = std::getenv(kShaderDirectoryVariable); overridden && *overridden) return overridden;
  const fs::path exeDir = ExecutableDirectory();
  std::error_code error;
  for (fs::path dir = exeDir;; dir = dir.parent_path()) {
    if (fs::is_directory(dir / kRelativeShaderDirectory, error)) return (dir / kRelativeShaderDirectory).string();
    if (dir == dir.parent_path()) break;
  }
  const fs::path installed = fs::path(FX_INSTALL_PREFIX) / kRelativeShaderDirectory;
  if (fs::is_directory(installed, error)) return installed.string();
  return (exeDir.parent_path() / kRelativeShaderDirectory).string();
}

}  // namespace

const std::string& ShaderDirectory() {
  static const std::string directory = Locate();
  return directory;
}

}  // namespace fx
