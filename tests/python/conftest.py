"""The Python tests run from the source folder on an empty cache of their own (fields,
spectra, programs, tuning), so they measure from scratch and leave the user's alone."""
import os
import sys
import tempfile

os.environ["SNAPFIT_CACHE_DIR"] = tempfile.mkdtemp(prefix="snapfit-python-tests-")
sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "examples", "python"))
