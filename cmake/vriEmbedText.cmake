# Writes OUTPUT, a C++ file defining `const std::string_view vri::NAME` with the text of INPUT, so that a
# tool carries the file and needs nothing installed beside it (the results viewer's script and style).
# Run as cmake -DINPUT=... -DOUTPUT=... -DNAME=... -P vriEmbedText.cmake, at build time.
file(READ ${INPUT} text)
set(delimiter "vri_embed")  # a raw string delimiter has at most 16 characters
string(FIND "${text}" ")${delimiter}\"" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${INPUT} contains )${delimiter}\", which would end the raw string that embeds it")
endif()
file(WRITE ${OUTPUT}.tmp "// Generated from ${INPUT} by cmake/vriEmbedText.cmake.\n#include <string_view>\n"
     "namespace vri {\nextern const std::string_view ${NAME};\n"
     "const std::string_view ${NAME} = R\"${delimiter}(${text})${delimiter}\";\n}  // namespace vri\n")
file(COPY_FILE ${OUTPUT}.tmp ${OUTPUT} ONLY_IF_DIFFERENT)
file(REMOVE ${OUTPUT}.tmp)
