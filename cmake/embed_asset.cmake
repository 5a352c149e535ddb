# cmake -DIN=file -DOUT=file.inc -P embed_asset.cmake: wraps a web asset in a C++ raw string literal,
# so the dashboard serves its page from the binary (no files to install, no CDN: works offline).
file(READ "${IN}" content)
string(FIND "${content}" ")ASSET\"" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${IN} contains the raw-string delimiter )ASSET\"")
endif()
file(WRITE "${OUT}.tmp" "R\"ASSET(${content})ASSET\"\n")
file(RENAME "${OUT}.tmp" "${OUT}")
