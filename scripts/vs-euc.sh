#!/usr/bin/env bash
# Instructions per frame, rastty against euc, drawing the bunny at 200×120
# samples (docs/accuracy.md, "Against a peer"). Counted by callgrind: (instructions
# of 40 frames − of 10) / 30, leaving out loading. Needs valgrind.
#
#   scripts/vs-euc.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --example vs_euc -q
bin=target/release/examples/vs_euc
count() { valgrind --tool=callgrind --callgrind-out-file=/dev/null "$bin" "$@" 2>&1 | sed -n 's/.*Collected : //p'; }
for who in rastty euc; do
  a=$(count "$who" 10)
  b=$(count "$who" 40)
  echo "$who: $(( (b - a) / 30 )) instructions per frame"
done
