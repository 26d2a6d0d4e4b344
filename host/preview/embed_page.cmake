# Writes OUTPUT: preview_page() returning the file INPUT as a raw string literal.
file(READ ${INPUT} contents)
file(WRITE ${OUTPUT} "// Generated from host/preview/page.html by embed_page.cmake; do not edit.
#include \"preview/preview_page.hpp\"

namespace clmarch {

const std::string& preview_page() {
  static const std::string page = R\"CLMARCH_PAGE(${contents})CLMARCH_PAGE\";
  return page;
}

}  // namespace clmarch
")
