#!/bin/sh
# `make llvm`: Debian's libllvm19, which Mitsuba's llvm_* variants (the renderer, brdfs.render.mitsuba)
# load through DRJIT_LIBLLVM_PATH (LLVM 15 fails). Idempotent: does nothing when the library is there.
# Installs it as root with apt-get; elsewhere prints one line saying what to run.
set -eu
found() { for f in /usr/lib/*/libLLVM-19.so /usr/lib/llvm-19/lib/libLLVM.so; do [ -e "$f" ] && { echo "$f"; return 0; }; done; return 1; }
if lib=$(found); then exit 0; fi
if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
  echo "make llvm: installing Debian's libllvm19 (Mitsuba's llvm variants need it)"
  apt-get update -qq >/dev/null
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libllvm19 >/dev/null
  found >/dev/null && exit 0
fi
echo "make llvm: Mitsuba's llvm variants need Debian's libllvm19; run: sudo apt-get install libllvm19" >&2
exit 1
