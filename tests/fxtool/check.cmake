# Runs a program (fxtool, replay, demo) once and checks its exit code and output (ctest, see CMakeLists.txt).
#   cmake -DPROGRAM=path -DARGS="a|b|c" -DEXPECT_RC=N [-DEXPECT_STDOUT=regex]... [-DEXPECT_STDERR=regex] -P check.cmake
# '|' separates arguments; EXPECT_STDOUT / EXPECT_STDERR are '|'-free regexes,
# several may be given in EXPECT_STDOUT separated by '@@'.
string(REPLACE "|" ";" args "${ARGS}")
execute_process(COMMAND ${PROGRAM} ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${PROGRAM} ${args}\n--- exit ${rc}\n--- stdout\n${out}--- stderr\n${err}")
if(NOT "${rc}" STREQUAL "${EXPECT_RC}")
  message(FATAL_ERROR "exit code ${rc}, expected ${EXPECT_RC}")
endif()
if(DEFINED EXPECT_STDOUT)
  string(REPLACE "@@" ";" patterns "${EXPECT_STDOUT}")
  foreach(p IN LISTS patterns)
    if(NOT out MATCHES "${p}")
      message(FATAL_ERROR "stdout does not match: ${p}")
    endif()
  endforeach()
endif()
if(DEFINED EXPECT_STDERR AND NOT err MATCHES "${EXPECT_STDERR}")
  message(FATAL_ERROR "stderr does not match: ${EXPECT_STDERR}")
endif()
