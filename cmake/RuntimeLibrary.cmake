# A library coinroll opens when it first calls into it (src/io/runtime_library.h) instead of linking
# it: gives `target`'s forwarders COINROLL_<prefix>_SONAME, read from the file pkg-config found (the
# headers' version), and COINROLL_<prefix>_PACKAGE, the Debian package holding it, for their
# messages. The packages also go to the .deb's Depends (COINROLL_RUNTIME_PACKAGES), which
# dpkg-shlibdeps, reading only what is linked, no longer finds.
function(coinroll_runtime_library target prefix library_file)
  execute_process(COMMAND ${CMAKE_OBJDUMP} -p ${library_file} OUTPUT_VARIABLE dump RESULT_VARIABLE failed
                  ERROR_QUIET)
  if(failed OR NOT dump MATCHES "SONAME +([^\n]+)")
    message(FATAL_ERROR "cannot read the soname of ${library_file} (${CMAKE_OBJDUMP} -p)")
  endif()
  string(STRIP "${CMAKE_MATCH_1}" soname)
  execute_process(COMMAND dpkg-query -S "*/${soname}" OUTPUT_VARIABLE owner ERROR_QUIET)
  if(owner MATCHES "^([^:, \n]+)")
    set(package ${CMAKE_MATCH_1})
    set_property(GLOBAL APPEND PROPERTY COINROLL_RUNTIME_PACKAGES ${package})
  else()
    set(package "the package that provides ${soname}")
  endif()
  target_compile_definitions(${target} PRIVATE COINROLL_${prefix}_SONAME="${soname}"
                                                COINROLL_${prefix}_PACKAGE="${package}")
endfunction()
