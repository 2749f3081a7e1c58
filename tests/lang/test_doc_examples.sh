#!/bin/sh
# test_doc_examples.sh — the shell sessions of docs/tutorial.md run as the
# page shows them: each command's exit code, and every line shown of its
# output printed, in order (tests/lang/doc_examples.py says how a session is
# read).  A stale hash or message on the page fails here, not in a reader's
# terminal.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
exec /usr/bin/python3 tests/lang/doc_examples.py "$ROOT" docs/tutorial.md
