# Runs a chapter (its quick mode, under ctest): the chapter's own checks decide (non-zero exit
# on a failed check), and its console output must fit in WIDTH columns.
#   cmake -DCOMMAND="prog;--quick;..." -DOUTPUT=file -DWIDTH_CHECK=line_width -DWIDTH=100
#         -P run_chapter.cmake
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE status OUTPUT_FILE "${OUTPUT}")
file(READ "${OUTPUT}" out)
message("${out}")
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the chapter failed (exit status ${status})")
endif()
execute_process(COMMAND "${WIDTH_CHECK}" "${OUTPUT}" "${WIDTH}" RESULT_VARIABLE wide
                ERROR_VARIABLE lines)
if(NOT wide EQUAL 0)
  message(FATAL_ERROR "console output wider than ${WIDTH} columns:\n${lines}")
endif()
