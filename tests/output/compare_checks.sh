# Sourced by tests/output/test_compare*.sh (not a test itself): the check
# that `pcsim compare ARGS` refuses bad input as every command must.
# Needs PCSIM_BIN, a function fail, and $before: the folder's listing.

bad() {  # bad EXPECTED_TEXT ARGS...: exit 2, one line with the text, nothing left behind
  local expected=$1 status=0
  shift
  "$PCSIM_BIN" compare "$@" > bad.log 2>&1 || status=$?
  [ $status -eq 2 ] && [ "$(grep -c . bad.log)" -eq 1 ] && grep -q "^pcsim: error: .*$expected" bad.log ||
    { cat bad.log; fail "compare $* (exit $status)"; }
  rm bad.log
  [ "$(ls -A)" == "$before" ] || { ls -A; fail "compare $* left something behind"; }
}
