"""Test session set-up: FEM results are cached in a fresh temporary directory per session, so tests never
depend on results left on the machine, while tests within the session reuse each other's FEM solves."""
import os
import tempfile

os.environ["FEMCHECK_CACHE"] = tempfile.mkdtemp(prefix="femcheck-test-cache-")
