# The repository describes the product, not the work that made it: no file names a work period or a tracker
# entry ("session" or "issue" with a number, or a bare number sign with digits), in code, comments, configs,
# docs or the metadata of the shipped weights. Dated studies are dated by the calendar (docs/research/).
# Fails listing path:line and the words for each match. Usage:
#   cmake -DROOT=<source tree> -P no_process_words.cmake
# Scans the files git tracks or would add (not the ignored ones: build trees, out/, data/); without git, or when
# ROOT is not the top of a git work tree, every file under ROOT but its build trees, out/, data/ and .git/.
# Text files are read whole; a binary file (a NUL byte in its first 8000, as git judges) is skipped, except a
# .safetensors file, whose JSON header (the metadata) is read.
cmake_minimum_required(VERSION 3.25)
if(NOT ROOT)
  message(FATAL_ERROR "usage: cmake -DROOT=<source tree> -P no_process_words.cmake")
endif()
file(REAL_PATH "${ROOT}" root)

# Matched on the lower-cased text, so case-insensitively. The first pattern: "session N", "session-N",
# "sessions N", "issue N", "issue #N", "issues #N", "issue-N" (N digits). The second: a tracker number alone,
# "(#N)", where the first has not matched already; not an HTML entity, a URL fragment, a shell "$#" or a hex
# colour.
set(patterns
    "(^|[^a-z])(sessions?|issues?)[-_ ]?#?[0-9]+"
    "(^|[^&a-z0-9_/$#])#[0-9]+([^a-z0-9_]|$)")

