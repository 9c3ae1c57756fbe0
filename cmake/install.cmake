# cmake --install: the RHI and the effect runtime as a CMake package, their public headers,
# the tools and the project's effect files. A user project writes
#   find_package(d3d11_on_vulkan CONFIG REQUIRED)
#   target_link_libraries(app PRIVATE d3d11_on_vulkan::d3d11_on_vulkan)
# (README "Porting a D3D11 program"; tests/install builds such a project).
include(CMakePackageConfigHelpers)

# One target for users: the RHI, the HLSL compiler, the effect runtime and the texture loader.
add_library(d3d11_on_vulkan INTERFACE)
target_link_libraries(d3d11_on_vulkan INTERFACE rhi hlsl_compiler fx_runtime texture_files)
add_library(d3d11_on_vulkan::d3d11_on_vulkan ALIAS d3d11_on_vulkan)
# A sanitized build (./run sanitize) installs sanitized static libraries: a program linking
# them needs the sanitizers' runtimes, so the package says so (tests/install links such a one).
if(SANITIZE)
  target_link_options(d3d11_on_vulkan INTERFACE -fsanitize=address,undefined)
endif()

# The static libraries' private dependencies (rhi_spirv, rhi_states) are part of the link.
install(TARGETS d3d11_on_vulkan rhi rhi_spirv rhi_states hlsl_compiler fx_frontend fx_runtime texture_files
        EXPORT d3d11_on_vulkanTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY rhi/include/ textures/include/ effects/fx/include/ effects/hlsl/include/ effects/runtime/include/
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS fxtool replay demo RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY shaders_hlsl/ DESTINATION ${D3D11VK_SHADER_INSTALL_DIR})

set(package_dir ${CMAKE_INSTALL_LIBDIR}/cmake/d3d11_on_vulkan)
install(EXPORT d3d11_on_vulkanTargets NAMESPACE d3d11_on_vulkan:: DESTINATION ${package_dir})
configure_package_config_file(cmake/d3d11_on_vulkanConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/d3d11_on_vulkanConfig.cmake INSTALL_DESTINATION ${package_dir})
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/d3d11_on_vulkanConfig.cmake DESTINATION ${package_dir})
