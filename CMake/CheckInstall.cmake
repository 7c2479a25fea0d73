# Test: `cmake --install` puts every module's program, library and XML in
# <prefix>/lib/ColonMap/cli-modules, and the installed program runs from there.
# Run with -DBUILD=<build tree> -DPREFIX=<scratch prefix> -DMODULES=<a|b|c>.
file(REMOVE_RECURSE ${PREFIX})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD} --prefix ${PREFIX}
  RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc})")
endif()
string(REPLACE "|" ";" MODULES "${MODULES}")
foreach(m ${MODULES})
  foreach(f ${m} lib${m}Lib.so ${m}.xml)
    if(NOT EXISTS ${PREFIX}/lib/ColonMap/cli-modules/${f})
      message(FATAL_ERROR "not installed: lib/ColonMap/cli-modules/${f}")
    endif()
  endforeach()
  execute_process(COMMAND ${PREFIX}/lib/ColonMap/cli-modules/${m} --xml
    RESULT_VARIABLE rc OUTPUT_VARIABLE printed)
  file(READ ${PREFIX}/lib/ColonMap/cli-modules/${m}.xml expected)
  if(NOT rc EQUAL 0 OR NOT printed STREQUAL expected)
    message(FATAL_ERROR "installed ${m} does not run or does not print its XML")
  endif()
endforeach()
file(REMOVE_RECURSE ${PREFIX})
