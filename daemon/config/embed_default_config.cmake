# Writes OUT: a C++ file embedding IN byte for byte (defaultConfigText()).
file(READ "${IN}" content)
string(FIND "${content}" ")xrdefcfg\"" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${IN} contains the raw-string delimiter")
endif()
file(WRITE "${OUT}.tmp"
  "// Generated from config/xregulator.toml by embed_default_config.cmake. Do not edit.\n"
  "#include \"config/config.h\"\n"
  "namespace xr {\n"
  "namespace { constexpr char kText[] = R\"xrdefcfg(${content})xrdefcfg\"; }\n"
  "std::string_view defaultConfigText() { return {kText, sizeof(kText) - 1}; }\n"
  "}  // namespace xr\n")
file(COPY_FILE "${OUT}.tmp" "${OUT}" ONLY_IF_DIFFERENT)
