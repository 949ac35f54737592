# Builds the documentation: run as a script (cmake -P) by the `docs` target and by the
# `docs.no_warnings` test.
#
#   -D LITERATE=<literate executable>  -D DOXYGEN=<doxygen>  -D DOXYFILE=<configured Doxyfile>
#   -D SOURCE_DIR=<source tree>  -D FIGURES=<figures directory>  -D WORK=<output directory>
#   -D MATHJAX=<MathJax 2 directory, or empty to skip copying it>
#   -D STRICT=ON|OFF   ON: any warning (converter or Doxygen) fails; OFF: warnings are shown
#
# Steps: (1) the chapter programs become pages in WORK/pages, (2) Doxygen writes WORK/html with
# a per-run configuration that includes DOXYFILE, (3) the parts of MathJax that the pages use
# are copied to WORK/html/mathjax, so the site works offline and can be moved anywhere.
cmake_minimum_required(VERSION 3.25)
foreach(var LITERATE DOXYGEN DOXYFILE SOURCE_DIR FIGURES WORK)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "build_docs.cmake: -D ${var}=... is required")
  endif()
endforeach()

# ---- 1. The chapter pages and the main page --------------------------------------------------
# Doxygen never deletes a page, so start from an empty site: nothing stale survives.
file(REMOVE_RECURSE "${WORK}/html")
set(strict_flag)
if(STRICT)
  set(strict_flag --strict)
endif()
execute_process(
  COMMAND "${LITERATE}" --chapters "${SOURCE_DIR}/chapters" --figures "${FIGURES}"
          --mainpage "${SOURCE_DIR}/docs/mainpage.md" --work "${WORK}" ${strict_flag}
  RESULT_VARIABLE status)
# 2: warnings under --strict (the pages exist: let Doxygen report its warnings too); else error.
set(converter_warned OFF)
if(status EQUAL 2)
  set(converter_warned ON)
elseif(NOT status EQUAL 0)
  message(FATAL_ERROR "docs: the chapter pages could not be made (see the messages above)")
endif()

# ---- 1b. The atlas page ----------------------------------------------------------------------
# The atlas program (atlas/) writes its page, stiff_cases.md, with its figures into
# FIGURES/atlas; until it has run, the page says so.
set(atlas "${FIGURES}/atlas")
if(EXISTS "${atlas}/stiff_cases.md")
  file(COPY "${atlas}/stiff_cases.md" DESTINATION "${WORK}/pages")
  file(GLOB atlas_figures "${atlas}/*.png")
  if(atlas_figures)
    file(COPY ${atlas_figures} DESTINATION "${WORK}/images")
  endif()
else()
  file(WRITE "${WORK}/pages/stiff_cases.md"
       "# Stiff and extreme cases {#stiff_cases}\n\n<em>The atlas has not been run yet: "
       "`scripts/figures.sh` runs it and puts its table and figures here.</em>\n")
endif()

# ---- 2. Doxygen ------------------------------------------------------------------------------
set(log "${WORK}/warnings.log")
file(REMOVE "${log}")
file(WRITE "${WORK}/Doxyfile.run"
  "@INCLUDE = \"${DOXYFILE}\"\n"
  "OUTPUT_DIRECTORY = \"${WORK}\"\n"
  "INPUT += \"${WORK}/pages\"\n"
  "FILE_PATTERNS += *.dox\n"
  # The pages at the root of the file tree: no empty "pages" folder beside app, plot and sph.
  "STRIP_FROM_PATH += \"${WORK}/pages\"\n"
  "IMAGE_PATH = \"${WORK}/images\"\n"
  "WARN_LOGFILE = \"${log}\"\n")
execute_process(COMMAND "${DOXYGEN}" "${WORK}/Doxyfile.run"
                WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE status)
set(warnings "")
if(EXISTS "${log}")
  file(READ "${log}" warnings)
  string(STRIP "${warnings}" warnings)
