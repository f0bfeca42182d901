# Target defaults shared by every library, app and test.
function(revisit_defaults target)
  target_compile_features(${target} PUBLIC cxx_std_17)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic)
  if(REVISIT_FUZZ)
    # Coverage instrumentation for libFuzzer in every target, sanitizers on; undefined behaviour halts
    # (a report that only prints would let the fuzzer run past it).
    target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all
                           -fno-omit-frame-pointer)
    target_link_options(${target} PUBLIC -fsanitize=address,undefined)
  elseif(REVISIT_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
    target_link_options(${target} PUBLIC -fsanitize=address,undefined)
  endif()
endfunction()

# revisit_module(NAME DEPS ...): a static library revisit_NAME from src/NAME/*.cpp.
# Headers are included as "NAME/file.hpp" from src/.
function(revisit_module name)
  cmake_parse_arguments(ARG "" "" "DEPS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/${name}/*.cpp)
  if(NOT sources)
    message(STATUS "revisit: module ${name} has no sources yet")
    return()
  endif()
  add_library(revisit_${name} STATIC ${sources})
  target_include_directories(revisit_${name} PUBLIC ${PROJECT_SOURCE_DIR}/src)
  target_link_libraries(revisit_${name} PUBLIC ${ARG_DEPS})
  set_target_properties(revisit_${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  revisit_defaults(revisit_${name})
endfunction()