# The files to scan, relative to root.
set(files "")
set(listed FALSE)
find_program(GIT git)
if(GIT)
  execute_process(COMMAND "${GIT}" -C "${root}" rev-parse --show-toplevel
                  RESULT_VARIABLE code OUTPUT_VARIABLE top ERROR_QUIET OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(code EQUAL 0 AND top)
    file(REAL_PATH "${top}" top)
  endif()
  if(code EQUAL 0 AND top STREQUAL root)
    execute_process(COMMAND "${GIT}" -C "${root}" -c core.quotepath=off ls-files --cached --others --exclude-standard
                    RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT code EQUAL 0)
      message(FATAL_ERROR "git ls-files failed in ${root}:\n${err}")
    endif()
    string(REPLACE "\n" ";" files "${out}")
    set(listed TRUE)
  endif()
endif()
if(NOT listed)
  file(GLOB entries RELATIVE "${root}" "${root}/*" "${root}/.*")
  foreach(entry IN LISTS entries)
    if(entry MATCHES "^(\\.git|\\.cache|build.*|out|data|__pycache__)$")
      continue()
    elseif(IS_DIRECTORY "${root}/${entry}")
      file(GLOB_RECURSE inside RELATIVE "${root}" "${root}/${entry}/*")
      list(APPEND files ${inside})
    else()
      list(APPEND files "${entry}")
    endif()
  endforeach()
endif()
list(REMOVE_DUPLICATES files)
list(SORT files)

# Appends "path:line: words" to `found` for every match of the patterns in `text`.
function(scan_text path text)
  string(TOLOWER "${text}" lower)
  set(original "${text}")  # the words are reported as written
  foreach(pattern IN LISTS patterns)
    set(rest "${lower}")
    set(line 1)
    while(TRUE)
      string(REGEX MATCH "${pattern}" match "${rest}")
      if(match STREQUAL "")
        break()
      endif()
      # Where the leftmost match starts: the text before it is what a replacement from it to the end leaves.
      string(REGEX REPLACE "${pattern}.*$" "" before "${rest}")
      string(LENGTH "${before}" start)
      string(LENGTH "${match}" length)
      string(REGEX MATCHALL "\n" newlines "${before}")
      list(LENGTH newlines lines)
      math(EXPR line "${line} + ${lines}")
      # The match may begin with the character before the words: a newline there puts them on the next line.
      string(SUBSTRING "${original}" ${start} ${length} words)
      set(at ${line})
      if(NOT words MATCHES "^[A-Za-z#]")
        string(SUBSTRING "${words}" 0 1 lead)
        if(lead STREQUAL "\n")
          math(EXPR at "${line} + 1")
        endif()
        string(SUBSTRING "${words}" 1 -1 words)
      endif()
      if(NOT words MATCHES "[0-9]$")
        string(REGEX REPLACE ".$" "" words "${words}")
      endif()
      list(APPEND found "${path}:${at}: ${words}")
      string(REGEX MATCHALL "\n" newlines "${match}")
      list(LENGTH newlines lines)
      math(EXPR line "${line} + ${lines}")
      math(EXPR next "${start} + ${length}")
      string(SUBSTRING "${rest}" ${next} -1 rest)
      string(SUBSTRING "${original}" ${next} -1 original)
    endwhile()
    # What this pattern matched is not matched again by the next ("issue #N" is not also "#N"); the character
    # before the words stays, so the lines do not move.
    string(REGEX REPLACE "${pattern}" "\\1~" lower "${lower}")
    set(original "${lower}")
  endforeach()
  set(found "${found}" PARENT_SCOPE)
endfunction()

set(found "")
set(scanned 0)
set(skipped 0)
foreach(path IN LISTS files)
  set(file "${root}/${path}")
  if(path STREQUAL "" OR IS_DIRECTORY "${file}" OR NOT EXISTS "${file}")
    continue()  # a file deleted but not yet committed, or a submodule
  endif()
  file(SIZE "${file}" size)
  if(path MATCHES "\\.safetensors$")
    # u64 little-endian header length, then the JSON header.
    if(size LESS 8)
      continue()
    endif()
    file(READ "${file}" head LIMIT 8 HEX)
    string(REGEX REPLACE "(..)(..)(..)(..)(..)(..)(..)(..)" "\\8\\7\\6\\5\\4\\3\\2\\1" head "${head}")
    string(REGEX REPLACE "^0+" "" head "${head}")
    if(head STREQUAL "" OR NOT head MATCHES "^[0-9a-f]+$")
      continue()
    endif()
    string(LENGTH "${head}" digits)
    if(digits GREATER 12)
      set(header ${size})  # beyond any file here: read what there is
    else()
      math(EXPR header "0x${head}")
    endif()
    math(EXPR available "${size} - 8")
    if(header GREATER available)
      set(header ${available})
    endif()
    file(READ "${file}" text OFFSET 8 LIMIT ${header})
    scan_text("${path} (header)" "${text}")
    math(EXPR scanned "${scanned} + 1")
    continue()
  endif()
  # Binary as git judges it: a NUL byte among the first 8000.
  file(READ "${file}" head LIMIT 8000 HEX)
  string(REGEX REPLACE "(..)" "\\1;" bytes "${head}")
  list(FIND bytes "00" nul)
  if(NOT nul EQUAL -1)
    math(EXPR skipped "${skipped} + 1")
    continue()
  endif()
  file(READ "${file}" text)
  scan_text("${path}" "${text}")
  math(EXPR scanned "${scanned} + 1")
endforeach()

list(LENGTH found count)
if(count GREATER 0)
  set(paths "")
  foreach(entry IN LISTS found)
    string(REGEX REPLACE ":[0-9]+: .*$" "" entry "${entry}")
    list(APPEND paths "${entry}")
  endforeach()
  list(REMOVE_DUPLICATES paths)
  list(LENGTH paths in)
  list(SORT found COMPARE NATURAL)
  list(JOIN found "\n" lines)
  message(NOTICE "${lines}")
  message(FATAL_ERROR "${count} work-period or tracker words in ${in} of ${scanned} files under ${root}: say what "
                      "the code or page is and why, not which session or issue made it.")
endif()
message(STATUS "no work-period or tracker words in ${scanned} files under ${root} (binary files skipped: ${skipped})")
