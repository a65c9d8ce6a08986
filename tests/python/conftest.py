"""What the Python tests share: the module from the build tree (PYTHONPATH, set by ctest), the shared
data folder, the command line for the numbers it prints, and small models."""
import os
import pathlib
import subprocess

import numpy as np
import pytest

import hairshadow as hs

SHARED = pathlib.Path(os.environ.get("HAIRSHADOW_SHARED_DIR", pathlib.Path(__file__).resolve().parents[3] / "shared"))
CLI = os.environ.get("HAIRSHADOW_CLI", "")
SINTEL = SHARED / "data" / "sintel" / "sintel_hair.16points.tfx"
RATBOY = SHARED / "data" / "ratboy" / "Ratboy_mohawk.tfx"
SMALL = "procedural:curly:strands=300:segments=12:seed=7"


def run_cli(*args):
    """The command's standard output (it must succeed)."""
    if not CLI:
        pytest.fail("HAIRSHADOW_CLI is not set (ctest sets it)")
    done = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, check=False)
    assert done.returncode == 0, done.stderr
    return done.stdout


@pytest.fixture(scope="session")
def small():
    return hs.procedural(SMALL)


@pytest.fixture(scope="session")
def sintel():
    if not SINTEL.exists():
        pytest.fail(f"the Sintel model is not at {SINTEL}: ../shared must lie beside the checkout")
    return hs.load(str(SINTEL))


def sample_points(model, count, seed=1):
    """Points of the model and points between them: in the hair, where shadows vary."""
    rng = np.random.default_rng(seed)
    p = model.points
    i = rng.integers(0, len(p), count)
    j = rng.integers(0, len(p), count)
    t = rng.random((count, 1), dtype=np.float32)
    return np.ascontiguousarray((p[i] * (1 - t) + p[j] * t).astype(np.float32))
