// The translation unit that builds the test files' precompiled header
// (tests/CMakeLists.txt, flange_test_pch): Catch2 and <flange/equations_of_motion.hpp>.
