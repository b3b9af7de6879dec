# Applies PKM_SANITIZERS (e.g. "address;undefined") to every target defined afterwards: the module
# libraries, the pkm program and the examples are compiled with all of them, and every program
# links their runtimes. The test programs' own code (GoogleTest assertions and fixtures) gets
# AddressSanitizer only (pkm_test_sanitizer_flags(), called in tests/): UndefinedBehaviorSanitizer
# on the test files full of assertion templates was the largest part of the sanitizer build's time,
# and the code under test (the libraries, and the pkm program the CLI tests drive) keeps every check.
# AddressSanitizer itself must stay on everywhere: Eigen allocates differently when it is on, and
# memory allocated by instrumented code and freed by uninstrumented code is reported as a bad free.
#
# UndefinedBehaviorSanitizer's alignment check is left out: it doubled the compile time of the
# Eigen-heavy libraries (a check on every load and store of Eigen's expression templates), and the
# faults it finds are covered otherwise — x86-64 loads and stores misaligned scalars correctly,
# C++17's aligned new gives Eigen's fixed-size members their alignment, and Eigen's own assertion
# on unaligned fixed-size objects is on in this (assertions enabled) build.
if(PKM_SANITIZERS)
  list(JOIN PKM_SANITIZERS "," _pkm_san)
  set(PKM_SANITIZER_FLAG -fsanitize=${_pkm_san})
  add_compile_options(${PKM_SANITIZER_FLAG} -fno-omit-frame-pointer -fno-sanitize-recover=all)
  if("undefined" IN_LIST PKM_SANITIZERS)
    add_compile_options(-fno-sanitize=alignment)
  endif()
  add_link_options(-fsanitize=${_pkm_san})
endif()
# GCC's -Wmaybe-uninitialized reports false positives in instrumented code (seen at -O1 in
# libstdc++'s <regex> under ASan); the Release build keeps the warning.
if(PKM_SANITIZERS AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  add_compile_options(-Wno-maybe-uninitialized)
endif()

# pkm_test_sanitizer_flags(): in the calling directory, targets defined afterwards are compiled
# with AddressSanitizer only (when it is among PKM_SANITIZERS); they still link every runtime.
macro(pkm_test_sanitizer_flags)
  if(PKM_SANITIZERS)
    get_directory_property(_pkm_opts COMPILE_OPTIONS)
    list(REMOVE_ITEM _pkm_opts ${PKM_SANITIZER_FLAG})
    if("address" IN_LIST PKM_SANITIZERS)
      list(APPEND _pkm_opts -fsanitize=address)
    endif()
    # GCC 12 at -O1 reports std::string concatenations as out-of-bounds copies (GCC bug 105651, a
    # false positive); the Release build compiles the same tests with these warnings on.
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
      list(APPEND _pkm_opts -Wno-array-bounds -Wno-stringop-overread -Wno-stringop-overflow)
    endif()
    set_directory_properties(PROPERTIES COMPILE_OPTIONS "${_pkm_opts}")
  endif()
endmacro()

# pkm_sanitized_program_flags(<target>): the pkm program's own code is parsing and printing; in
# the sanitizer build it is compiled at -O0, which saves a third of its compile time and costs
# nothing at run time (the work is done in the instrumented, optimised libraries).
function(pkm_sanitized_program_flags target)
  if(PKM_SANITIZERS)
    target_compile_options(${target} PRIVATE -O0)
  endif()
endfunction()