endif()
if(NOT warnings STREQUAL "")
  # Point the warnings about chapter pages at the chapters' own files and lines.
  execute_process(COMMAND "${LITERATE}" --work "${WORK}" --explain "${log}"
                  OUTPUT_VARIABLE explained RESULT_VARIABLE explain_status)
  if(explain_status EQUAL 0)
    string(STRIP "${explained}" warnings)
  endif()
endif()
if(NOT status EQUAL 0)
  message(FATAL_ERROR "docs: doxygen failed (exit status ${status})\n${warnings}")
endif()
if(NOT warnings STREQUAL "")
  string(REGEX MATCHALL "\n" lines "\n${warnings}")
  list(LENGTH lines count)
  if(STRICT)
    message(FATAL_ERROR "docs: Doxygen warned (${count} lines in ${log}):\n${warnings}")
  endif()
  message(WARNING "docs: Doxygen warned (${count} lines in ${log}):\n${warnings}")
endif()
if(converter_warned)
  message(FATAL_ERROR "docs: the chapter pages have warnings (see the literate: lines above)")
endif()

# ---- 2b. Markup that Doxygen left raw: a bold that starts with "(" or holds a formula or code
# shows its asterisks, and code in a heading shows its tags.  The code listings (one
# <div class="line"> per line) may hold "**" of their own, so they are left out.
if(STRICT)
  file(GLOB pages "${WORK}/html/ch[0-9][0-9].html" "${WORK}/html/papers.html"
                  "${WORK}/html/design.html" "${WORK}/html/index.html"
                  "${WORK}/html/stiff_cases.html")
  set(raw "")
  foreach(page IN LISTS pages)
    file(STRINGS "${page}" lines)
    foreach(line IN LISTS lines)
      if(line MATCHES "<div class=\"line\">" OR line MATCHES "class=\"fragment\"")
        continue()
      endif()
      if(line MATCHES "\\*\\*[^ ]" OR line MATCHES "&lt;tt&gt;")
        get_filename_component(name "${page}" NAME)
        string(SUBSTRING "${line}" 0 160 shown)
        string(APPEND raw "  ${name}: ${shown}\n")
      endif()
    endforeach()
  endforeach()
  if(NOT raw STREQUAL "")
    message(FATAL_ERROR "docs: raw markup in the pages (use <b>...</b> for a bold that starts "
                        "with a parenthesis or holds a formula or code):\n${raw}")
  endif()
endif()

# ---- 2b'. Every class and struct has a description (with EXTRACT_ALL a class without one still
# gets a page, an empty one, and no warning): a second Doxygen run without EXTRACT_ALL, without
# output and without the generated "Used in the chapters" lines (which would count as a
# description) lists the undocumented compounds.
if(STRICT)
  file(WRITE "${WORK}/Doxyfile.compounds"
    "@INCLUDE = \"${WORK}/Doxyfile.run\"\n"
    "EXTRACT_ALL = NO\n"
    "EXCLUDE_PATTERNS += */used_in.dox\n"
    "GENERATE_HTML = NO\n"
    "OUTPUT_DIRECTORY = \"${WORK}/compounds\"\n"
    "WARN_LOGFILE = \"${WORK}/compounds.log\"\n")
  file(REMOVE "${WORK}/compounds.log")
  execute_process(COMMAND "${DOXYGEN}" "${WORK}/Doxyfile.compounds"
                  WORKING_DIRECTORY "${WORK}" OUTPUT_QUIET ERROR_QUIET)
  file(STRINGS "${WORK}/compounds.log" undocumented REGEX "Compound .* is not documented")
  if(undocumented)
    list(JOIN undocumented "\n" shown)
    message(FATAL_ERROR "docs: classes without a description (their pages would be empty):\n"
                        "${shown}")
  endif()
endif()

