# The fuzzers' two steps, run by CTest:
# - MODE=build: configures a separate build in FUZZ_DIR/build with clang, every target compiled
#   with -fsanitize=address,undefined,fuzzer-no-link, and builds the four fuzz targets;
#   cmake -DMODE=build -DSOURCE_DIR= -DFUZZ_DIR= -DCC= -DCXX= -DASSETS= [-DGENERATOR=] -P RunFuzz.cmake
# - MODE=run: runs fuzzer FUZZER for SECONDS seconds from the committed corpus CORPUS (read-only
#   seeds), the shared assets matching ASSET_GLOB (';'-separated, relative to ASSETS; used in place,
#   never copied into the repository) and what earlier runs found (FUZZ_DIR/corpus/NAME). Fails on
#   a finding: libFuzzer exits non-zero and leaves crash-* / leak-* / timeout-* in FUZZ_DIR/findings.
#   cmake -DMODE=run -DFUZZ_DIR= -DFUZZER= -DNAME= -DCORPUS= -DDICT= -DASSETS= -DASSET_GLOB= -DSECONDS= -P RunFuzz.cmake
if(MODE STREQUAL "build")
  set(required SOURCE_DIR FUZZ_DIR CC CXX ASSETS)
elseif(MODE STREQUAL "run")
  set(required FUZZ_DIR FUZZER NAME CORPUS DICT ASSETS SECONDS)
else()
  message(FATAL_ERROR "RunFuzz.cmake: -DMODE=build or -DMODE=run is required")
endif()
foreach(v IN LISTS required)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "RunFuzz.cmake: -D${v}= is required")
  endif()
endforeach()

if(MODE STREQUAL "build")
  if(NOT GENERATOR)
    set(GENERATOR Ninja)
  endif()
  set(flags "-fsanitize=address,undefined,fuzzer-no-link -fno-sanitize-recover=undefined -fno-omit-frame-pointer -g -O1")
  execute_process(
    COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${FUZZ_DIR}/build -G ${GENERATOR}
            -DCMAKE_C_COMPILER=${CC} -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_BUILD_TYPE=RelWithDebInfo
            "-DCMAKE_C_FLAGS=${flags}" "-DCMAKE_CXX_FLAGS=${flags}" "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined"
            -DTHRONG_BUILD_FUZZERS=ON -DTHRONG_BUILD_TESTS=OFF -DTHRONG_BUILD_APPS=OFF -DTHRONG_BUILD_BENCHMARKS=OFF
            -DTHRONG_WERROR=OFF -DTHRONG_FUZZ_ASSETS=${ASSETS}
    RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "configuring the fuzz build failed")
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${FUZZ_DIR}/build --target fuzz_gltf fuzz_glb_startup fuzz_scene fuzz_messages RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "building the fuzzers failed")
  endif()
  return()
endif()

# Seeds: the committed corpus and the assets, each as it is; the working corpus grows in FUZZ_DIR.
set(work ${FUZZ_DIR}/corpus/${NAME})
file(MAKE_DIRECTORY ${work} ${FUZZ_DIR}/findings ${FUZZ_DIR}/assets-${NAME})
set(seeds ${CORPUS})
if(ASSET_GLOB)
  set(patterns)
  foreach(g IN LISTS ASSET_GLOB)
    list(APPEND patterns ${ASSETS}/${g})
  endforeach()
  file(GLOB assets ${patterns})
  # libFuzzer reads seed folders, not files: link the chosen assets into one (no copies).
  file(REMOVE_RECURSE ${FUZZ_DIR}/assets-${NAME})
  file(MAKE_DIRECTORY ${FUZZ_DIR}/assets-${NAME})
  set(i 0)
  foreach(a IN LISTS assets)
    get_filename_component(ext ${a} EXT)
    file(CREATE_LINK ${a} ${FUZZ_DIR}/assets-${NAME}/asset${i}${ext} SYMBOLIC)
    math(EXPR i "${i} + 1")
  endforeach()
  list(APPEND seeds ${FUZZ_DIR}/assets-${NAME})
endif()
execute_process(
  COMMAND ${FUZZ_DIR}/build/tests/fuzz/${FUZZER} -max_total_time=${SECONDS} -timeout=30 -rss_limit_mb=2560
          -dict=${DICT} -artifact_prefix=${FUZZ_DIR}/findings/${NAME}- -print_final_stats=1
          ${work} ${seeds}
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${FUZZER} found a problem (exit ${rc}); the input is in ${FUZZ_DIR}/findings")
endif()
message(STATUS "${FUZZER}: ${SECONDS} s without a finding")
