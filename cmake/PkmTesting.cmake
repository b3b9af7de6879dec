# pkm_add_test_program(<target> <module> FILES ... [LIBS ...]): builds the test files (each
# tests/<module>/<name>_test.cpp, compiled on its own) into one gtest program and registers its
# tests with CTest, one CTest test per test case. It links the module they test (pkm::<module>,
# when there is such a library: the CLI tests run the pkm program instead) and LIBS, nothing else.
include(GoogleTest)

# pkm_test_code_flags(<target>): the test programs' own code (assertions, fixtures, the loops that
# call the code under test) is compiled at -O0, in every build: it runs once per test, while the
# code under test keeps its build's optimisation. GoogleTest's macros and matchers make test files
# expensive to optimise: -O0 compiles them about a third faster. In sanitizer builds the test code
# also gets no debug information (GoogleTest reports its own failures by file and line).
function(pkm_test_code_flags target)
  target_compile_options(${target} PRIVATE -O0)
  if(PKM_SANITIZERS)
    target_compile_options(${target} PRIVATE -g0)
  endif()
endfunction()
function(pkm_add_test_program target module)
  cmake_parse_arguments(ARG "" "" "FILES;LIBS" ${ARGN})
  add_executable(${target} ${ARG_FILES})
  set(module_lib)
  if(TARGET pkm::${module})
    set(module_lib pkm::${module})
  endif()
  target_link_libraries(${target} PRIVATE ${module_lib} ${ARG_LIBS} pkm_test_support GTest::gtest
                                          GTest::gmock GTest::gtest_main)
  pkm_set_warnings(${target})
  pkm_test_code_flags(${target})
  pkm_use_pch(${target} pkm_pch_test)
  set_target_properties(${target} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
  # Each test file keeps its helpers in `namespace PKM_TEST_NS { ... }` instead of an anonymous
  # namespace: in a unity batch PKM_TEST_NS names a namespace of its own per file (CMake's
  # UNITY_BUILD_UNIQUE_ID), so two files' helpers of the same name neither clash nor overload
  # each other; without unity builds it is one name, and each file is its own translation unit.
  if(PKM_UNITY_BUILD)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8
                                               UNITY_BUILD_UNIQUE_ID PKM_TEST_NS)
  else()
    target_compile_definitions(${target} PRIVATE PKM_TEST_NS=pkm_test_local)
  endif()
  gtest_discover_tests(${target} DISCOVERY_TIMEOUT 60
                       PROPERTIES ENVIRONMENT "PKM_SOURCE_DIR=${PROJECT_SOURCE_DIR}")
endfunction()