# ---- 2c. Every figure of a chapter page links to its full-size file: the page shows it at the
# page's width, a click shows every pixel.
file(GLOB chapter_pages "${WORK}/html/ch[0-9][0-9].html")
foreach(page IN LISTS chapter_pages)
  file(READ "${page}" html)
  string(REGEX REPLACE "<div class=\"image\">\n<img src=\"([^\"]+)\" alt=\"\"/>"
         "<div class=\"image\">\n<a href=\"\\1\" title=\"Full size\"><img src=\"\\1\" alt=\"\"/></a>"
         linked "${html}")
  if(NOT linked STREQUAL html)
    file(WRITE "${page}" "${linked}")
  endif()
endforeach()

# ---- 2d. Links that lead nowhere: in the course's own pages, every link to an anchor of the
# same page or to a local page (and its anchor) must find it.
if(STRICT)
  file(GLOB pages "${WORK}/html/ch[0-9][0-9].html" "${WORK}/html/papers.html"
                  "${WORK}/html/design.html" "${WORK}/html/index.html"
                  "${WORK}/html/chapters.html")
  set(broken "")
  foreach(page IN LISTS pages)
    get_filename_component(name "${page}" NAME)
    file(READ "${page}" html)
    string(REGEX MATCHALL "href=\"[^\":]*\"" links "${html}")
    list(REMOVE_DUPLICATES links)
    foreach(link IN LISTS links)
      string(REGEX REPLACE "^href=\"([^\"]*)\"$" "\\1" target "${link}")
      string(FIND "${target}" "#" hash)
      if(hash EQUAL -1)
        set(file_part "${target}")
        set(anchor "")
      else()
        string(SUBSTRING "${target}" 0 ${hash} file_part)
        string(SUBSTRING "${target}" ${hash} -1 anchor)
      endif()
      if(file_part STREQUAL "")
        set(target_html "${html}")
      elseif(EXISTS "${WORK}/html/${file_part}")
        if(anchor STREQUAL "")
          continue()
        endif()
        file(READ "${WORK}/html/${file_part}" target_html)
      else()
        string(APPEND broken "  ${name}: ${target} (no such file)\n")
        continue()
      endif()
      if(NOT anchor STREQUAL "")
        string(SUBSTRING "${anchor}" 1 -1 id)
        string(FIND "${target_html}" "id=\"${id}\"" at_id)
        string(FIND "${target_html}" "name=\"${id}\"" at_name)
        if(at_id EQUAL -1 AND at_name EQUAL -1)
          string(APPEND broken "  ${name}: ${target} (no such anchor)\n")
        endif()
      endif()
    endforeach()
  endforeach()
  if(NOT broken STREQUAL "")
    message(FATAL_ERROR "docs: links that lead nowhere:\n${broken}")
  endif()
endif()

# ---- 3. MathJax, offline: the core, TeX input, SVG output with the TeX fonts ----------------
if(MATHJAX)
  if(NOT EXISTS "${MATHJAX}/MathJax.js")
    message(WARNING "docs: MathJax not found in ${MATHJAX}: formulas will not render "
                    "(install libjs-mathjax)")
  else()
    set(to "${WORK}/html/mathjax")
    file(COPY "${MATHJAX}/MathJax.js" DESTINATION "${to}")
    file(COPY "${MATHJAX}/extensions" DESTINATION "${to}")
    file(COPY "${MATHJAX}/jax/element" "${MATHJAX}/jax/input" DESTINATION "${to}/jax"
         PATTERN "AsciiMath" EXCLUDE PATTERN "MathML" EXCLUDE)
    file(COPY "${MATHJAX}/jax/output/SVG/jax.js" "${MATHJAX}/jax/output/SVG/config.js"
              "${MATHJAX}/jax/output/SVG/autoload"
         DESTINATION "${to}/jax/output/SVG")
    file(COPY "${MATHJAX}/jax/output/SVG/fonts/TeX" DESTINATION "${to}/jax/output/SVG/fonts")
    file(COPY "${MATHJAX}/localization/en" DESTINATION "${to}/localization")
  endif()
  message(STATUS "docs: ${WORK}/html/index.html")
endif()
