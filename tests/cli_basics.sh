#!/usr/bin/env bash
# The command's contract: --help lists the subcommands, --version answers, usage errors are one
# `tessera: error:` line plus a hint and exit 2.
set -u
tessera=$1
fail() { echo "FAIL: $*"; exit 1; }

out=$("$tessera" --help) || fail "--help exited $?"
grep -q "info" <<<"$out" || fail "--help does not list the subcommands: $out"

"$tessera" --version | grep -q "^tessera [0-9]" || fail "--version"

err=$("$tessera" --no-such-flag 2>&1 >/dev/null); code=$?
[ $code -eq 2 ] || fail "unknown flag exited $code, expected 2"
[ "$(grep -c '^tessera: error: ' <<<"$err")" -eq 1 ] || fail "expected one error line, got: $err"
grep -q '^hint: ' <<<"$err" || fail "no hint line: $err"

err=$("$tessera" 2>&1 >/dev/null); code=$?
[ $code -eq 2 ] || fail "no command exited $code, expected 2"
grep -q '^tessera: error: no command given' <<<"$err" || fail "no-command message: $err"

err=$("$tessera" info --bogus 2>&1 >/dev/null); code=$?
[ $code -eq 2 ] || fail "subcommand usage error exited $code"
grep -q "tessera info --help" <<<"$err" || fail "hint should name the subcommand: $err"

"$tessera" info >/dev/null || fail "info exited $?"
echo "cli_basics: ok"
