// The one object of xr_test_pch: the target exists to compile GoogleTest's
// headers once into a precompiled header that every test executable reuses
// (tests/CMakeLists.txt, docs/development.md "make test's time").
