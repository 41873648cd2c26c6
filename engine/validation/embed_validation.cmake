# Writes every validation/<case>/case.json and every examples/*.json into a C++ include as
# {path, raw string} pairs ("validation/<case>/case.json", "examples/<name>.json"): the cases and
# the example specs they start from travel inside the binary, so a validation run on a server or a
# Slurm node needs no source tree.
file(GLOB cases ${SOURCE_DIR}/validation/*/case.json)
file(GLOB examples ${SOURCE_DIR}/examples/*.json)
set(files ${cases} ${examples})
list(SORT files)
set(content "// Generated from validation/ and examples/ by engine/validation/embed_validation.cmake. Do not edit.\n")
foreach(f ${files})
  file(RELATIVE_PATH rel ${SOURCE_DIR} ${f})
  file(READ ${f} text)
  string(APPEND content "{\"${rel}\", R\"rupture_case(${text})rupture_case\"},\n")
endforeach()
file(WRITE ${OUT}.tmp "${content}")
file(COPY_FILE ${OUT}.tmp ${OUT} ONLY_IF_DIFFERENT)
