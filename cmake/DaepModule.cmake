# daep_add_module(<name> [DEPS <targets>...] [INCLUDES <dirs>...])
# One library per module: libs/<name>/src/*.cpp with public headers in libs/<name>/include.
# The target is daep_<name>, aliased daep::<name>.
function(daep_add_module name)
  cmake_parse_arguments(ARG "" "" "DEPS;INCLUDES" ${ARGN})
  file(GLOB srcs CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/src/*.cpp")
  set(target daep_${name})
  if(srcs)
    add_library(${target} STATIC ${srcs})
    target_include_directories(${target} PUBLIC "${CMAKE_CURRENT_SOURCE_DIR}/include" ${ARG_INCLUDES})
    target_link_libraries(${target} PUBLIC ${ARG_DEPS})
    daep_set_warnings(${target})
  else()
    add_library(${target} INTERFACE)
    target_include_directories(${target} INTERFACE "${CMAKE_CURRENT_SOURCE_DIR}/include" ${ARG_INCLUDES})
    target_link_libraries(${target} INTERFACE ${ARG_DEPS})
  endif()
  add_library(daep::${name} ALIAS ${target})
endfunction()

function(daep_set_warnings target)
  # clang has no -Wshadow=local; its nearest is -Wshadow-uncaptured-local.
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic
    $<IF:$<CXX_COMPILER_ID:GNU>,-Wshadow=local,-Wshadow-uncaptured-local> -Wno-psabi)
endfunction()

# daep_add_gtest(<name> DEPS <targets>...): tests/<module>/*.cpp as one GoogleTest binary.
function(daep_add_gtest name)
  cmake_parse_arguments(ARG "" "" "DEPS" ${ARGN})
  file(GLOB srcs CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/*.cpp")
  if(NOT srcs)
    return()
  endif()
  add_executable(${name} ${srcs})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE
    DAEP_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    DAEP_SHARED_DIR="${PROJECT_SOURCE_DIR}/../shared")
  daep_set_warnings(${name})
  include(GoogleTest)
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 600)
endfunction()
