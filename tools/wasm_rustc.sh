#!/usr/bin/env bash
# RUSTC_WRAPPER for tools/build_web.sh: cargo calls it as `wasm_rustc.sh RUSTC ARGS...`.
# With Debian bookworm's rustc 1.85, library functions stabilised later (used by wide and
# nalgebra) are still unstable features: crates other than the standard library (built
# from source by -Zbuild-std) get -Zcrate-attr=feature($PK_WASM_FEATURES), and crate X
# also gets the features in $PK_WASM_FEATURES_X (for those that only a crate linking
# alloc knows: naming them elsewhere is an error).
rustc="$1"
shift
name=""
prev=""
for a in "$@"; do
  case "$a" in */rustlib/src/rust/library/*) exec "$rustc" "$@" ;; esac
  if [ "$prev" = "--crate-name" ]; then name="$a"; fi
  prev="$a"
done
extra_var="PK_WASM_FEATURES_$name"
features="${PK_WASM_FEATURES:-}"
extra="${!extra_var:-}"
if [ -n "$extra" ]; then features="${features:+$features,}$extra"; fi
if [ -n "$features" ] && [ "$name" != "build_script_build" ]; then
  exec "$rustc" "$@" "-Zcrate-attr=feature($features)"
fi
exec "$rustc" "$@"
