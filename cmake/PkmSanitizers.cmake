# Applies PKM_SANITIZERS (e.g. "address;undefined") to every target defined afterwards.
if(PKM_SANITIZERS)
  list(JOIN PKM_SANITIZERS "," _pkm_san)
  add_compile_options(-fsanitize=${_pkm_san} -fno-omit-frame-pointer -fno-sanitize-recover=all)
  add_link_options(-fsanitize=${_pkm_san})
endif()
# GCC's -Wmaybe-uninitialized reports false positives in instrumented code (seen at -O1 in
# libstdc++'s <regex> under ASan); the Release build keeps the warning.
if(PKM_SANITIZERS AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  add_compile_options(-Wno-maybe-uninitialized)
endif()
