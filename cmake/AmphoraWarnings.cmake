# Warnings for amphora's own targets (dependencies are included as SYSTEM headers).
add_library(amphora_warnings INTERFACE)
target_compile_options(amphora_warnings INTERFACE
  $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor>)
