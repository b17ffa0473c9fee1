# Runs one command and passes only when it FAILS the way a user should see it
# fail: a non-zero exit status (optionally exactly EXPECT_EXIT), a message
# matching EXPECT_REGEX on stdout or stderr, and no sign of a crash.
#
#   cmake -DCOMMAND="prog^^arg1^^arg2" -DEXPECT_REGEX="file\\.csv:7: .*"
#         [-DEXPECT_EXIT=1] [-DWORKING_DIRECTORY=dir] -P expect_failure.cmake
#
# COMMAND separates its words with "^^" (ctest would split a ';'-list into
# separate arguments of cmake itself). EXPECT_REGEX is a CMake regular
# expression; it must not contain ';'.

if("${COMMAND}" STREQUAL "")
  message(FATAL_ERROR "expect_failure.cmake: COMMAND is not set")
endif()
if("${EXPECT_REGEX}" STREQUAL "")
  message(FATAL_ERROR "expect_failure.cmake: EXPECT_REGEX is not set")
endif()
string(REPLACE "^^" ";" command_list "${COMMAND}")
if("${WORKING_DIRECTORY}" STREQUAL "")
  set(WORKING_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}")
endif()

execute_process(
  COMMAND ${command_list}
  WORKING_DIRECTORY "${WORKING_DIRECTORY}"
  RESULT_VARIABLE status
  OUTPUT_VARIABLE out
  ERROR_VARIABLE err
  TIMEOUT 60)
set(all "${out}${err}")
string(REPLACE ";" " " shown "${command_list}")
set(report "command: ${shown}\nexit status: ${status}\n--- stdout ---\n${out}--- stderr ---\n${err}")

# A signal or a timeout leaves a text such as "Child aborted" instead of a number.
if(NOT status MATCHES "^[0-9]+$")
  message(FATAL_ERROR "expected a clean non-zero exit, got '${status}'\n${report}")
endif()
if(status EQUAL 0)
  message(FATAL_ERROR "expected failure, but the command succeeded\n${report}")
endif()
if(NOT "${EXPECT_EXIT}" STREQUAL "" AND NOT status EQUAL EXPECT_EXIT)
  message(FATAL_ERROR "expected exit status ${EXPECT_EXIT}, got ${status}\n${report}")
endif()
# User errors must be reported as such, not as crashes or internal errors.
foreach(crash "internal error" "PETSC ERROR" "terminate called" "Segmentation fault"
              "Assertion")
  string(FIND "${all}" "${crash}" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "the failure looks like a crash ('${crash}'), not a user error\n${report}")
  endif()
endforeach()
if(NOT all MATCHES "${EXPECT_REGEX}")
  message(FATAL_ERROR "the output does not match\n  ${EXPECT_REGEX}\n${report}")
endif()
message(STATUS "failed as expected (exit ${status}): ${all}")
