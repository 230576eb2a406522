#!/usr/bin/env bash
# Every doctest case name can be run by CTest: doctest_discover_tests splits a name at ';'
# into two tests, each of which then matches no case and passes having run nothing.
#   tests/test_case_names.sh TESTS_DIR
set -euo pipefail
bad=$(grep -nE 'TEST_CASE\("[^"]*;' "$1"/*.cpp || true)
if [ -n "$bad" ]; then
  echo "test case names with ';' (CTest would run none of them):" >&2
  echo "$bad" >&2
  exit 1
fi
echo "$(cat "$1"/*.cpp | grep -cE 'TEST_CASE\("') test case names, none with ';'"
