# expect_files(DIR WHAT NAME...): DIR must hold exactly NAME... (paths relative to DIR, at any depth, folders and
# hidden entries included, so a leftover staging folder or temporary file fails), else a fatal error naming WHAT.
function(expect_files dir what)
  file(GLOB_RECURSE written LIST_DIRECTORIES true RELATIVE ${dir} ${dir}/* ${dir}/.*)
  list(REMOVE_DUPLICATES written)
  list(SORT written)
  set(expected ${ARGN})
  list(SORT expected)
  if(NOT written STREQUAL "${expected}")
    message(FATAL_ERROR "${what}: ${dir} holds '${written}', expected '${expected}'")
  endif()
  message(STATUS "${what}: ${written}")
endfunction()
