# no_process_words.cmake can fail: on a small tree with planted words (in text, in a safetensors header, after a
# CRLF and at the very start of a file) it must exit non-zero and name each one as path:line, and no more:
# not the look-alikes of clean.txt, not a binary file, not what git ignores or a build tree holds. Run on the
# tree as plain files and again as a git work tree; then, the planted files removed, it must pass. Usage:
#   cmake -DCHECK=no_process_words.cmake -DOUT=<dir> -P planted_words.cmake
cmake_minimum_required(VERSION 3.25)
# The words are assembled here so that this file passes the check itself.
set(S "sess")
set(S_UPPER "SESS")
set(I "iss")
set(H "#")

file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${OUT}/src" "${OUT}/build/x" "${OUT}/ignored")
file(WRITE "${OUT}/clean.txt"
     "The demo's scripted ${S}ion (${S}ion.txt) of 3 frames, tissue 4, no ${I}ue here; colour ${H}1a2b3c, &${H}45;, "
     "a fragment page.md/${H}12, $${H}1 arguments, ${I}ues: 3 of them.\n")
file(WRITE "${OUT}/notes.md" "# Notes\n\nMade in ${S}ion 12 and\n${S_UPPER}IONS-3, see ${I}ue ${H}21 (${I}ues ${H}20).\n")
file(WRITE "${OUT}/src/code.cpp" "// Renderer (${H}4): the frame.\r\n// ${I}ue-22 fixed\r\nint x = 0;\n")
file(WRITE "${OUT}/src/start.cmake" "${H}7: the first line\n")
file(WRITE "${OUT}/build/x/generated.txt" "${S}ion 5\n")  # a build tree: never scanned
file(WRITE "${OUT}/ignored/scratch.txt" "${S}ion 6\n")    # ignored by git: scanned only without git
file(WRITE "${OUT}/.gitignore" "/build/\n/ignored/\n")

# Binary files, written through printf: a safetensors file (u64 header length, the JSON header, data bytes holding
# a word that is not metadata) and a file with a NUL byte among its first bytes.
set(header "{\"__metadata__\":{\"note\":\"${I}ue 20's young smoke\"}}")
string(LENGTH "${header}" length)  # under 256: one byte, then seven zero bytes
math(EXPR length "${length}" OUTPUT_FORMAT HEXADECIMAL)
string(REPLACE "0x" "\\x" length "${length}")
execute_process(COMMAND printf "${length}\\000\\000\\000\\000\\000\\000\\000" OUTPUT_FILE "${OUT}/part_length"
                COMMAND_ERROR_IS_FATAL ANY)
file(WRITE "${OUT}/part_header" "${header}")
execute_process(COMMAND printf "\\000${S}ion 9" OUTPUT_FILE "${OUT}/part_data" COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND ${CMAKE_COMMAND} -E cat "${OUT}/part_length" "${OUT}/part_header" "${OUT}/part_data"
                OUTPUT_FILE "${OUT}/weights.safetensors" COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND printf "GIF89a\\000\\001 ${S}ion 7" OUTPUT_FILE "${OUT}/blob.bin" COMMAND_ERROR_IS_FATAL ANY)
file(REMOVE "${OUT}/part_length" "${OUT}/part_header" "${OUT}/part_data")

set(expected
    "notes.md:3: ${S}ion 12"
    "notes.md:4: ${S_UPPER}IONS-3"
    "notes.md:4: ${I}ue ${H}21"
    "notes.md:4: ${I}ues ${H}20"
    "src/code.cpp:1: ${H}4"
    "src/code.cpp:2: ${I}ue-22"
    "src/start.cmake:1: ${H}7"
    "weights.safetensors (header):1: ${I}ue 20")

function(run_check label expect_failure)
  execute_process(COMMAND ${CMAKE_COMMAND} -DROOT=${OUT} -P ${CHECK} RESULT_VARIABLE code OUTPUT_VARIABLE out
                  ERROR_VARIABLE err)
  set(all "${out}${err}")
  message(STATUS "${label}: exit ${code}\n${all}")
  if(expect_failure AND code EQUAL 0)
    message(FATAL_ERROR "${label}: the check passed on planted words")
  elseif(NOT expect_failure AND NOT code EQUAL 0)
    message(FATAL_ERROR "${label}: the check failed on a clean tree")
  endif()
  set(found "")
  string(REGEX MATCHALL "[^\n]+:[0-9]+: [^\n]+" found "${all}")
  set(found "${found}" PARENT_SCOPE)
  set(all "${all}" PARENT_SCOPE)
endfunction()

function(expect_found label)
  set(want ${expected} ${ARGN})
  foreach(entry IN LISTS want)
    if(NOT entry IN_LIST found)
      message(FATAL_ERROR "${label}: '${entry}' was not reported")
    endif()
  endforeach()
  foreach(entry IN LISTS found)
    if(NOT entry IN_LIST want)
      message(FATAL_ERROR "${label}: '${entry}' was reported, and is not planted")
    endif()
  endforeach()
endfunction()

# Plain files: everything but the build tree, the ignored folder included.
run_check("without git" TRUE)
expect_found("without git" "ignored/scratch.txt:1: ${S}ion 6")

# A git work tree: what git would add, not what it ignores.
find_program(GIT git)
if(GIT)
  execute_process(COMMAND ${GIT} init -q "${OUT}" COMMAND_ERROR_IS_FATAL ANY)
  run_check("git work tree" TRUE)
  expect_found("git work tree")
  file(REMOVE_RECURSE "${OUT}/.git")
endif()

# The words gone, it passes.
file(REMOVE "${OUT}/notes.md" "${OUT}/src/code.cpp" "${OUT}/src/start.cmake" "${OUT}/weights.safetensors"
     "${OUT}/ignored/scratch.txt")
run_check("clean tree" FALSE)
