# Writes api/openapi.yaml into a C++ include holding one raw string literal (served at /openapi.yaml).
file(READ ${IN} text)
file(WRITE ${OUT}.tmp "R\"rupture_openapi(${text})rupture_openapi\"\n")
file(COPY_FILE ${OUT}.tmp ${OUT} ONLY_IF_DIFFERENT)
