# The install test (ctest install.package): cmake --install into a fresh temporary prefix,
# configure and build tests/install/consumer against it as a user's project would, run the
# consumer, and run the installed `demo` from the prefix, which must find its effect files
# there (no source path is compiled in).
#   cmake -DBUILD_DIR=... -DCONSUMER_DIR=... -DWORK_DIR=... [-DLAUNCHER=ccache] -P run_install_test.cmake
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("$ ${ARGN}\n${out}${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}")
  endif()
  set(last_output "${out}${err}" PARENT_SCOPE)
endfunction()

# Outside the build tree, so that nothing found there could stand in for the prefix.
string(RANDOM LENGTH 8 suffix)
set(root /tmp/d3d11vk-install-${suffix})
set(prefix ${root}/prefix)
file(REMOVE_RECURSE ${root})
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

set(configure ${CMAKE_COMMAND} -S ${CONSUMER_DIR} -B ${root}/consumer -G Ninja
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${prefix})
if(LAUNCHER)
  list(APPEND configure -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
endif()
run(${configure})
run(${CMAKE_COMMAND} --build ${root}/consumer)
run(${root}/consumer/consumer)
if(NOT last_output MATCHES "consumer: ok")
  message(FATAL_ERROR "the consumer did not report ok")
endif()

# The installed demo, moved: its effect files come from <prefix>/share.
file(RENAME ${prefix} ${root}/moved)
run(${root}/moved/bin/demo --headless --out ${root}/out)
if(NOT EXISTS ${root}/out/demo_scene.png)
  message(FATAL_ERROR "the installed demo wrote no image")
endif()
file(REMOVE_RECURSE ${root})
