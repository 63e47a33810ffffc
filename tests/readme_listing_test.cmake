# The README's "Use as a library" listing is exactly examples/library/main.cpp (the program
# the ctest library_example builds and runs): the ```cpp block after the line
# "<!-- listing: examples/library/main.cpp -->".
file(READ ${README} readme)
file(READ ${LISTING} listing)
set(marker "<!-- listing: examples/library/main.cpp -->\n```cpp\n")
string(FIND "${readme}" "${marker}" at)
if(at LESS 0)
  message(FATAL_ERROR "README: marker '<!-- listing: examples/library/main.cpp -->' + ```cpp not found")
endif()
string(LENGTH "${marker}" n)
math(EXPR at "${at} + ${n}")
string(SUBSTRING "${readme}" ${at} -1 rest)
string(FIND "${rest}" "```\n" end)
string(SUBSTRING "${rest}" 0 ${end} block)
if(NOT block STREQUAL listing)
  message(FATAL_ERROR "README listing differs from ${LISTING}: copy the file into the README")
endif()
