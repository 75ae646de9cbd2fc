# Runs a benchmark that writes a CSV and checks the file's header line: scripts and results pages
# read these columns by name, so a change to them must be deliberate (the test says which).
#   cmake -DCOMMAND="prog;arg;..." -DCSV=path -DEXPECTED="a,b,c" -P CheckCsvColumns.cmake
file(REMOVE "${CSV}")
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE code OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "${COMMAND} exited with ${code}:\n${err}")
endif()
if(NOT EXISTS "${CSV}")
  message(FATAL_ERROR "${COMMAND} wrote no ${CSV}")
endif()
file(STRINGS "${CSV}" lines LIMIT_COUNT 1)
if(NOT lines STREQUAL EXPECTED)
  message(FATAL_ERROR "${CSV}: the columns changed\n  expected: ${EXPECTED}\n  written:  ${lines}")
endif()
message(STATUS "${CSV}: columns as expected")
