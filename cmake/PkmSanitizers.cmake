# Applies PKM_SANITIZERS (e.g. "address;undefined") to every target defined afterwards.
if(PKM_SANITIZERS)
  list(JOIN PKM_SANITIZERS "," _pkm_san)
  add_compile_options(-fsanitize=${_pkm_san} -fno-omit-frame-pointer -fno-sanitize-recover=all)
  add_link_options(-fsanitize=${_pkm_san})
endif()
