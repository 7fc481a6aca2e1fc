# Sourced by tests/cli_*.sh (after they define $tessera and fail()):
# expect_error CODE ARGS... runs `tessera ARGS...` and fails the test unless it exits CODE
# with exactly one "tessera: error: " line on stderr; the stderr text is left in $err.
expect_error() {
    local code=$1 got
    shift
    err=$("$tessera" "$@" 2>&1 >/dev/null); got=$?
    [ $got -eq "$code" ] || fail "'$*' exited $got, expected $code: $err"
    [ "$(grep -c '^tessera: error: ' <<<"$err")" -eq 1 ] || fail "'$*': expected one error line: $err"
}
