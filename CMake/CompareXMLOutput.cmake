# Test: `<module> --xml` prints exactly the module's XML file.
execute_process(COMMAND ${EXE} --xml OUTPUT_VARIABLE printed RESULT_VARIABLE rc)
file(READ ${XML} expected)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${EXE} --xml exited with ${rc}")
endif()
if(NOT printed STREQUAL expected)
  message(FATAL_ERROR "${EXE} --xml does not print ${XML} exactly")
endif()
