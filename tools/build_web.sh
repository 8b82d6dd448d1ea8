#!/usr/bin/env bash
# Rebuilds the web page's WebAssembly module (rust/wasm) and the files the page loads it
# from, into python/planarkin/web/ (or into $1):
#   planarkin.wasm   the module (what `planarkin web` serves and the size is measured on)
#   wasm.js          the same bytes as base64, so the page also works from file://
#   scenes.js        the built-in scenes (python/planarkin/scene/builtin/*.json) as text
#
# Toolchain (Debian): apt-get install -y rustc-web cargo-web rust-web-src lld
# rustup's cargo comes first on PATH and has no wasm32 standard library, so Debian's
# rustc and cargo are named, and the standard library is built from its source.
set -euo pipefail
# Debian bookworm's rustc-web is 1.85, and some dependencies (wide, via nalgebra) use
# library functions stabilised in 1.87-1.89. RUSTC_BOOTSTRAP (already needed for
# -Zbuild-std) lets the compiler take them as the unstable features they were in 1.85;
# with a rustc >= 1.89 these attributes only warn. PK_WASM_FEATURES overrides the list.
# tools/wasm_rustc.sh adds them to every crate but the standard library.
export PK_WASM_FEATURES="${PK_WASM_FEATURES-float_next_up_down,integer_sign_cast,unbounded_shifts,unsigned_is_multiple_of}"
export PK_WASM_FEATURES_nalgebra="${PK_WASM_FEATURES_nalgebra-const_vec_string_slice}"
root="$(cd "$(dirname "$0")/.." && pwd)"
out="${1:-$root/python/planarkin/web}"
target="${CARGO_TARGET_DIR:-$root/target-wasm}"
cargo_bin="${PK_WASM_CARGO:-/usr/bin/cargo}"
rustc_bin="${PK_WASM_RUSTC:-/usr/bin/rustc}"
jobs="${PK_WASM_JOBS:-1}"
mkdir -p "$out"
cd "$root"
# paths in the module (panic locations) name neither this checkout nor the cargo home, so
# the same sources and toolchain give the same bytes anywhere
cargo_home="${CARGO_HOME:-$HOME/.cargo}"
export RUSTFLAGS="${RUSTFLAGS:-} --remap-path-prefix=$root=planarkin --remap-path-prefix=$cargo_home=cargo"
RUSTC_WRAPPER="$root/tools/wasm_rustc.sh" RUSTC="$rustc_bin" RUSTC_BOOTSTRAP=1 CARGO_TARGET_DIR="$target" \
  CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_LINKER=wasm-ld \
  CARGO_PROFILE_RELEASE_LTO=fat CARGO_PROFILE_RELEASE_OPT_LEVEL=3 CARGO_PROFILE_RELEASE_PANIC=abort \
  "$cargo_bin" build -j "$jobs" --release --target wasm32-unknown-unknown -p planarkin-wasm --ignore-rust-version \
  -Zbuild-std=std,panic_abort
cp "$target/wasm32-unknown-unknown/release/planarkin_wasm.wasm" "$out/planarkin.wasm"
python3 "$root/tools/web_assets.py" "$out"
ls -l "$out/planarkin.wasm" "$out/wasm.js" "$out/scenes.js"
