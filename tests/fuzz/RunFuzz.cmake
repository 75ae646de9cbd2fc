# Builds the glTF fuzzer with clang (-fsanitize=fuzzer,address,undefined) in its own build tree
# and runs it from seeds for SECONDS seconds. Fails on a finding (libFuzzer exits non-zero and
# leaves crash-* / leak-* / timeout-* files in FUZZ_DIR/findings).
# cmake -DSOURCE_DIR= -DFUZZ_DIR= -DCC= -DCXX= -DASSETS= -DDICT= -DSECONDS= [-DGENERATOR=] -P RunFuzz.cmake
foreach(v SOURCE_DIR FUZZ_DIR CC CXX ASSETS DICT SECONDS)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "RunFuzz.cmake: -D${v}= is required")
  endif()
endforeach()
if(NOT GENERATOR)
  set(GENERATOR Ninja)
endif()
set(flags "-fsanitize=address,undefined,fuzzer-no-link -fno-sanitize-recover=undefined -fno-omit-frame-pointer -g -O1")
execute_process(
  COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${FUZZ_DIR}/build -G ${GENERATOR}
          -DCMAKE_C_COMPILER=${CC} -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_BUILD_TYPE=RelWithDebInfo
          "-DCMAKE_C_FLAGS=${flags}" "-DCMAKE_CXX_FLAGS=${flags}" "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined"
          -DTHRONG_BUILD_FUZZERS=ON -DTHRONG_BUILD_TESTS=OFF -DTHRONG_BUILD_APPS=OFF -DTHRONG_BUILD_BENCHMARKS=OFF
          -DTHRONG_WERROR=OFF
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configuring the fuzz build failed")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${FUZZ_DIR}/build --target fuzz_gltf RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building fuzz_gltf failed")
endif()

# Seeds: the assets as they are (no copies in the repository), plus small generated documents.
set(seeds ${FUZZ_DIR}/seeds)
file(REMOVE_RECURSE ${seeds})
file(MAKE_DIRECTORY ${seeds} ${FUZZ_DIR}/corpus ${FUZZ_DIR}/findings)
file(GLOB_RECURSE assets ${ASSETS}/minimal/*.gl* ${ASSETS}/malformed/*.gl* ${ASSETS}/characters/*.glb
     ${ASSETS}/town/kenney_city_builder/road-straight.glb)
set(i 0)
foreach(a IN LISTS assets)
  if(a MATCHES "\\.(gltf|glb)$")
    get_filename_component(ext ${a} EXT)
    file(COPY_FILE ${a} ${seeds}/asset${i}${ext})
    math(EXPR i "${i} + 1")
  endif()
endforeach()
# A two-joint rig with a skinned triangle and a clip (base64: positions, joints, weights, times, rotations).
set(b64 "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAAAAAAAAAEAAAAAAAEAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAAD8AAAA/AAAAAAAAAAAAAIA/AAAAAAAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAAAAAAAAAD0BDU/9AQ1Pw==")
file(WRITE ${seeds}/rig.gltf "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0,2]}],
\"nodes\":[{\"name\":\"a\",\"children\":[1]},{\"name\":\"b\",\"translation\":[0,1,0]},{\"mesh\":0,\"skin\":0}],
\"skins\":[{\"joints\":[0,1]}],
\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"JOINTS_0\":1,\"WEIGHTS_0\":2}}]}],
\"animations\":[{\"samplers\":[{\"input\":3,\"output\":4,\"interpolation\":\"LINEAR\"}],\"channels\":[{\"sampler\":0,\"target\":{\"node\":1,\"path\":\"rotation\"}}]}],
\"buffers\":[{\"byteLength\":148,\"uri\":\"data:application/octet-stream;base64,${b64}\"}],
\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":36},{\"buffer\":0,\"byteOffset\":36,\"byteLength\":24},
{\"buffer\":0,\"byteOffset\":60,\"byteLength\":48},{\"buffer\":0,\"byteOffset\":108,\"byteLength\":8},{\"buffer\":0,\"byteOffset\":116,\"byteLength\":32}],
\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},{\"bufferView\":1,\"componentType\":5123,\"count\":3,\"type\":\"VEC4\"},
{\"bufferView\":2,\"componentType\":5126,\"count\":3,\"type\":\"VEC4\"},{\"bufferView\":3,\"componentType\":5126,\"count\":2,\"type\":\"SCALAR\"},
{\"bufferView\":4,\"componentType\":5126,\"count\":2,\"type\":\"VEC4\",\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":3,\"componentType\":5121},\"values\":{\"bufferView\":4}}}]}
")
file(WRITE ${seeds}/static.gltf "{\"asset\":{\"version\":\"2.0\"},\"nodes\":[{\"mesh\":0,\"matrix\":[1,0,0,0,0,1,0,0,0,0,1,0,5,0,0,1]}],
\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"mode\":5,\"material\":0}]}],\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,0,0,1]}}],
\"buffers\":[{\"byteLength\":36,\"uri\":\"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA\"}],
\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}]}
")
file(WRITE ${seeds}/empty.gltf "{\"asset\":{\"version\":\"2.0\"},\"skins\":[{\"joints\":[0]}],\"nodes\":[{}]}")

execute_process(
  COMMAND ${FUZZ_DIR}/build/tests/fuzz/fuzz_gltf -max_total_time=${SECONDS} -timeout=20 -rss_limit_mb=2560
          -dict=${DICT} -artifact_prefix=${FUZZ_DIR}/findings/ -print_final_stats=1
          ${FUZZ_DIR}/corpus ${seeds}
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "fuzz_gltf found a problem (exit ${rc}); the input is in ${FUZZ_DIR}/findings")
endif()
message(STATUS "fuzz_gltf: ${SECONDS} s without a finding")
