# Writes a C++ source defining a module's XML description as a NUL-terminated char array.
# Run with -DXML=<file> -DOUT=<file> -DNAME=<module> -DFORM=<entry|body>:
#  entry: the exported `XMLModuleDescription` Slicer's loader reads with dlsym, and the
#         module's ModuleEntryPoint over the body colonmap::modules::Run<NAME>;
#  body:  colonmap::modules::<NAME>XML, for modules that run other modules in-process
#         (ColonSupineProne), kept apart from the exported symbol.
file(READ ${XML} content)
set(delimiter "colonmapxml")
string(FIND "${content}" ")${delimiter}\"" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${XML} contains the raw-string delimiter ${delimiter}")
endif()
if(FORM STREQUAL "entry")
  file(WRITE ${OUT}.tmp
"// Generated from ${XML}: do not edit.\n"
"#include \"CLI/ModuleRunner.h\"\n"
"namespace colonmap::modules { void Run${NAME}(cli::ModuleContext& ctx); }\n"
"COLONMAP_CLI_EXPORT const char XMLModuleDescription[] =\n"
"R\"${delimiter}(${content})${delimiter}\";\n"
"COLONMAP_CLI_EXPORT int ModuleEntryPoint(int argc, char* argv[]) {\n"
"  return colonmap::cli::RunModule(\"${NAME}\", XMLModuleDescription, argc, argv,\n"
"                                  &colonmap::modules::Run${NAME});\n"
"}\n")
else()
  file(WRITE ${OUT}.tmp
"// Generated from ${XML}: do not edit.\n"
"namespace colonmap::modules {\n"
"extern const char ${NAME}XML[];\n"
"const char ${NAME}XML[] =\n"
"R\"${delimiter}(${content})${delimiter}\";\n"
"}  // namespace colonmap::modules\n")
endif()
file(RENAME ${OUT}.tmp ${OUT})
