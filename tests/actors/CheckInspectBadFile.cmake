# cmake -DINSPECT=<throng-inspect> -DFILE=<bad glTF> -DWHERE=<pointer> -P CheckInspectBadFile.cmake
# throng-inspect must exit 1 with exactly one line "file: where: problem".
execute_process(COMMAND ${INSPECT} ${FILE} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 1)
  message(FATAL_ERROR "exit code ${rc}, expected 1")
endif()
string(STRIP "${err}" line)
if(line MATCHES "\n" OR NOT "${out}" STREQUAL "")
  message(FATAL_ERROR "expected one line on stderr and nothing on stdout, got:\n${out}${err}")
endif()
string(FIND "${line}" "${FILE}: ${WHERE}: " at)
if(NOT at EQUAL 0)
  message(FATAL_ERROR "expected '${FILE}: ${WHERE}: problem', got '${line}'")
endif()
