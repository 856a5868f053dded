#!/usr/bin/env bash
# Rewrites docs/catalogue.md from the compiler's catalogue (after adding or changing an
# attribute, a setting or an effect). Reference.CatalogueIsCurrent fails until this is run.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --build build --target gbx-reference >/dev/null
./build/tools/gbx-reference > docs/catalogue.md
git --no-pager diff --stat -- docs/catalogue.md
