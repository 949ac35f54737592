# Run a command that must fail: a non-zero exit status and a message on standard error that
# matches EXPECT.  Used to check that bad input gives a clear error, never a crash or a run.
#   cmake -DCOMMAND="prog;--opt;value" -DEXPECT="regex" -P expect_failure.cmake
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err
                TIMEOUT 60)
if(status EQUAL 0)
  message(FATAL_ERROR "expected a failure, but the command succeeded:\n${out}\n${err}")
endif()
if(status MATCHES "[A-Za-z]")
  message(FATAL_ERROR "expected a clean error exit, got '${status}' (a crash or time-out?)\n${err}")
endif()
if(NOT err MATCHES "${EXPECT}")
  message(FATAL_ERROR "exit status ${status}, but standard error does not match '${EXPECT}':\n${err}")
endif()
message(STATUS "failed as expected (status ${status}): ${err}")
