# Doxygen's input filter for the public headers (docs/Doxyfile): their comments are plain `//`
# lines, which Doxygen does not read as documentation. From `#pragma once` on, a comment line
# becomes `///` (the declaration below it), a comment after code on the same line `///<` (the
# member before it), and comment lines continuing such a trailing comment at its column `///<`.
BEGIN { opened = 0; trail = -1 }
/^#pragma once/ { opened = 1 }
{
  line = $0
  if (!opened) { print line; next }
  if (match(line, /^[ \t]*\/\/ ?/)) {
    col = index(line, "//")
    if (trail >= 0 && col == trail) { sub(/\/\//, "///<", line); print line; next }
    trail = -1; sub(/\/\//, "///", line); print line; next
  }
  if (match(line, /[;,{(]?[ \t]+\/\/ /) && line !~ /"[^"]*\/\/[^"]*"/ && line !~ /^[ \t]*#/) {
    trail = index(line, "  //") + 2; sub(/  \/\/ /, "  ///< ", line); print line; next
  }
  trail = -1; print line
}
