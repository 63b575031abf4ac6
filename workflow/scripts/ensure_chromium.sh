#!/bin/sh
# `make chromium`: Debian's chromium, for the explorer's browser tests (tests/explore, within `make test`),
# `make report-check` and `make docs-check`. Idempotent: does nothing when a chromium is on the PATH.
# Installs it as root with apt-get; elsewhere prints one line saying what to run.
set -eu
found() { for b in chromium chromium-browser google-chrome; do command -v "$b" >/dev/null 2>&1 && return 0; done; return 1; }
if found; then exit 0; fi
if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
  echo "make chromium: installing Debian's chromium (the explorer's browser tests need it)"
  apt-get update -qq >/dev/null
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null
  found && exit 0
fi
echo "make chromium: the browser tests need Debian's chromium; run: sudo apt-get install chromium" >&2
exit 1
