#!/usr/bin/env bash
# Rewrites the README's `punctual render` synopsis (the options under "## Command line") from
# `punctual render --help`, which the render option table and the variant tables generate: after
# adding an option or a variant, run this rather than editing the synopsis by hand.
# VariantHelp.ReadmeSynopsisIsTheRenderHelp fails while the two differ.
#   scripts/readme-synopsis.sh [PUNCTUAL]     (default build/punctual)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
binary="${1:-$root/build/punctual}"
[ -x "$binary" ] || { echo "readme-synopsis.sh: $binary: no such program (build first: scripts/build.sh)" >&2; exit 1; }
help="$("$binary" render --help)"
HELP="$help" python3 - "$root/README.md" <<'PY'
import os, sys, tempfile
path = sys.argv[1]
help_text = os.environ["HELP"] + "\n"
head = "punctual render [SCENE.gltf|SCENE.glb|--scene NAME] [options]\n"
options = help_text[help_text.index("options:\n") + len("options:\n"):]
readme = open(path, encoding="utf-8").read()
start = readme.find(head)
end = readme.find("punctual reference ", start)
if start < 0 or end < 0:
    sys.exit("readme-synopsis.sh: README.md: no `punctual render` synopsis followed by `punctual reference`")
updated = readme[:start + len(head)] + options + readme[end:]
if updated == readme:
    print("README.md: the synopsis is already the render help")
    sys.exit(0)
# All or nothing: a temporary beside it, renamed over it.
fd, temporary = tempfile.mkstemp(dir=os.path.dirname(path), prefix=".README.md.")
with os.fdopen(fd, "w", encoding="utf-8") as out:
    out.write(updated)
os.chmod(temporary, os.stat(path).st_mode & 0o777)
os.replace(temporary, path)
print("README.md: the synopsis rewritten from `punctual render --help`")
PY
