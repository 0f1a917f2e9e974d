#!/usr/bin/env bash
# Regenerates every chart, CSV and summary of docs/study.md:
#   docs/study/regenerate.sh
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
cd "$root"
cargo build --release -p aster-cli
for spec in comm/study-hertz.toml comm/study-zzzz237.toml comm/study-friction.toml; do
    target/release/aster study "$spec" --out docs/study
done
