# colonmap_add_cli_module(<Name> SOURCES <files> [LIBRARIES <targets>])
#
# Adds a Slicer CLI module the way SlicerExecutionModel's SEMMacroBuildCLI does (DESIGN §3.1a):
#  - <Name>Body: the module's code (it defines colonmap::modules::Run<Name>, the body run by
#    cli::RunModule) and its XML as colonmap::modules::<Name>XML, for in-process reuse;
#  - lib<Name>Lib.so: the body plus a generated ModuleEntryPoint, exporting only
#    XMLModuleDescription (the embedded <Name>.xml) and ModuleEntryPoint, C linkage; all else
#    hidden;
#  - <Name>: a one-line main over the library;
#  - <Name>.xml copied beside both, in the build tree's lib/ColonMap/cli-modules and on install;
#  - tests: the XML validates against the shared schema and `<Name> --xml` prints it exactly.
function(colonmap_add_cli_module name)
  cmake_parse_arguments(M "" "" "SOURCES;LIBRARIES" ${ARGN})
  set(xml ${CMAKE_CURRENT_SOURCE_DIR}/${name}.xml)
  foreach(form entry body)
    set(generated_${form} ${CMAKE_CURRENT_BINARY_DIR}/${name}XML_${form}.cxx)
    add_custom_command(OUTPUT ${generated_${form}}
      COMMAND ${CMAKE_COMMAND} -DXML=${xml} -DOUT=${generated_${form}} -DNAME=${name} -DFORM=${form}
              -P ${PROJECT_SOURCE_DIR}/CMake/EmbedXML.cmake
      DEPENDS ${xml} ${PROJECT_SOURCE_DIR}/CMake/EmbedXML.cmake
      COMMENT "Embedding ${name}.xml (${form})")
  endforeach()

  # The body, compiled once: colonmap::modules::Run<Name> and <Name>XML. Static and
  # position-independent so both the module's own library and ColonSupineProne link it.
  add_library(${name}Body STATIC ${M_SOURCES} ${generated_body})
  target_link_libraries(${name}Body PUBLIC ColonMapCLI ${M_LIBRARIES})
  set_target_properties(${name}Body PROPERTIES
    POSITION_INDEPENDENT_CODE ON
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON)

  add_library(${name}Lib SHARED ${generated_entry})
  target_link_libraries(${name}Lib PRIVATE ${name}Body)
  set_target_properties(${name}Lib PROPERTIES
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON
    LIBRARY_OUTPUT_DIRECTORY ${ColonMap_CLI_MODULES_DIR}
    LINK_DEPENDS ${PROJECT_SOURCE_DIR}/CMake/CLIModule.map)
  target_link_options(${name}Lib PRIVATE
    -Wl,--version-script=${PROJECT_SOURCE_DIR}/CMake/CLIModule.map -Wl,--no-undefined)

  add_executable(${name} ${PROJECT_SOURCE_DIR}/CMake/CLIModuleMain.cxx)
  target_link_libraries(${name} PRIVATE ${name}Lib ColonMapProgramStart)
  set_target_properties(${name} PROPERTIES
    RUNTIME_OUTPUT_DIRECTORY ${ColonMap_CLI_MODULES_DIR}
    BUILD_RPATH "\$ORIGIN"
    INSTALL_RPATH "\$ORIGIN")

  configure_file(${xml} ${ColonMap_CLI_MODULES_DIR}/${name}.xml COPYONLY)
  install(TARGETS ${name} ${name}Lib
    RUNTIME DESTINATION ${ColonMap_CLI_INSTALL_DIR}
    LIBRARY DESTINATION ${ColonMap_CLI_INSTALL_DIR})
  install(FILES ${xml} DESTINATION ${ColonMap_CLI_INSTALL_DIR})

  set_property(GLOBAL APPEND PROPERTY COLONMAP_CLI_MODULES ${name})
  add_test(NAME ${name}.XMLValidates
    COMMAND ${XMLLINT_EXECUTABLE} --noout --schema ${ColonMap_SHARED_DIR}/schemas/ModuleDescription.xsd ${xml})
  add_test(NAME ${name}.XMLFlagPrintsFile
    COMMAND ${CMAKE_COMMAND} -DEXE=$<TARGET_FILE:${name}> -DXML=${xml}
            -P ${PROJECT_SOURCE_DIR}/CMake/CompareXMLOutput.cmake)
endfunction()
