# Sourced by the CLI test scripts. expect_refused EXPECT COMMAND...: the command fails within 60 s (a blocked
# read fails the check) with exactly one stderr line matching EXPECT (grep -E); otherwise the failure is printed
# and `status` set to 1.
status=0
refused_err=$(mktemp)
trap 'rm -f "$refused_err"' EXIT
expect_refused() {
  local expect=$1; shift
  timeout 60 "$@" > /dev/null 2> "$refused_err"; local code=$?
  if [ $code -eq 0 ] || [ "$(wc -l < "$refused_err")" -ne 1 ] || ! grep -Eq -- "$expect" "$refused_err"; then
    echo "FAILED: $*: expected one line matching '$expect' and a failure, got exit $code and:"
    cat "$refused_err"
    status=1
  else
    echo "ok: exit $code: $(cat "$refused_err")"
  fi
}
