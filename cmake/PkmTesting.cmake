# pkm_add_test(<module> <name>): builds tests/<module>/<name>_test.cpp as one gtest binary
# and registers its tests with CTest.
include(GoogleTest)
function(pkm_add_test module name)
  set(target test_${module}_${name})
  add_executable(${target} ${CMAKE_CURRENT_SOURCE_DIR}/${module}/${name}_test.cpp)
  target_link_libraries(${target} PRIVATE pkm::pkm pkm_test_support GTest::gtest GTest::gmock
                                          GTest::gtest_main)
  pkm_set_warnings(${target})
  set_target_properties(${target} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
  gtest_discover_tests(${target} DISCOVERY_TIMEOUT 60
                       PROPERTIES ENVIRONMENT "PKM_SOURCE_DIR=${PROJECT_SOURCE_DIR}")
endfunction()
