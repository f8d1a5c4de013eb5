# Runs a command and passes only when it exits 0 AND its output (stdout + stderr) matches PASS_REGEX.
# ctest's own PASS_REGULAR_EXPRESSION ignores the exit status, so a crash after printing the expected line
# would pass; this wrapper is used instead:
#   cmake -DPASS_REGEX=<regex> -P run_and_match.cmake <command> [args...]
if(NOT DEFINED PASS_REGEX)
  message(FATAL_ERROR "run_and_match.cmake: set -DPASS_REGEX=<regex>")
endif()
# Everything after the script's name is the command.
set(command "")
set(after_script FALSE)
math(EXPR last "${CMAKE_ARGC} - 1")
foreach(i RANGE ${last})
  if(after_script)
    string(REPLACE ";" "\\;" arg "${CMAKE_ARGV${i}}")  # keep a ';' inside one argument
    list(APPEND command "${arg}")
  elseif(CMAKE_ARGV${i} MATCHES "run_and_match\\.cmake$")
    set(after_script TRUE)
  endif()
endforeach()
if(NOT command)
  message(FATAL_ERROR "run_and_match.cmake: no command given")
endif()
execute_process(COMMAND ${command} RESULT_VARIABLE status OUTPUT_VARIABLE output ERROR_VARIABLE output)
message("${output}")
if(NOT status STREQUAL "0")
  message(FATAL_ERROR "FAILED: exit status ${status} (expected 0): ${command}")
endif()
if(NOT output MATCHES "${PASS_REGEX}")
  message(FATAL_ERROR "FAILED: the output does not match \"${PASS_REGEX}\"")
endif()
