#!/usr/bin/env bash
# npm run bench: speed and size figures, each printed against a baseline run beside it.
set -euo pipefail
cd "$(dirname "$0")/.."
npx tsx bench/run.ts
echo
bash scripts/build-avr.sh
