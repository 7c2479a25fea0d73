# Writes a C++ source defining the module's XML description as an exported, NUL-terminated char
# array (what Slicer's loader reads with dlsym). Run with -DXML=<file> -DOUT=<file>.
file(READ ${XML} content)
set(delimiter "colonmapxml")
string(FIND "${content}" ")${delimiter}\"" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${XML} contains the raw-string delimiter ${delimiter}")
endif()
file(WRITE ${OUT}.tmp
"// Generated from ${XML}: do not edit.\n"
"extern \"C\" __attribute__((visibility(\"default\"))) const char XMLModuleDescription[] =\n"
"R\"${delimiter}(${content})${delimiter}\";\n")
file(RENAME ${OUT}.tmp ${OUT})
